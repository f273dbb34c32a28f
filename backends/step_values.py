"""Which values of a converted program count motor steps (issue 24).

When the target counts in other steps than the source (`Writer.factor` != 1: an X150 program at
4000 steps/rev written for an MCode drive at `MS=100`, 20000 steps/rev), a value that counts steps
must be scaled and one that is a plain number must not. The backend sees a constant the frontend
marked in steps (`Const.unit is STEPS`) and a position it writes in a move; a variable is seen only
through what is assigned to it, so this module follows the assignments and gives each value a kind:

- `CONST`: constants in steps only (`D25000`): exact in either unit, so written scaled where the
  rest is in the drive's steps and as it is where the rest is in the source's;
- `READING`: a position reading (`P`, the drive's own counter, in its steps); next to plain numbers
  it can be read in the source's steps instead (`P/5+50000`);
- `STEPS`: in the drive's steps (a variable holding constants or readings, a sum of a reading and
  constants);
- `PLAIN`: numbers in the source's units (`VAR1=100`, or a variable also assigned such numbers):
  a distance held so is multiplied by the factor where it is moved to (`MR Z0*5`);
- `MIXED`: a sum of the drive's steps and plain numbers that no single writing makes right (X150
  `VAR8=VAR7+50000` where VAR7 holds a reading): refused at its line;
- `NEUTRAL`: nothing decides (0, an unassigned variable).

A variable's kind joins those of all its assignments (it keeps its value across routines); the
analysis runs over the whole module until nothing changes. A product of steps by a plain number
counts steps (`POS*2`); steps times steps is mixed.
"""
from __future__ import annotations

from mcc.compiler import ir

NEUTRAL, CONST, READING, STEPS, PLAIN, MIXED = "neutral", "const", "reading", "steps", "plain", "mixed"
STEP_READINGS = ("position", "encoder")
IN_STEPS = (CONST, READING, STEPS)  # values the drive's steps can hold
TARGET = {(CONST, READING): STEPS, (CONST, STEPS): STEPS, (READING, READING): STEPS, (READING, STEPS): STEPS,
          (CONST, PLAIN): PLAIN, (READING, PLAIN): PLAIN, (STEPS, PLAIN): MIXED}


def join(a: str, b: str) -> str:
    """Two values that meet: a sum, or two assignments to one variable."""
    if a == NEUTRAL or a == b:
        return b
    if b == NEUTRAL:
        return a
    if MIXED in (a, b):
        return MIXED
    return TARGET.get((a, b)) or TARGET.get((b, a)) or MIXED


def scale(a: str, b: str) -> str:
    """A product or quotient: steps times a plain number counts steps."""
    if MIXED in (a, b) or a in IN_STEPS and b in IN_STEPS:
        return MIXED  # steps times steps is no position either
    if a in IN_STEPS:
        return a
    if b in IN_STEPS:
        return b
    return join(a, b)


def step_readings(expr) -> list:
    """The position readings in `expr` (the drive's own counters)."""
    return [node for node in ir.walk_expr(expr) if isinstance(node, ir.Status) and node.meaning in STEP_READINGS]


class StepValues:
    def __init__(self, module: ir.Module):
        self.vars: dict[str, str] = {}
        assignments = [(op.target.name, op.value) for _, block in module.blocks() for op in block.ops
                       if isinstance(op, ir.Assign)]
        changed = True
        while changed:
            changed = False
            for name, value in assignments:
                new = join(self.vars.get(name, NEUTRAL), self.kind(value))
                if new != self.vars.get(name, NEUTRAL):
                    self.vars[name] = new
                    changed = True

    def holds_plain(self, name: str) -> bool:
        """Whether the variable holds numbers in the source's units (written without scaling)."""
        return self.vars.get(name, PLAIN) in (PLAIN, NEUTRAL)

    def kind(self, node) -> str:
        if isinstance(node, ir.Const):
            if node.unit is ir.Unit.STEPS:
                return CONST if node.value != 0 else NEUTRAL
            return PLAIN if node.unit is ir.Unit.NONE and node.value != 0 else NEUTRAL
        if isinstance(node, ir.Var):
            kind = self.vars.get(node.name, PLAIN)
            return STEPS if kind in (CONST, READING) else kind  # held in the drive's steps
        if isinstance(node, ir.Status):
            return READING if node.meaning in STEP_READINGS else PLAIN
        if isinstance(node, ir.UnOp):
            return self.kind(node.operand)
        if isinstance(node, ir.BinOp):
            left, right = self.kind(node.left), self.kind(node.right)
            if node.op in ("+", "-"):
                return join(left, right)
            if node.op in ("*", "/"):
                return scale(left, right)
            return MIXED if left in IN_STEPS or right in IN_STEPS or MIXED in (left, right) else join(left, right)
        if isinstance(node, ir.Func):
            kinds = [self.kind(arg) for arg in node.args]
            if node.name == "abs" and len(kinds) == 1:
                return kinds[0]
            return MIXED if any(k in IN_STEPS or k == MIXED for k in kinds) else PLAIN
        if isinstance(node, ir.Compare):
            return join(self.kind(node.left), self.kind(node.right))
        return PLAIN
