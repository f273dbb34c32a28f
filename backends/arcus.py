"""The Arcus PMX-4EX-SA backend: IR → canonical standalone text + an assembly-level listing.

The work is done in five passes, each one a section of this module:

1. **Legalize** (`Legalizer`): a copy of each routine's CFG in which every operation is one Arcus
   statement can express. Expressions with several operators are split into one-operator
   assignments through the reserved temporaries (`[arcus] temporaries`, V60-V63 by default);
   register writes get a literal or one variable; conditions become one comparison of plain
   values (AND/OR/NOT are computed into a 0/1 flag with nested IFs); predicated calls become an
   IF around GOSUB; waits for an input become an empty WHILE. What Arcus cannot express at all is
   reported (G003 for operations of other dialects, A206 for computed values where Arcus needs a
   number) and left out.
2. **Move modes** (`modes.py`): where a move needs ABS or INC and the mode in force is not known
   to be it, an ABS/INC statement is inserted.
3. **Structure** (`Structurer`): Arcus has no GOTO, so IF/ELSEIF/ELSE/ENDIF and WHILE/ENDWHILE are
   rebuilt from the CFG with a dominator-tree method in the spirit of Ramsey's "Beyond Relooper"
   (ICFP 2022), restricted to what Arcus has (no `br`, no `break`): a branch becomes an IF whose
   arms end at the branch's unique merge child in the dominator tree (or at the enclosing follow),
   a loop (header = target of a back edge) becomes a WHILE when its only exit is the header's
   test. Loops left from one other place are first rewritten with a flag variable; anything else
   (irreducible graphs, loops with several exits) makes the routine a dispatch loop on a reserved
   variable, reported as a note (A202).
4. **Layout**: main program, END, then the SUB blocks, one canonical statement per line.
5. **Cost** (`cost_rows`): every statement is expanded into the assembly lines of the cost model
   of the target profile (`[arcus.cost]`, docs/arcus-cost-model.md), numbered from 0 like the
   controller's program counter and mapped back to the source; a program over the budget is an
   error (A201) that names the model, the budget, the count and the costliest source lines.

The backend reads only the IR, the profile and the Arcus catalog (for keyword spellings and what a
register may be used for); it never sees a syntax tree.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field
from typing import Union

from mcc.backends.listing import Listing
from mcc.compiler import ir
from mcc.compiler.arcus import catalog as arcus_catalog
from mcc.compiler.arcus import modes
from mcc.compiler.diagnostics import Diagnostics
from mcc.compiler.profiles import Profile
from mcc.compiler.span import Span

DIALECT = "arcus"
AXES = ("X", "Y", "Z", "U")
ARCUS_BINARY = {"+", "-", "*", "/", "%", "&", "|", "<<", ">>"}
NEGATE = {"=": "!=", "!=": "=", "<": ">=", ">=": "<", ">": "<=", "<=": ">"}
COMPARE_SPELLING = {"==": "=", "<>": "!="}
OPCODES = {"+": "ADD", "-": "SUB", "*": "MUL", "/": "DIV", "%": "MOD", "&": "AND", "|": "OR", "<<": "SHL",
           ">>": "SHR", "~": "NOT"}
HOME_KEYWORDS = {"switch": 0, "switch+index": 2, "index": 3}  # IR method -> ASCII homing mode (catalog home_mode)
MOTION_IR = {ir.MotionParam.MAX_SPEED: "max_speed", ir.MotionParam.INITIAL_SPEED: "initial_speed",
             ir.MotionParam.ACCEL: "accel"}
VARIABLE = re.compile(r"V([0-9]+)\Z", re.IGNORECASE)
EXIT = "%exit"
TAIL_COPY = 4  # operations of an END block the structurer may write twice rather than give up
PLACEHOLDER = re.compile(r"\{(\w+)\}")
TRUE = ir.Compare("=", ir.Const(1), ir.Const(1))
CONSTANT_TESTS = {"=": lambda a, b: a == b, "!=": lambda a, b: a != b, "<": lambda a, b: a < b,
                  "<=": lambda a, b: a <= b, ">": lambda a, b: a > b, ">=": lambda a, b: a >= b}


class Unstructurable(Exception):
    """The CFG has no IF/WHILE form (the reason is the message)."""


# =============================================================================================
# Configuration


@dataclass
class Config:
    budget: int
    model: str
    calibrated: bool
    warn_fraction: float
    costs: dict[str, int]
    default_cost: int
    temporaries: list[int]
    sub_range: tuple[int, int]
    allocate_from: int
    axes: tuple[str, ...]
    max_copied: int

    @classmethod
    def from_profile(cls, profile: Profile) -> "Config":
        cost = profile.get("arcus.cost", {}) or {}
        temps = [int(v) for v in (profile.get("arcus.temporaries") or [60, 61, 62, 63])]
        rng = profile.get("arcus.subroutines") or [0, 31]
        axes = tuple(a for a in profile.axes if a in AXES) or AXES
        return cls(budget=int(cost.get("budget", 3230)), model=str(cost.get("model", "h-estimate")),
                   calibrated=bool(cost.get("calibrated", False)),
                   warn_fraction=float(cost.get("warn_fraction", 0.9)),
                   costs={str(k).upper(): int(v) for k, v in (cost.get("statements") or {}).items()},
                   default_cost=int(cost.get("default", 1)), temporaries=temps,
                   sub_range=(int(rng[0]), int(rng[1])),
                   allocate_from=int(profile.get("arcus.allocate_subroutines_from", 1)), axes=axes,
                   max_copied=int(profile.get("arcus.loop_test_copy_max", 4)))

    def cost(self, key: str) -> int:
        return max(1, self.costs.get(key, self.default_cost))


# =============================================================================================
# Structured program (what the structurer builds and the layout writes)


@dataclass
class Simple:
    op: ir.Op


@dataclass
class IfNode:
    arms: list[tuple[ir.Compare, list]]  # IF and ELSEIF arms: (condition, body)
    orelse: list
    spans: list[Span | None]  # the IF and ELSEIF lines
    else_span: Span | None = None
    end_span: Span | None = None


@dataclass
class WhileNode:
    cond: ir.Compare
    body: list
    span: Span | None = None
    end_span: Span | None = None


@dataclass
class EndNode:
    span: Span | None = None


Node = Union[Simple, IfNode, WhileNode, EndNode]


def negate(cond: ir.Compare) -> ir.Compare:
    return ir.Compare(NEGATE[cond.op], cond.left, cond.right, cond.span)


# =============================================================================================
# 1. Legalization


class Temps:
    """The reserved temporaries: expression temporaries from the low end (short-lived, a stack),
    loop flags and the dispatch variable from the high end (long-lived)."""

    def __init__(self, pool: list[int]):
        self.pool = pool
        self.live = 0
        self.peak = 0
        self.high = 0  # variables taken from the top
        self.base = 0  # the first of them the current routine may use
        self.exhausted = False

    def alloc(self) -> ir.Var:
        if self.live >= len(self.pool):
            self.exhausted = True
            number = self.pool[-1] if self.pool else 63
        else:
            number = self.pool[self.live]
        self.live += 1
        self.peak = max(self.peak, self.live)
        return ir.Var(f"V{number}")

    def release(self, count: int = 1) -> None:
        self.live -= count

    def top(self, depth: int) -> ir.Var | None:
        """The current routine's long-lived variable number `depth`, from the top of the pool.

        Each routine gets its own (`start_routine`): a loop flag or dispatch variable must survive
        the GOSUBs made while it is live, so callers and callees never share one."""
        index = self.base + depth
        self.high = max(self.high, index + 1)
        if index >= len(self.pool):
            self.exhausted = True
            return None
        return ir.Var(f"V{self.pool[-1 - index]}")

    def start_routine(self) -> None:
        self.base = self.high

    @property
    def conflict(self) -> bool:
        return self.exhausted or self.peak + self.high > len(self.pool)


class Legalizer:
    """Rewrites one routine into a CFG of operations Arcus can write (pass 1)."""

    def __init__(self, emitter: "Emitter", routine: ir.Routine):
        self.em = emitter
        self.routine = routine
        self.out = ir.Routine(routine.name, routine.kind, span=routine.span, number=routine.number)
        self.labels = {block.label for block in routine.blocks}
        self.block: ir.Block | None = None
        self.split = 0

    def run(self) -> ir.Routine:
        for block in self.routine.blocks:
            self.block = ir.Block(block.label, span=block.span, named=block.named)
            self.out.blocks.append(self.block)
            for op in block.ops:
                self.op(op)
            self.terminator(block.terminator, block.span)
        return self.out

    # blocks -----------------------------------------------------------------------------------
    def new_block(self, span: Span | None) -> ir.Block:
        self.split += 1
        block = ir.Block(f"{self.routine.name}.{self.split}%", span=span)
        self.out.blocks.append(block)
        return block

    def emit(self, op: ir.Op) -> None:
        self.block.ops.append(op)

    # operations ---------------------------------------------------------------------------------
    def op(self, op: ir.Op) -> None:
        em = self.em
        temps = em.temps
        base = temps.live
        try:
            handler = getattr(self, "op_" + type(op).__name__.lower(), None)
            if handler is None:
                em.unsupported(op, f"{type(op).__name__} has no Arcus statement")
            else:
                handler(op)
        except _Skip:
            pass
        temps.live = base

    def op_assign(self, op: ir.Assign) -> None:
        target = self.em.var(op.target)
        self.assign(target, op.value, op.span)

    def op_setmotion(self, op: ir.SetMotion) -> None:
        name = MOTION_IR.get(op.param)
        if name is None:
            self.em.unsupported(op, f"the {op.param.value} setting has no Arcus statement (Arcus has HSPD, LSPD "
                                    "and ACC, a ramp time used for both acceleration and deceleration)")
            raise _Skip
        unit = op.value.unit if isinstance(op.value, ir.Const) else ir.Unit.NONE
        allowed = {ir.Unit.NONE, ir.Unit.MS} if op.param is ir.MotionParam.ACCEL else \
            {ir.Unit.NONE, ir.Unit.STEPS_PER_S}
        if unit not in allowed:
            arcus_unit = "a ramp time in ms" if op.param is ir.MotionParam.ACCEL else "in pulses/s"
            self.em.unsupported(op, f"the {op.param.value.replace('_', ' ')} is given in {unit.value}, and the "
                                    f"Arcus setting is {arcus_unit}: convert it in the source", code="G005")
            raise _Skip
        self.emit(ir.SetMotion(op.param, self.em.axis(op.axis, op, setting=True), self.value(op.value, op),
                               op.span))

    def op_move(self, op: ir.Move) -> None:
        targets = tuple((self.em.axis(axis, op), self.value(value, op, units=_POSITION_UNITS))
                        for axis, value in op.targets)
        if op.options:
            self.em.unsupported(op, "move options (MCode MA p2/p3) have no Arcus form; the move is written "
                                    "without them", severity_note=True)
        self.emit(ir.Move(op.mode, targets, span=op.span))

    def op_arc(self, op: ir.Arc) -> None:
        if tuple(op.axes) != ("X", "Y"):
            self.em.unsupported(op, "Arcus ARC/CIR move the X and Y axes only")
            raise _Skip
        center = tuple(self.literal(c, op, "ARC/CIR centre") for c in op.center)
        angle = None if op.angle is None else self.literal(op.angle, op, "ARC angle")
        self.emit(ir.Arc(op.axes, center, op.clockwise, angle, op.span))

    def op_slew(self, op: ir.Slew) -> None:
        if op.velocity is not None or op.direction not in (1, -1):
            self.em.unsupported(op, "Arcus jogs at the current HSPD in a direction (JOGX+); a slew at a "
                                    "given velocity has no statement")
            raise _Skip
        self.emit(ir.Slew(self.em.axis(op.axis, op), direction=op.direction, span=op.span))

    def op_home(self, op: ir.Home) -> None:
        if op.method not in HOME_KEYWORDS or op.direction not in (1, -1):
            self.em.unsupported(op, f"homing by '{op.method}' without a direction has no Arcus statement "
                                    "(HOME, ZHOME and ZOME home in + or - on the switch, switch+index or index)")
            raise _Skip
        self.emit(ir.Home(self.em.axis(op.axis, op), op.method, op.direction, span=op.span))

    def op_stop(self, op: ir.Stop) -> None:
        self.emit(ir.Stop(self.em.axis(op.axis, op, setting=True), op.ramp, op.span))

    def op_waitmotion(self, op: ir.WaitMotion) -> None:
        self.emit(ir.WaitMotion(self.em.axis(op.axis, op, setting=True), op.span))

    def op_delay(self, op: ir.Delay) -> None:
        duration = op.duration
        if isinstance(duration, ir.Const) and duration.unit is ir.Unit.S:
            duration = ir.Const(duration.value * 1000, ir.Unit.MS, duration.span)
        self.emit(ir.Delay(self.literal(duration, op, "DELAY"), op.span))

    def op_setoutput(self, op: ir.SetOutput) -> None:
        if op.index is not None and not 1 <= op.index <= 8:
            self.em.unsupported(op, f"output {op.index}: the PMX-4EX-SA has DO1-DO8")
            raise _Skip
        self.emit(ir.SetOutput(op.index, self.value(op.value, op), op.span))

    def op_setposition(self, op: ir.SetPosition) -> None:
        self.emit(ir.SetPosition(self.em.axis(op.axis, op), self.value(op.value, op, units=_POSITION_UNITS),
                                 op.span))

    def op_call(self, op: ir.Call) -> None:
        if self.em.sub_number(op.routine, op) is None:
            raise _Skip
        if op.cond is None:
            self.emit(ir.Call(op.routine, span=op.span))
            return
        call = self.new_block(op.span)
        after = self.new_block(op.span)
        self.test(op.cond, call.label, after.label, op.span)
        call.ops.append(ir.Call(op.routine, span=op.span))
        call.terminator = ir.Jump(after.label, op.span)
        self.block = after

    def op_waitinput(self, op: ir.WaitInput) -> None:
        loop = self.new_block(op.span)
        after = self.new_block(op.span)
        self.block.terminator = ir.Jump(loop.label, op.span)
        self.block = loop
        self.test(op.cond, after.label, loop.label, op.span)
        self.block = after

    def op_native(self, op: ir.Native) -> None:
        if op.dialect != DIALECT:
            self.em.unsupported(op, f"{op.dialect} {op.mnemonic or 'statement'} has no Arcus equivalent")
            raise _Skip
        keyword = self.em.keyword_of(op.mnemonic)
        args = op.args
        if args:
            literal = keyword is not None and keyword.literal_only
            args = tuple(self.literal(a, op, op.mnemonic) if literal else self.value(a, op) for a in args)
        self.emit(ir.Native(op.dialect, op.mnemonic.upper(), args, op.form, op.axis, op.span))

    # values -------------------------------------------------------------------------------------
    def assign(self, target: ir.Var, value: ir.Expr, span: Span | None) -> None:
        """target = value as one-operator assignments (L2675-L2677)."""
        em = self.em
        if em.is_atom(value, readable=True):
            self.emit(ir.Assign(target, em.atom(value), span))
            return
        if isinstance(value, ir.UnOp) and value.op in ("~", "!"):
            operand = self.operand(value.operand, span)
            self.emit(ir.Assign(target, ir.UnOp("~", operand, value.span), span))
            return
        if isinstance(value, ir.UnOp) and value.op == "-":
            value = ir.BinOp("-", ir.Const(0), value.operand, value.span)
        if isinstance(value, ir.BinOp) and value.op in ARCUS_BINARY:
            left = self.operand(value.left, span)
            right = self.operand(value.right, span)
            self.emit(ir.Assign(target, ir.BinOp(value.op, left, right, value.span), span))
            return
        em.unsupported_expr(value, span)
        raise _Skip

    def materialize(self, value: ir.Expr, span: Span | None) -> ir.Var:
        temp = self.em.temps.alloc()
        self.assign(temp, value, span)
        return temp

    def operand(self, value: ir.Expr, span: Span | None) -> ir.Expr:
        """An operand of a one-operator assignment: a literal, a variable or an [Argument] register."""
        if self.em.is_atom(value, operation=True):
            return self.em.atom(value)
        return self.materialize(value, span)

    def value(self, value: ir.Expr, op: ir.Op, units: frozenset | None = None) -> ir.Expr:
        """A register's written value: a literal or one variable (L1797)."""
        if isinstance(value, ir.Const):
            if units is not None and value.unit not in units:
                self.em.unsupported(op, f"a value in {value.unit.value} cannot be written for Arcus, which counts "
                                        "pulses", code="G005")
                raise _Skip
            return self.em.atom(value)
        if isinstance(value, ir.Var):
            return self.em.var(value)
        return self.materialize(value, getattr(op, "span", None))

    def literal(self, value: ir.Expr, op: ir.Op, what: str) -> ir.Const:
        if isinstance(value, ir.Const) and float(value.value).is_integer():
            return ir.Const(int(value.value), value.unit, value.span)
        self.em.diags.add("A206", self.em.span_of(op),
                          f"{what} takes a number written out on the PMX-4EX-SA; this program computes it at run "
                          "time: use a constant")
        raise _Skip

    # conditions and terminators --------------------------------------------------------------------
    def target(self, label: str, span: Span | None) -> str:
        """A jump target inside this routine; a jump into another routine (other dialects) becomes
        a block of its own: into the main program from the setup lines, a fall-through; into a
        subroutine's entry, GOSUB then END (a transfer without return); anywhere else, reported."""
        if label in self.labels:
            return label
        em = self.em
        routine = em.entries.get(label)
        block = self.new_block(span)
        holder = type("Holder", (), {"span": span})()
        if routine is not None and routine.kind is ir.RoutineKind.MAIN and \
                self.routine.kind is ir.RoutineKind.IMMEDIATE:
            block.terminator = ir.FallOff(span)  # the setup lines are written before the main program
        elif routine is not None and routine.name in em.sub_numbers:
            block.ops.append(ir.Call(routine.name, span=span))
            block.terminator = ir.End(span)
            em.unsupported(holder, f"the jump into {routine.name} is written as GOSUB "
                                   f"{em.sub_numbers[routine.name]} then END (Arcus has no GOTO)", code="G005")
        else:
            block.terminator = ir.End(span)
            em.unsupported(holder, f"a jump to {label} inside another routine has no Arcus form (no GOTO)")
        return block.label

    def terminator(self, term: ir.Terminator | None, span: Span | None) -> None:
        block = self.block
        if isinstance(term, ir.Jump):
            block.terminator = ir.Jump(self.target(term.target, term.span), term.span)
        elif isinstance(term, ir.Branch):
            base = self.em.temps.live
            then, otherwise = self.target(term.then, term.span), self.target(term.otherwise, term.span)
            try:
                self.test(term.cond, then, otherwise, term.span)
            except _Skip:  # reported: the condition has no Arcus form
                self.block.terminator = ir.End(term.span)
            self.em.temps.live = base
        elif isinstance(term, ir.GotoRoutine):
            if self.em.sub_number(term.routine, None, span) is not None:
                self.emit(ir.Call(term.routine, span=term.span))
            self.block.terminator = ir.End(term.span)
        elif isinstance(term, (ir.Return, ir.FallOff)) or term is None:
            # Falling off the main program is END (spec 5.1): written as END, so that a program and
            # its compiled text structure alike. A subroutine's end is its ENDSUB.
            end_span = getattr(term, "span", None) or span
            kind = self.routine.kind
            block.terminator = ir.End(end_span) if kind is ir.RoutineKind.MAIN else \
                ir.Return(end_span) if kind is ir.RoutineKind.SUBROUTINE else ir.FallOff(end_span)
        else:
            block.terminator = term

    def test(self, cond: ir.Cond, then: str, otherwise: str, span: Span | None) -> None:
        """Ends the current block with a branch on `cond`, as one Arcus comparison."""
        cond = self.normal(cond)
        if isinstance(cond, ir.Compare) and isinstance(cond.left, ir.Const) and isinstance(cond.right, ir.Const):
            # A constant condition (WHILE 1=1) is a plain jump: the loop it makes has no exit.
            holds = CONSTANT_TESTS[cond.op](cond.left.value, cond.right.value)
            self.block.terminator = ir.Jump(then if holds else otherwise, span)
            return
        if isinstance(cond, ir.Compare):
            left = self.cond_operand(cond.left, span)
            right = self.cond_operand(cond.right, span)
            self.block.terminator = ir.Branch(ir.Compare(cond.op, left, right, cond.span), then, otherwise, span)
            return
        flag = self.em.temps.alloc()
        self.flag(cond, flag, span)
        self.block.terminator = ir.Branch(ir.Compare("=", flag, ir.Const(1)), then, otherwise, span)

    def flag(self, cond: ir.Logic, flag: ir.Var, span: Span | None) -> None:
        """flag = 1 when cond holds, else 0, with nested IFs (an AND: flag=0, IF a, IF b, flag=1; an OR
        by De Morgan: flag=1, IF !a, IF !b, flag=0): a shape the structurer always rebuilds."""
        first, second = cond.left, cond.right
        initial, final = (0, 1) if cond.op == "and" else (1, 0)
        if cond.op != "and":
            first, second = self.normal(ir.Not(first)), self.normal(ir.Not(second))
        self.emit(ir.Assign(flag, ir.Const(initial), span))
        after = ir.Block("", span=span)
        inner = self.new_block(span)
        after.label = self.new_label()
        self.test(first, inner.label, after.label, span)
        self.block = inner
        setter = self.new_block(span)
        self.test(second, setter.label, after.label, span)
        setter.ops.append(ir.Assign(flag, ir.Const(final), span))
        setter.terminator = ir.Jump(after.label, span)
        self.out.blocks.append(after)
        self.block = after

    def new_label(self) -> str:
        self.split += 1
        return f"{self.routine.name}.{self.split}%"

    def normal(self, cond: ir.Cond) -> ir.Compare | ir.Logic:
        """Conditions as comparisons and AND/OR of comparisons (NOT pushed inside)."""
        if isinstance(cond, ir.Compare):
            op = COMPARE_SPELLING.get(cond.op, cond.op)
            if op not in NEGATE:
                self.em.unsupported_cond(cond)
                raise _Skip
            return ir.Compare(op, cond.left, cond.right, cond.span)
        if isinstance(cond, ir.Truth):
            return ir.Compare("!=", cond.expr, ir.Const(0), cond.span)
        if isinstance(cond, ir.Logic) and cond.op in ("and", "or"):
            return ir.Logic(cond.op, self.normal(cond.left), self.normal(cond.right), cond.span)
        if isinstance(cond, ir.Not):
            inner = self.normal(cond.cond)
            if isinstance(inner, ir.Compare):
                return negate(inner)
            return ir.Logic("or" if inner.op == "and" else "and", self.normal(ir.Not(inner.left)),
                            self.normal(ir.Not(inner.right)), cond.span)
        self.em.unsupported_cond(cond)
        raise _Skip

    def cond_operand(self, value: ir.Expr, span: Span | None) -> ir.Expr:
        if self.em.is_atom(value, condition=True):
            return self.em.atom(value)
        return self.materialize(value, span)


class _Skip(Exception):
    """An operation that was reported and is left out."""


_POSITION_UNITS = frozenset({ir.Unit.NONE, ir.Unit.STEPS, ir.Unit.COUNTS})


# =============================================================================================
# 3. Structuring


class Graph:
    """Reachability, dominators and loops of one routine's CFG (with a virtual exit node)."""

    def __init__(self, routine: ir.Routine):
        self.blocks = {b.label: b for b in routine.blocks}
        self.entry = routine.blocks[0].label if routine.blocks else EXIT
        self.succ: dict[str, list[str]] = {}
        for label, block in self.blocks.items():
            term = block.terminator
            if isinstance(term, (ir.Return, ir.FallOff)) or term is None:
                self.succ[label] = [EXIT]
            else:
                self.succ[label] = [t for t in ir.successors(term) if t in self.blocks]
        self.succ[EXIT] = []
        self.order = self.reverse_postorder()
        self.index = {label: i for i, label in enumerate(self.order)}
        self.preds: dict[str, list[str]] = {label: [] for label in self.order}
        for label in self.order:
            for s in self.succ[label]:
                self.preds[s].append(label)
        self.idom = self.dominators()
        self.children: dict[str, list[str]] = {label: [] for label in self.order}
        for label in self.order:
            parent = self.idom.get(label)
            if parent is not None and parent != label:
                self.children[parent].append(label)
        self.number_dominator_tree()
        self.back_edges = {(u, v) for u in self.order for v in self.succ[u] if self.dominates(v, u)}
        self.headers = {v for _, v in self.back_edges}
        self.reducible = self.check_reducible()

    def reverse_postorder(self) -> list[str]:
        seen = {self.entry}
        post: list[str] = []
        stack = [(self.entry, iter(self.succ[self.entry]))]
        while stack:
            label, it = stack[-1]
            for s in it:
                if s not in seen:
                    seen.add(s)
                    stack.append((s, iter(self.succ[s])))
                    break
            else:
                stack.pop()
                post.append(label)
        return post[::-1]

    def dominators(self) -> dict[str, str]:
        """Cooper, Harvey and Kennedy's iterative algorithm over the reverse postorder."""
        idom = {self.entry: self.entry}
        index = self.index
        changed = True
        while changed:
            changed = False
            for label in self.order[1:]:
                new = None
                for p in self.preds[label]:
                    if p not in idom:
                        continue
                    if new is None:
                        new = p
                        continue
                    a, b = p, new
                    while a != b:
                        while index[a] > index[b]:
                            a = idom[a]
                        while index[b] > index[a]:
                            b = idom[b]
                    new = a
                if new is not None and idom.get(label) != new:
                    idom[label] = new
                    changed = True
        return idom

    def number_dominator_tree(self) -> None:
        """Pre- and post-order numbers of the dominator tree: a dominates b when b's interval lies in
        a's, a constant-time test (walking up the tree would make long programs quadratic)."""
        self.pre: dict[str, int] = {}
        self.post: dict[str, int] = {}
        counter = 0
        stack = [(self.entry, iter(self.children.get(self.entry, ())))]
        self.pre[self.entry] = counter
        while stack:
            label, it = stack[-1]
            child = next(it, None)
            if child is None:
                stack.pop()
                counter += 1
                self.post[label] = counter
            else:
                counter += 1
                self.pre[child] = counter
                stack.append((child, iter(self.children[child])))

    def dominates(self, a: str, b: str) -> bool:
        """a dominates b."""
        if a not in self.pre or b not in self.pre:
            return False
        return self.pre[a] <= self.pre[b] and self.post[b] <= self.post[a]

    def check_reducible(self) -> bool:
        """Every edge to a node still on the DFS stack must be a back edge (target dominates source)."""
        on_stack = {self.entry}
        seen = {self.entry}
        stack = [(self.entry, iter(self.succ[self.entry]))]
        while stack:
            label, it = stack[-1]
            for s in it:
                if s in on_stack and not self.dominates(s, label):
                    return False
                if s not in seen:
                    seen.add(s)
                    on_stack.add(s)
                    stack.append((s, iter(self.succ[s])))
                    break
            else:
                stack.pop()
                on_stack.discard(label)
        return True

    def forward_preds(self, label: str) -> int:
        return sum(1 for p in self.preds.get(label, ()) if (p, label) not in self.back_edges)

    def loop_body(self, header: str) -> set[str]:
        body = {header}
        work = [u for u, v in self.back_edges if v == header]
        while work:
            label = work.pop()
            if label in body:
                continue
            body.add(label)
            work.extend(self.preds.get(label, ()))
        return body

    def terminating(self) -> set[str]:
        """Blocks from which every path ends at an END (never falls through to anything after)."""
        result: set[str] = set()
        changed = True
        while changed:
            changed = False
            for label in reversed(self.order):
                if label in result or label == EXIT:
                    continue
                block = self.blocks[label]
                succ = self.succ[label]
                if isinstance(block.terminator, ir.End) or (succ and all(s in result for s in succ)):
                    result.add(label)
                    changed = True
        return result

    def exits(self, header: str, body: set[str], ends: set[str]) -> list[tuple[str, str]]:
        return [(u, v) for u in body for v in self.succ[u] if v not in body and v not in ends]


def flag_loops(routine: ir.Routine, temps: Temps, max_copied: int) -> None:
    """Rewrites loops whose one exit is not the header's test into `f=1; WHILE f=1 ... f=0` form.

    The exit edge u -> e goes to a new block `f=0` that jumps to a new header testing f, whose false
    edge leads to e; entries to the old header go through a new block `f=1`. A loop that exits at its
    header but has operations there (a do-while, a condition computed into temporaries) is written
    with the operations copied before WHILE and at the end of the body when there are at most
    `max_copied` of them, with a flag otherwise. Raises Unstructurable when the graph is irreducible
    or a loop has several exits (the dispatch fallback handles those)."""
    counter = 0
    done: set[str] = set()
    while True:
        graph = Graph(routine)
        if not graph.reducible:
            raise Unstructurable("the control-flow graph is irreducible (a loop is entered at two places)")
        ends = graph.terminating()
        loops = [(graph.loop_body(h), h) for h in graph.headers]
        loops.sort(key=lambda item: (len(item[0]), graph.index[item[1]]))
        target = None
        for body, header in loops:
            if header in done:
                continue
            exits = graph.exits(header, body, ends)
            term = graph.blocks[header].terminator
            clean = isinstance(term, ir.Branch) and len(exits) == 1 and exits[0][0] == header \
                and len(graph.blocks[header].ops) <= max_copied
            if not exits or clean:
                continue
            if len(exits) > 1:
                raise Unstructurable("a loop is left from several places")
            target = (header, body, exits[0])
            break
        if target is None:
            return
        header, body, (source, exit_label) = target
        depth = sum(1 for h in graph.headers if h != header and header in graph.loop_body(h))
        flag = temps.top(depth)
        if flag is None:
            raise Unstructurable("no temporary variable is left for a loop flag")
        counter += 1
        span = graph.blocks[header].span
        pre = ir.Block(f"{routine.name}.pre{counter}%", [ir.Assign(flag, ir.Const(1), span)], span=span)
        test = ir.Block(f"{routine.name}.test{counter}%", span=span)
        leave = ir.Block(f"{routine.name}.leave{counter}%", [ir.Assign(flag, ir.Const(0), span)], span=span)
        pre.terminator = ir.Jump(test.label, span)
        test.terminator = ir.Branch(ir.Compare("=", flag, ir.Const(1)), header, exit_label, span)
        leave.terminator = ir.Jump(test.label, span)
        for block in routine.blocks:
            inside = block.label in body
            _retarget(block, header, test.label if inside else pre.label)
            if block.label == source:
                _retarget(block, exit_label, leave.label)
        entry_moved = routine.blocks[0].label == header
        routine.blocks.extend([test, leave])
        routine.blocks.insert(0 if entry_moved else len(routine.blocks), pre)
        done.add(test.label)
        done.add(header)


def _retarget(block: ir.Block, old: str, new: str) -> None:
    term = block.terminator
    if isinstance(term, ir.Jump) and term.target == old:
        term.target = new
    elif isinstance(term, ir.Branch):
        if term.then == old:
            term.then = new
        if term.otherwise == old:
            term.otherwise = new


class Structurer:
    """Rebuilds IF/ELSEIF/ELSE and WHILE from a reducible CFG (pass 3)."""

    def __init__(self, routine: ir.Routine):
        self.graph = Graph(routine)
        self.blocks = self.graph.blocks
        self.emitted: set[str] = set()
        self.ends = self.graph.terminating()
        self.exit_span: Span | None = None

    def run(self) -> list:
        graph = self.graph
        if not graph.reducible:
            raise Unstructurable("the control-flow graph is irreducible")
        if graph.entry == EXIT:
            return []
        code = self.region(graph.entry, EXIT, frozenset(), frozenset())
        missing = [label for label in graph.order if label != EXIT and label not in self.emitted]
        if missing:
            raise Unstructurable(f"block {missing[0]} is reached from outside its IF or WHILE")
        return code

    def span(self, label: str) -> Span | None:
        block = self.blocks.get(label)
        return block.span if block is not None else None

    def leaves(self, arm: str, join: str) -> bool:
        """The arm ENDs on every path without ever reaching `join`."""
        if arm not in self.ends:
            return False
        seen = {arm}
        work = [arm]
        while work:
            label = work.pop()
            if label == join:
                return False
            for succ in self.graph.succ.get(label, ()):
                if succ not in seen:
                    seen.add(succ)
                    work.append(succ)
        return True

    def copyable(self, label: str) -> bool:
        """A short block that ENDs the program may be written twice (tail duplication)."""
        block = self.blocks[label]
        return isinstance(block.terminator, ir.End) and len(block.ops) <= TAIL_COPY

    def is_test(self, label: str) -> bool:
        """A block that only tests (an ELSEIF): no operations, a branch, one way in."""
        block = self.blocks.get(label)
        return (block is not None and not block.ops and isinstance(block.terminator, ir.Branch)
                and label not in self.graph.headers and label not in self.emitted
                and self.graph.forward_preds(label) == 1)

    def join(self, label: str, follow: str) -> str:
        merges = [c for c in self.graph.children[label] if self.graph.forward_preds(c) >= 2]
        if not merges:
            return follow
        if len(merges) > 1:
            raise Unstructurable("a branch's paths meet at more than one place")
        return merges[0]

    def region(self, label: str | None, follow: str, forbidden: frozenset, active: frozenset,
               first: bool = False) -> list:
        out: list = []
        while label is not None and (label != follow or first):
            starting, first = first, False
            if label == EXIT:
                raise Unstructurable("a return from the middle of a routine")
            if label in forbidden and not starting:
                raise Unstructurable("a jump out of an IF or WHILE")
            if label in self.graph.headers and label not in active:
                code, label = self.loop(label, follow, forbidden, active)
                out += code
                continue
            if label in self.emitted and not self.copyable(label):
                raise Unstructurable("a block is reached from two structured places")
            self.emitted.add(label)
            block = self.blocks[label]
            out += [Simple(op) for op in block.ops]
            term = block.terminator
            if isinstance(term, ir.Jump):
                label = term.target
            elif isinstance(term, ir.Branch):
                label = self.branch(label, term, follow, forbidden, active, out)
            elif isinstance(term, ir.End):
                out.append(EndNode(term.span))
                label = None
            else:  # Return, FallOff: the routine's end
                self.exit_span = getattr(term, "span", None) or self.exit_span
                label = EXIT
                if follow != EXIT:
                    raise Unstructurable("a return from the middle of a routine")
        return out

    def branch(self, label: str, term: ir.Branch, follow: str, forbidden: frozenset, active: frozenset,
               out: list) -> str | None:
        if term.then == term.otherwise:
            return term.then
        join = self.join(label, follow)
        inner = (forbidden | {follow}) - {join}
        then, otherwise = term.then, term.otherwise
        cond = term.cond
        if join == follow and self.leaves(otherwise, join) and not self.leaves(then, join) and then != follow \
                and self.is_test(then):
            cond, then, otherwise = negate(cond), otherwise, then  # the ENDing arm first, as below
        if join == follow and self.leaves(then, join) and otherwise != follow and self.is_test(otherwise):
            # IF a / END / ELSEIF b ...: keep the ELSEIF chain; its own merge point closes the whole IF.
            join = self.join(otherwise, follow)
            inner = (forbidden | {follow}) - {join}
        elif join == follow:
            # One arm never comes back (it ENDs): keep it inside the IF, go on with the other one.
            if self.leaves(then, join):
                out.append(self.if_node(cond, self.region(then, join, inner, active), [], term, None,
                                        self.span(otherwise)))
                return otherwise
            if self.leaves(otherwise, join):
                out.append(self.if_node(negate(cond), self.region(otherwise, join, inner, active), [], term, None,
                                        self.span(then)))
                return then
        then_code = self.region(then, join, inner, active)
        else_code = self.region(otherwise, join, inner, active)
        else_span = self.span(otherwise) if otherwise != join else None
        end_span = self.span(join) if join != follow else None
        out.append(self.if_node(cond, then_code, else_code, term, else_span, end_span))
        return join

    @staticmethod
    def if_node(cond: ir.Compare, then: list, orelse: list, term: ir.Branch, else_span: Span | None,
                end_span: Span | None = None) -> IfNode:
        if not then and orelse:
            cond, then, orelse = negate(cond), orelse, []
        if len(orelse) == 1 and isinstance(orelse[0], IfNode):  # ELSE IF ... -> ELSEIF
            inner = orelse[0]
            return IfNode([(cond, then)] + inner.arms, inner.orelse, [term.span] + inner.spans, inner.else_span,
                          end_span or inner.end_span)
        return IfNode([(cond, then)], orelse, [term.span], else_span if orelse else None, end_span)

    def loop(self, header: str, follow: str, forbidden: frozenset, active: frozenset) -> tuple[list, str | None]:
        graph = self.graph
        body = graph.loop_body(header)
        block = self.blocks[header]
        term = block.terminator
        leaving = [(u, v) for u in body for v in graph.succ[u] if v not in body]
        tested = [v for u, v in leaving if u == header and isinstance(term, ir.Branch)]
        others = [(u, v) for u, v in leaving if not (u == header and v in tested)]
        # Edges to blocks that END are not exits: those blocks are written inside the loop.
        if len(tested) == 1 and all(v in self.ends for _, v in others):
            exit_label = tested[0]
        elif all(v in self.ends for _, v in leaving):  # endless loop: WHILE 1=1
            code = self.region(header, header, (forbidden | {follow}) - {header}, active | {header}, first=True)
            return [WhileNode(TRUE, code, block.span)], None
        else:
            raise Unstructurable("a loop is left from the middle of its body")
        inside = term.otherwise if term.then == exit_label else term.then
        cond = term.cond if term.then == inside else negate(term.cond)
        self.emitted.add(header)
        pre = [Simple(op) for op in block.ops]
        code = self.region(inside, header, (forbidden | {follow, exit_label}) - {header}, active | {header})
        end_span = self.blocks[exit_label].span if exit_label in self.blocks else None
        return pre + [WhileNode(cond, code + list(pre), term.span, end_span)], exit_label


def dispatch(routine: ir.Routine, var: ir.Var) -> list:
    """The fallback: WHILE var!=0 with one IF arm per basic block; var holds the next block's number."""
    graph = Graph(routine)
    labels = [label for label in graph.order if label != EXIT]
    number = {label: i + 1 for i, label in enumerate(labels)}
    number[EXIT] = 0

    def goto(label: str, span: Span | None) -> Simple:
        return Simple(ir.Assign(var, ir.Const(number.get(label, 0)), span))

    arms = []
    spans = []
    for label in labels:
        block = graph.blocks[label]
        body: list = [Simple(op) for op in block.ops]
        term = block.terminator
        if isinstance(term, ir.Jump):
            body.append(goto(term.target, term.span))
        elif isinstance(term, ir.Branch):
            body.append(IfNode([(term.cond, [goto(term.then, term.span)])], [goto(term.otherwise, term.span)],
                               [term.span]))
        elif isinstance(term, ir.End):
            body.append(EndNode(term.span))
        else:
            body.append(goto(EXIT, getattr(term, "span", None)))
        arms.append((ir.Compare("=", var, ir.Const(number[label])), body))
        spans.append(block.span)
    start = Simple(ir.Assign(var, ir.Const(number.get(graph.entry, 0)), routine.span))
    if not arms:
        return []
    return [start, WhileNode(ir.Compare("!=", var, ir.Const(0)), [IfNode(arms, [], spans)], routine.span)]


# =============================================================================================
# 4. Layout and 5. cost


@dataclass
class Stmt:
    """One line of the output and the assembly lines it costs."""

    text: str
    key: str  # cost key (catalog name, V, V_OP; a move lists its axes)
    spans: tuple[Span, ...]
    rows: list[tuple[str, str]] = field(default_factory=list)  # (opcode, operands) of the natural expansion
    jumps: dict[str, int] = field(default_factory=dict)  # placeholder -> statement index
    cost: int = 0
    address: int = 0


class Emitter:
    def __init__(self, module: ir.Module, profile: Profile):
        self.module = module
        self.profile = profile
        self.config = Config.from_profile(profile)
        self.cat = arcus_catalog.load()
        self.diags = Diagnostics()
        self.temps = Temps(self.config.temporaries)
        self.var_map: dict[str, str] = {}
        self.sub_numbers: dict[str, int] = {}
        self.reported: dict[int, object] = {}
        self.stmts: list[Stmt] = []
        self.dispatched: list[str] = []
        self.by_ir = {k.ir: k for k in self.cat.keywords if k.ir and k.kind not in (arcus_catalog.ASCII_ONLY,)}
        self.homes = {int(k.get("home_mode")): k for k in self.cat.keywords
                      if k.ir == "home" and k.get("home_mode") is not None}

    # diagnostics ------------------------------------------------------------------------------
    def file_span(self) -> Span:
        return Span(self.module.path or "<ir>", 1, 1, 1, 1, 0, 0)

    def span_of(self, op) -> Span:
        span = getattr(op, "span", None)
        return span if span is not None else self.file_span()

    def unsupported(self, op, why: str, code: str = "G003", severity_note: bool = False) -> None:
        if id(op) in self.reported:
            return
        self.reported[id(op)] = op  # kept alive so that its id is not reused
        from mcc.compiler.diagnostics import Severity

        self.diags.add(code, self.span_of(op), f"not written for the Arcus PMX-4EX-SA: {why}",
                       severity=Severity.WARNING if severity_note else None)

    def unsupported_expr(self, value: ir.Expr, span: Span | None) -> None:
        what = type(value).__name__
        if isinstance(value, (ir.BinOp, ir.UnOp)):
            what = f"the operator '{value.op}'"
        elif isinstance(value, ir.Func):
            what = f"the function {value.name}"
        elif isinstance(value, ir.Const):
            what = f"the number {value.value} (Arcus variables are whole numbers)"
        elif isinstance(value, ir.DeviceRef):
            what = f"the {value.dialect} register {value.name}"
        holder = type("Holder", (), {"span": span or getattr(value, "span", None)})()
        self.unsupported(holder, f"{what} has no Arcus form")

    def unsupported_cond(self, cond: ir.Cond) -> None:
        holder = type("Holder", (), {"span": getattr(cond, "span", None)})()
        self.unsupported(holder, f"this condition ({type(cond).__name__}) has no Arcus form")

    # names -------------------------------------------------------------------------------------
    def var(self, var: ir.Var) -> ir.Var:
        name = var.name.upper()
        if VARIABLE.match(name):
            return ir.Var(name, var.span)
        if name not in self.var_map:
            used = {int(VARIABLE.match(n.upper()).group(1)) for n in self.all_variable_names()
                    if VARIABLE.match(n.upper())} | set(self.config.temporaries) | \
                   {int(v[1:]) for v in self.var_map.values()}
            free = next((i for i in range(0, 64) if i not in used), None)
            if free is None:
                self.diags.add("A205", self.span_of(var), f"no Arcus variable left for {var.name}: V0-V63 are all "
                                                          "used or reserved")
                free = 0
            self.var_map[name] = f"V{free}"
        return ir.Var(self.var_map[name], var.span)

    def all_variable_names(self) -> set[str]:
        if not hasattr(self, "_names"):
            names = set(self.module.variables)
            for _, block in self.module.blocks():
                for op in block.ops:
                    if isinstance(op, ir.Assign):
                        names.add(op.target.name)
                    for expr in ir.op_exprs(op):
                        names.update(e.name for e in ir.walk_expr(expr) if isinstance(e, ir.Var))
                names.update(e.name for expr in ir.term_exprs(block.terminator) for e in ir.walk_expr(expr)
                             if isinstance(e, ir.Var))
            self._names = names
        return self._names

    def axis(self, axis: str, op, setting: bool = False) -> str:
        """An IR axis name as an Arcus axis letter ("*" stays "*" for global settings and stops)."""
        upper = axis.upper()
        if upper in AXES:
            return upper
        if upper in ("", ir.ALL_AXES):
            return ir.ALL_AXES if setting else self.config.axes[0]
        if len(self.config.axes) and upper.isdigit() and 1 <= int(upper) <= len(self.config.axes):
            return self.config.axes[int(upper) - 1]
        self.unsupported(op, f"axis '{axis}' has no Arcus axis letter (X, Y, Z, U)")
        raise _Skip

    def sub_number(self, routine: str, op, span: Span | None = None) -> int | None:
        if routine not in self.sub_numbers:
            holder = op if op is not None else type("Holder", (), {"span": span})()
            self.unsupported(holder, f"the call target '{routine}' is not a subroutine of this program")
            return None
        return self.sub_numbers[routine]

    # catalog-driven spelling -------------------------------------------------------------------------
    def keyword_of(self, mnemonic: str) -> arcus_catalog.Keyword | None:
        match = self.cat.match(mnemonic.upper())
        return match.keyword if match is not None else None

    def register(self, ref: ir.DeviceRef) -> arcus_catalog.Keyword | None:
        if ref.dialect != DIALECT:
            return None
        return self.cat.lookup(ref.name, ref.axis, ref.index)

    def is_atom(self, value: ir.Expr, readable: bool = False, operation: bool = False,
                condition: bool = False) -> bool:
        if isinstance(value, ir.Const):
            return float(value.value).is_integer()
        if isinstance(value, ir.Var):
            return True
        if isinstance(value, ir.DeviceRef):
            keyword = self.register(value)
            if keyword is None or not keyword.readable:
                return False
            return (readable or (operation and keyword.in_operation) or (condition and keyword.in_condition))
        return False

    def atom(self, value: ir.Expr) -> ir.Expr:
        if isinstance(value, ir.Const):
            return ir.Const(int(value.value), value.unit, value.span)
        if isinstance(value, ir.Var):
            return self.var(value)
        return value

    def text(self, value: ir.Expr) -> str:
        if isinstance(value, ir.Const):
            return str(int(value.value))
        if isinstance(value, ir.Var):
            return value.name
        if isinstance(value, ir.DeviceRef):
            keyword = self.register(value)
            if keyword is None:
                return value.name
            return keyword.spell(value.axis if value.axis != ir.ALL_AXES else "", value.index)
        if isinstance(value, ir.UnOp):
            return f"~{self.text(value.operand)}"
        if isinstance(value, ir.BinOp):
            return f"{self.text(value.left)}{value.op}{self.text(value.right)}"
        return "?"

    def cond_text(self, cond: ir.Compare) -> str:
        return f"{self.text(cond.left)}{cond.op}{self.text(cond.right)}"

    # the whole program ---------------------------------------------------------------------------------
    def run(self) -> Listing:
        listing = Listing(DIALECT)
        self.moved = modes.changers(self.module, explicit_moves=True)
        self.entries = {r.blocks[0].label: r for r in self.module.routines if r.blocks}
        self.number_routines()
        main_code: list = []
        subs: list[tuple[ir.Routine, list, Span | None]] = []
        for routine in self.module.routines:
            kind = routine.kind
            if kind in (ir.RoutineKind.HANDLER, ir.RoutineKind.POWERUP):
                holder = type("Holder", (), {"span": routine.span})()
                self.unsupported(holder, f"{routine.name} is a {kind.value} routine; Arcus has no event handlers "
                                         "or power-up entry")
                continue
            code, end_span = self.compile_routine(routine)
            if kind is ir.RoutineKind.SUBROUTINE:
                subs.append((routine, code, end_span))
            else:  # MAIN, and IMMEDIATE commands, which run before the program
                if kind is ir.RoutineKind.IMMEDIATE:
                    code = [n for n in code if not isinstance(n, EndNode)]
                    main_code = code + main_code
                else:
                    main_code += code
        self.check_temporaries()
        self.flatten(main_code)
        if not main_code or not isinstance(main_code[-1], EndNode):
            self.add("END", "END", None, [("HALT", "")])
        for routine, code, end_span in subs:
            number = self.sub_numbers[routine.name]
            self.add(f"SUB {number}", "SUB", routine.span, [("ENTRY", f"SUB {number}")])
            self.flatten(code)
            self.add("ENDSUB", "ENDSUB", end_span, [("RET", "")])
        self.layout(listing)
        return listing

    def number_routines(self) -> None:
        low, high = self.config.sub_range
        taken: set[int] = set()
        pending: list[ir.Routine] = []
        for routine in self.module.routines:
            if routine.kind is not ir.RoutineKind.SUBROUTINE:
                continue
            number = routine.number
            if number is not None and low <= number <= high and number not in taken:
                self.sub_numbers[routine.name] = number
                taken.add(number)
            else:
                pending.append(routine)
        candidates = (n for n in range(max(low, self.config.allocate_from), high + 1) if n not in taken)
        for routine in pending:
            number = next(candidates, None)
            if number is None:
                self.diags.add("A207", routine.span or self.file_span(),
                               f"no subroutine number left for {routine.name}: the profile allows {low}-{high}")
                continue
            self.sub_numbers[routine.name] = number
            taken.add(number)

    def compile_routine(self, routine: ir.Routine) -> tuple[list, Span | None]:
        legal = Legalizer(self, routine).run()
        self.insert_modes(legal)
        self.temps.start_routine()
        flags = ir.Routine(legal.name, legal.kind, [self.copy_block(b) for b in legal.blocks], legal.span,
                           legal.number)
        try:
            flag_loops(flags, self.temps, self.config.max_copied)
            structurer = Structurer(flags)
            return structurer.run(), structurer.exit_span
        except Unstructurable as why:
            var = self.temps.top(0)
            if var is None:
                var = ir.Var(f"V{self.config.temporaries[-1] if self.config.temporaries else 63}")
            self.dispatched.append(routine.name)
            self.diags.add("A202", routine.span or self.file_span(),
                           f"{routine.name}: {why}; it is written as a dispatch loop on {var.name} "
                           "(WHILE {0}!=0 with one IF arm per block)".format(var.name))
            exit_span = next((b.terminator.span for b in legal.blocks
                              if isinstance(b.terminator, (ir.Return, ir.FallOff))), None)
            return dispatch(legal, var), exit_span

    @staticmethod
    def copy_block(block: ir.Block) -> ir.Block:
        term = block.terminator
        if isinstance(term, ir.Jump):
            term = ir.Jump(term.target, term.span)
        elif isinstance(term, ir.Branch):
            term = ir.Branch(term.cond, term.then, term.otherwise, term.span)
        return ir.Block(block.label, list(block.ops), term, block.span, block.named)

    def insert_modes(self, routine: ir.Routine) -> None:
        """Pass 2: ABS/INC before a move whose mode is not the one in force (modes.py).

        Two states flow through the CFG: the mode the IR's own ABS/INC select (what a MODAL move
        means) and the mode the written program has in force (which an inserted ABS/INC changes).
        An ABSOLUTE/RELATIVE move needs the written mode to be its own; a MODAL move needs it to be
        the IR's mode when that one is known."""
        moved = self.moved
        entry = modes.entry_state(routine, self.profile)

        def transfer(block: ir.Block, state: tuple[str, str, bool], ops: list | None) -> tuple[str, str, bool]:
            meant, written, changed = state  # changed: an inserted switch may hide an unknown mode
            for op in block.ops:
                if isinstance(op, ir.Move):
                    need = modes.STATE_OF.get(op.mode) or (meant if meant != modes.UNKNOWN else None)
                    if need is not None and written != need:
                        written = need
                        changed = changed or meant != written
                        if ops is not None:
                            ops.append(ir.Native(DIALECT, need, span=op.span))
                    elif need is None and changed and ops is not None:
                        self.uncertain_mode(op)
                if ops is not None:
                    ops.append(op)
                selected = modes.switch(op)
                if selected is not None:
                    meant = written = selected
                    changed = False
                elif isinstance(op, ir.Call) and op.routine in moved:
                    meant = written = modes.UNKNOWN
            return meant, written, changed

        if not routine.blocks:
            return
        blocks = {b.label: b for b in routine.blocks}
        states: dict[str, tuple[str, str, bool]] = {routine.blocks[0].label: (entry, entry, False)}
        work = [routine.blocks[0].label]
        while work:
            label = work.pop()
            out = transfer(blocks[label], states[label], None)
            for succ in ir.successors(blocks[label].terminator):
                if succ not in blocks:
                    continue
                old = states.get(succ)
                new = out if old is None else (modes.meet(old[0], out[0]), modes.meet(old[1], out[1]),
                                               old[2] or out[2])
                if old != new:
                    states[succ] = new
                    work.append(succ)
        for block in routine.blocks:
            if block.label in states:
                ops: list[ir.Op] = []
                transfer(block, states[block.label], ops)
                block.ops = ops

    def uncertain_mode(self, op: ir.Move) -> None:
        if id(op) in self.reported:
            return
        self.reported[id(op)] = op
        self.diags.add("A208", self.span_of(op),
                       "this move uses the ABS/INC mode in force, which is not known here, and an ABS or INC "
                       "written for an earlier move with an explicit mode may have changed it: make the move's "
                       "mode explicit in the source")

    def check_temporaries(self) -> None:
        temps = self.temps
        if temps.conflict:
            self.diags.add("A205", self.file_span(),
                           f"compiling this program needs {temps.peak + temps.high} temporary variables at once; "
                           f"the profile reserves {len(temps.pool)} ([arcus] temporaries = {temps.pool}): reserve "
                           "more or simplify the expressions")
        if temps.peak == 0 and temps.high == 0:
            return
        used = {f"V{n}" for n in temps.pool[:temps.peak]} | {f"V{n}" for n in temps.pool[len(temps.pool) - temps.high:]}
        for name in sorted(self.all_variable_names()):
            upper = name.upper()
            if upper in used:
                variable = self.module.variables.get(name)
                span = variable.span if variable is not None and variable.span is not None else self.file_span()
                self.diags.add("A203", span, f"{upper} is one of the variables mcc reserves for temporaries "
                                             f"({', '.join(f'V{n}' for n in temps.pool)}) and this program needs it: "
                                             "the compiled code overwrites it; use V0-V59 or change "
                                             "[arcus] temporaries in the profile")

    # flattening the structure into statements ---------------------------------------------------------
    def add(self, text: str, key: str, span: Span | None, rows: list[tuple[str, str]],
            jumps: dict[str, int] | None = None) -> int:
        self.stmts.append(Stmt(text, key, (span,) if span is not None else (), rows, jumps or {}))
        return len(self.stmts) - 1

    def flatten(self, nodes: list) -> None:
        for node in nodes:
            if isinstance(node, Simple):
                self.simple(node.op)
            elif isinstance(node, EndNode):
                self.add("END", "END", node.span, [("HALT", "")])
            elif isinstance(node, WhileNode):
                head = self.add(f"WHILE {self.cond_text(node.cond)}", "WHILE", node.span,
                                [("TEST", self.cond_text(node.cond)), ("JF", "{after}")])
                self.flatten(node.body)
                tail = self.add("ENDWHILE", "ENDWHILE", node.end_span or node.span, [("JMP", "{head}")],
                                {"head": head})
                self.stmts[head].jumps["after"] = tail + 1
            else:
                self.if_(node)

    def if_(self, node: IfNode) -> None:
        tests: list[int] = []
        exits: list[int] = []
        for i, (cond, body) in enumerate(node.arms):
            text = self.cond_text(cond)
            span = node.spans[i] if i < len(node.spans) else None
            if i == 0:
                index = self.add(f"IF {text}", "IF", span, [("TEST", text), ("JF", "{next}")])
            else:
                index = self.add(f"ELSEIF {text}", "ELSEIF", span,
                                 [("JMP", "{end}"), ("TEST", text), ("JF", "{next}")])
                exits.append(index)
                self.stmts[tests[-1]].jumps["next"] = index
            tests.append(index)
            self.flatten(body)
        if node.orelse:
            index = self.add("ELSE", "ELSE", node.else_span or node.spans[0], [("JMP", "{end}")])
            exits.append(index)
            self.stmts[tests[-1]].jumps["next"] = index
            self.flatten(node.orelse)
        end = self.add("ENDIF", "ENDIF", node.end_span or node.spans[0], [("NOP", "")])
        if "next" not in self.stmts[tests[-1]].jumps:
            self.stmts[tests[-1]].jumps["next"] = end
        for index in exits:
            self.stmts[index].jumps["end"] = end

    def simple(self, op: ir.Op) -> None:
        """One operation as one statement (WAIT on every axis is one per axis)."""
        span = op.span
        text = self.text
        if isinstance(op, ir.Assign):
            value = op.value
            target = op.target.name
            if isinstance(value, ir.BinOp):
                rows = [("LOAD", text(value.left)), (OPCODES[value.op], f"{text(value.right)} -> {target}")]
                self.add(f"{target}={text(value)}", "V_OP", span, rows)
            elif isinstance(value, ir.UnOp):
                rows = [("LOAD", text(value.operand)), ("NOT", f"-> {target}")]
                self.add(f"{target}={text(value)}", "V_OP", span, rows)
            else:
                self.add(f"{target}={text(value)}", "V", span, [("LET", f"{target} <- {text(value)}")])
        elif isinstance(op, ir.SetMotion):
            keyword = self.by_ir[MOTION_IR[op.param]]
            name = keyword.spell(op.axis if op.axis != ir.ALL_AXES else "")
            self.write(name, keyword.name, op.value, span)
        elif isinstance(op, ir.Move):
            parts = "".join(f"{axis}{text(value)}" for axis, value in op.targets)
            rows = [("MOVE", f"{axis} <- {text(value)}") for axis, value in op.targets]
            self.add(parts, " ".join(axis for axis, _ in op.targets), span, rows)
        elif isinstance(op, ir.Arc):
            keyword = self.by_ir["arc" if op.angle is not None else "circle"]
            suffix = "P" if op.clockwise else "N"
            operands = [text(c) for c in op.center] + ([text(op.angle)] if op.angle is not None else [])
            name = keyword.spell(suffix=suffix)
            rows = [("ARG", v) for v in operands] + [(name, "")]
            self.add(f"{name}{':'.join(operands)}", keyword.name, span, rows)
        elif isinstance(op, ir.Slew):
            self.bare(self.by_ir["jog"], span, axis=op.axis, direction=op.direction)
        elif isinstance(op, ir.Home):
            self.bare(self.homes[HOME_KEYWORDS[op.method]], span, axis=op.axis, direction=op.direction)
        elif isinstance(op, ir.Stop):
            keyword = self.by_ir["stop" if op.ramp else "abort"]
            self.bare(keyword, span, axis=op.axis if op.axis != ir.ALL_AXES else "")
        elif isinstance(op, ir.WaitMotion):
            for axis in (self.config.axes if op.axis == ir.ALL_AXES else (op.axis,)):
                self.bare(self.by_ir["wait_motion"], span, axis=axis)
        elif isinstance(op, ir.Delay):
            self.write("DELAY", "DELAY", op.duration, span)
        elif isinstance(op, ir.SetOutput):
            keyword = self.cat.lookup("DO", index=op.index)
            self.write(keyword.spell(index=op.index), keyword.name, op.value, span)
        elif isinstance(op, ir.SetPosition):
            keyword = self.by_ir["position"]
            self.write(keyword.spell(op.axis), keyword.name, op.value, span)
        elif isinstance(op, ir.Call):
            number = self.sub_numbers[op.routine]
            self.add(f"GOSUB {number}", "GOSUB", span, [("CALL", "{sub%d}" % number)])
        elif isinstance(op, ir.Native):
            keyword = self.keyword_of(op.mnemonic)
            key = keyword.name if keyword is not None else op.mnemonic
            if op.args:
                self.write(op.mnemonic, key, op.args[0], span, form=op.form or "=")
            else:
                self.add(op.mnemonic, key, span, [("EXEC", op.mnemonic)])

    def write(self, name: str, key: str, value: ir.Expr, span: Span | None, form: str = "=") -> None:
        self.add(f"{name}{form}{self.text(value)}", key, span, [("SET", f"{name} <- {self.text(value)}")])

    def bare(self, keyword: arcus_catalog.Keyword, span: Span | None, axis: str = "", direction: int = 0) -> None:
        name = keyword.spell(axis, direction=direction)
        self.add(name, keyword.name, span, [("EXEC", name)])

    # layout, cost model and listing ---------------------------------------------------------------------
    def cost_of(self, stmt: Stmt) -> int:
        if stmt.key and all(part in AXES for part in stmt.key.split(" ")):  # a move: per axis named
            return sum(self.config.cost(axis) for axis in stmt.key.split(" "))
        return self.config.cost(stmt.key)

    def layout(self, listing: Listing) -> None:
        config = self.config
        address = 0
        sub_address: dict[int, int] = {}
        for stmt in self.stmts:
            stmt.cost = self.cost_of(stmt)
            stmt.address = address
            address += stmt.cost
            if stmt.key == "SUB":
                sub_address[int(stmt.text.split()[1])] = stmt.address
        total = address
        detail: list[tuple[str, tuple[Span, ...]]] = []
        subs = {f"sub{n}": f"{a:04d}" for n, a in sub_address.items()}
        for stmt in self.stmts:
            listing.emit(stmt.text, *stmt.spans)
            targets = {name: f"{self.entry(i, total) if name == 'next' else self.address(i, total):04d}"
                       for name, i in stmt.jumps.items()}
            targets.update(subs)
            rows = [f"{op:<5} {PLACEHOLDER.sub(lambda m: targets.get(m.group(1), '????'), operands)}".rstrip()
                    for op, operands in stmt.rows]
            for row in fit(rows, stmt.cost):
                detail.append((row, stmt.spans))
        listing.detail = detail
        statements = len(self.stmts)
        share = 100.0 * total / config.budget if config.budget else 0.0
        listing.stats = {"statements": statements, "asm_lines": total, "asm_budget": config.budget,
                         "asm_percent": round(share, 1), "cost_model": config.model,
                         "temporaries": self.temps.peak + self.temps.high,
                         "dispatch_loops": len(self.dispatched)}
        listing.header = self.header(total, statements)
        self.check_budget(total)
        listing.diagnostics = self.diags

    def address(self, index: int, total: int) -> int:
        return self.stmts[index].address if index < len(self.stmts) else total

    def entry(self, index: int, total: int) -> int:
        """Where a failed IF/ELSEIF test lands: the test of the next ELSEIF (after its jump to
        ENDIF), the first line after ELSE, or the ENDIF."""
        stmt = self.stmts[index]
        if stmt.key == "ELSEIF":
            return stmt.address + min(1, stmt.cost - 1)
        if stmt.key == "ELSE":
            return stmt.address + stmt.cost
        return self.address(index, total)

    def header(self, total: int, statements: int) -> str:
        config = self.config
        status = "calibrated" if config.calibrated else "uncalibrated estimates (spec 6.4 H-estimate)"
        return "\n".join([
            f"; mcc arcus listing for {self.profile.title or self.profile.product} (profile {self.profile.name})",
            f"; cost model: {config.model}, {status}; per-statement costs from [arcus.cost] of the profile",
            f"; budget: {config.budget} assembly lines; this program: {total} lines for {statements} statements "
            f"({100.0 * total / config.budget if config.budget else 0:.1f} %)",
            "; rows: mcc pseudo-instructions, one per assembly line the model counts, numbered like the program "
            "counter (SPC); the controller's real encoding (SA<n>) is undocumented",
        ])

    def check_budget(self, total: int) -> None:
        config = self.config
        if not config.budget:
            return
        if total <= config.budget:
            if total > config.warn_fraction * config.budget:
                self.diags.add("A204", self.file_span(),
                               f"the program needs {total} of the {config.budget} assembly lines of the target "
                               f"({100.0 * total / config.budget:.0f} %) under the cost model '{config.model}', "
                               "whose costs are estimates: it may not fit on the controller")
            return
        per_line: dict[tuple[str, int], int] = {}
        first_span: dict[tuple[str, int], Span] = {}
        for stmt in self.stmts:
            for span in stmt.spans[:1]:
                key = (span.file, span.line)
                per_line[key] = per_line.get(key, 0) + stmt.cost
                first_span.setdefault(key, span)
        top = sorted(per_line.items(), key=lambda item: (-item[1], item[0][1]))[:5]
        listed = ", ".join(f"line {line} ({cost})" for (_, line), cost in top)
        span = first_span[top[0][0]] if top else self.file_span()
        self.diags.add("A201", span,
                       f"the program needs {total} assembly lines under the cost model '{config.model}' but the "
                       f"budget of profile '{self.profile.name}' is {config.budget}: shorten it by "
                       f"{total - config.budget} lines (loops, subroutines); the costliest source lines are "
                       f"{listed or 'not known'}",
                       notes=tuple(f"{first_span[k].label}: {cost} assembly lines" for k, cost in top))


def fit(rows: list[str], cost: int) -> list[str]:
    """Exactly `cost` rows: extra natural rows share the last one, missing ones are continuation rows."""
    if not rows:
        rows = ["NOP"]
    if len(rows) > cost:
        rows = rows[:cost - 1] + [" ; ".join(rows[cost - 1:])]
    while len(rows) < cost:
        rows.append(".     (continued: the model charges this statement another line)")
    return rows


def emit(module: ir.Module, profile: Profile) -> Listing:
    """Canonical Arcus standalone text and its assembly-level listing for an IR module."""
    return Emitter(module, profile).run()
