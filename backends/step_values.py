"""Which values of a converted program count motor steps (issue 24).

When the target counts in other steps than the source (`Writer.factor` != 1: an X150 program at
4000 steps/rev written for an MCode drive at `MS=100`, 20000 steps/rev), a value that counts steps
must be scaled and one that is a plain number must not. The backend scales what it can see: a
constant the frontend marked in steps (`Const.unit is STEPS`) and a position it writes in a move.
A variable is only seen through what is assigned to it, so this module follows the assignments:

- `STEPS`: the value counts the target's steps as the output computes it: a constant in steps
  (scaled when written), a position reading (`P`, the drive's own counter), a variable holding one;
- `PLAIN`: a number the output writes as the source did (`VAR1=100`): used as a distance it is
  multiplied by the factor where it is moved to;
- `MIXED`: a sum of the two (X150 `VAR8=POS+50000`: the reading counts target steps, the 50000
  source steps): no single factor makes it right, and the backend refuses it at its line;
- `NEUTRAL`: nothing decides (0, an unassigned variable).

A product or quotient of steps by a plain number counts steps (`POS*2`); a sum or difference of
steps and a plain number is mixed. The analysis runs over the whole module (a variable keeps its
value across routines) until nothing changes.
"""
from __future__ import annotations

from mcc.compiler import ir

NEUTRAL, STEPS, PLAIN, MIXED = "neutral", "steps", "plain", "mixed"
STEP_READINGS = ("position", "encoder")


def join(a: str, b: str) -> str:
    """Two values that meet (a sum, two assignments to one variable)."""
    if a == NEUTRAL:
        return b
    if b == NEUTRAL or a == b:
        return a
    return MIXED


def scale(a: str, b: str) -> str:
    """A product or quotient: steps times a plain number counts steps."""
    if MIXED in (a, b) or a == b == STEPS:
        return MIXED  # steps times steps is no position either
    if STEPS in (a, b):
        return STEPS
    return join(a, b)


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

    def kind(self, node) -> str:
        if isinstance(node, ir.Const):
            if node.unit is ir.Unit.STEPS:
                return STEPS if node.value != 0 else NEUTRAL
            return PLAIN if node.unit is ir.Unit.NONE and node.value != 0 else NEUTRAL
        if isinstance(node, ir.Var):
            return self.vars.get(node.name, PLAIN)
        if isinstance(node, ir.Status):
            return STEPS if node.meaning in STEP_READINGS else PLAIN
        if isinstance(node, ir.UnOp):
            return self.kind(node.operand)
        if isinstance(node, ir.BinOp):
            left, right = self.kind(node.left), self.kind(node.right)
            if node.op in ("+", "-"):
                return join(left, right)
            if node.op in ("*", "/"):
                return scale(left, right)
            return MIXED if STEPS in (left, right) or MIXED in (left, right) else join(left, right)
        if isinstance(node, ir.Func):
            kinds = [self.kind(arg) for arg in node.args]
            if node.name == "abs" and len(kinds) == 1:
                return kinds[0]
            return MIXED if STEPS in kinds or MIXED in kinds else PLAIN
        if isinstance(node, ir.Compare):
            return join(self.kind(node.left), self.kind(node.right))
        return PLAIN
