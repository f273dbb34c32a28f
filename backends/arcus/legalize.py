"""Pass 1: a copy of a routine's CFG in which every operation is one statement Arcus can write.

Arcus computes one operator per statement, writes registers from a literal or one variable, and
tests one comparison of plain values. So expressions with several operators are split into
one-operator assignments through the reserved temporaries (temporaries.py); register writes get a
literal or one variable; conditions become one comparison (AND/OR/NOT are computed into a 0/1 flag
with nested IFs, a shape the structurer always rebuilds); predicated calls become an IF around GOSUB;
waits for an input become an empty WHILE; jumps into other routines become GOSUB+END or a
fall-through. What Arcus cannot express at all is reported (G003 for operations of other dialects,
A206 for computed values where Arcus needs a number) and left out, so that one bad operation costs
one diagnostic and the rest of the program is still written.

The result obeys what backends/structure.py assumes of a routine.
"""

from __future__ import annotations

from mcc.backends.arcus.context import Context
from mcc.backends.arcus.target import AXES, DIALECT, HOME_KEYWORDS, MOTION_IR
from mcc.backends.structure import NEGATE, negate
from mcc.compiler import ir
from mcc.compiler.span import Span

ARCUS_BINARY = {"+", "-", "*", "/", "%", "&", "|", "<<", ">>"}
COMPARE_SPELLING = {"==": "=", "<>": "!="}
CONSTANT_TESTS = {"=": lambda a, b: a == b, "!=": lambda a, b: a != b, "<": lambda a, b: a < b,
                  "<=": lambda a, b: a <= b, ">": lambda a, b: a > b, ">=": lambda a, b: a >= b}
POSITION_UNITS = frozenset({ir.Unit.NONE, ir.Unit.STEPS, ir.Unit.COUNTS})  # what Arcus positions may be given in


class Skip(Exception):
    """An operation that was reported and is left out."""


class Legalizer:
    """Rewrites one routine into a CFG of operations Arcus can write (pass 1)."""

    def __init__(self, ctx: Context, routine: ir.Routine):
        self.ctx = ctx
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
        ctx = self.ctx
        temps = ctx.temps
        base = temps.live
        try:
            handler = getattr(self, "op_" + type(op).__name__.lower(), None)
            if handler is None:
                ctx.unsupported(op, f"{type(op).__name__} has no Arcus statement")
            else:
                handler(op)
        except Skip:
            pass
        temps.live = base

    def op_assign(self, op: ir.Assign) -> None:
        target = self.ctx.var(op.target)
        self.assign(target, op.value, op.span)

    def op_setmotion(self, op: ir.SetMotion) -> None:
        name = MOTION_IR.get(op.param)
        if name is None:
            self.ctx.unsupported(op, f"the {op.param.value} setting has no Arcus statement (Arcus has HSPD, LSPD "
                                     "and ACC, a ramp time used for both acceleration and deceleration)")
            raise Skip
        unit = op.value.unit if isinstance(op.value, ir.Const) else ir.Unit.NONE
        allowed = {ir.Unit.NONE, ir.Unit.MS} if op.param is ir.MotionParam.ACCEL else \
            {ir.Unit.NONE, ir.Unit.STEPS_PER_S}
        if unit not in allowed:
            arcus_unit = "a ramp time in ms" if op.param is ir.MotionParam.ACCEL else "in pulses/s"
            self.ctx.unsupported(op, f"the {op.param.value.replace('_', ' ')} is given in {unit.value}, and the "
                                     f"Arcus setting is {arcus_unit}: convert it in the source", code="G005")
            raise Skip
        self.emit(ir.SetMotion(op.param, self.axis(op.axis, op, setting=True), self.value(op.value, op),
                               op.span))

    def op_move(self, op: ir.Move) -> None:
        targets = tuple((self.axis(axis, op), self.value(value, op, units=POSITION_UNITS))
                        for axis, value in op.targets)
        if op.options:
            self.ctx.unsupported(op, "move options (MCode MA p2/p3) have no Arcus form; the move is written "
                                     "without them", severity_note=True)
        self.emit(ir.Move(op.mode, targets, span=op.span))

    def op_arc(self, op: ir.Arc) -> None:
        if tuple(op.axes) != ("X", "Y"):
            self.ctx.unsupported(op, "Arcus ARC/CIR move the X and Y axes only")
            raise Skip
        center = tuple(self.literal(c, op, "ARC/CIR centre") for c in op.center)
        angle = None if op.angle is None else self.literal(op.angle, op, "ARC angle")
        self.emit(ir.Arc(op.axes, center, op.clockwise, angle, op.span))

    def op_slew(self, op: ir.Slew) -> None:
        if op.velocity is not None or op.direction not in (1, -1):
            self.ctx.unsupported(op, "Arcus jogs at the current HSPD in a direction (JOGX+); a slew at a "
                                     "given velocity has no statement")
            raise Skip
        self.emit(ir.Slew(self.axis(op.axis, op), direction=op.direction, span=op.span))

    def op_home(self, op: ir.Home) -> None:
        if op.method not in HOME_KEYWORDS or op.direction not in (1, -1):
            self.ctx.unsupported(op, f"homing by '{op.method}' without a direction has no Arcus statement "
                                     "(HOME, ZHOME and ZOME home in + or - on the switch, switch+index or index)")
            raise Skip
        self.emit(ir.Home(self.axis(op.axis, op), op.method, op.direction, span=op.span))

    def op_stop(self, op: ir.Stop) -> None:
        self.emit(ir.Stop(self.axis(op.axis, op, setting=True), op.ramp, op.span))

    def op_waitmotion(self, op: ir.WaitMotion) -> None:
        self.emit(ir.WaitMotion(self.axis(op.axis, op, setting=True), op.span))

    def op_delay(self, op: ir.Delay) -> None:
        duration = op.duration
        if isinstance(duration, ir.Const) and duration.unit is ir.Unit.S:
            duration = ir.Const(duration.value * 1000, ir.Unit.MS, duration.span)
        self.emit(ir.Delay(self.literal(duration, op, "DELAY"), op.span))

    def op_setoutput(self, op: ir.SetOutput) -> None:
        if op.index is not None and not 1 <= op.index <= 8:
            self.ctx.unsupported(op, f"output {op.index}: the PMX-4EX-SA has DO1-DO8")
            raise Skip
        self.emit(ir.SetOutput(op.index, self.value(op.value, op), op.span))

    def op_setposition(self, op: ir.SetPosition) -> None:
        self.emit(ir.SetPosition(self.axis(op.axis, op), self.value(op.value, op, units=POSITION_UNITS),
                                 op.span))

    def op_call(self, op: ir.Call) -> None:
        if self.sub_number(op.routine, op) is None:
            raise Skip
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
            self.ctx.unsupported(op, f"{op.dialect} {op.mnemonic or 'statement'} has no Arcus equivalent")
            raise Skip
        keyword = self.ctx.keyword_of(op.mnemonic)
        args = op.args
        if args:
            literal = keyword is not None and keyword.literal_only
            args = tuple(self.literal(a, op, op.mnemonic) if literal else self.value(a, op) for a in args)
        self.emit(ir.Native(op.dialect, op.mnemonic.upper(), args, op.form, op.axis, op.span))

    # values -------------------------------------------------------------------------------------
    def assign(self, target: ir.Var, value: ir.Expr, span: Span | None) -> None:
        """target = value as one-operator assignments (L2675-L2677)."""
        if self.is_atom(value, readable=True):
            self.emit(ir.Assign(target, self.atom(value), span))
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
        self.unsupported_expr(value, span)
        raise Skip

    def materialize(self, value: ir.Expr, span: Span | None) -> ir.Var:
        temp = self.ctx.temps.alloc()
        self.assign(temp, value, span)
        return temp

    def operand(self, value: ir.Expr, span: Span | None) -> ir.Expr:
        """An operand of a one-operator assignment: a literal, a variable or an [Argument] register."""
        if self.is_atom(value, operation=True):
            return self.atom(value)
        return self.materialize(value, span)

    def value(self, value: ir.Expr, op: ir.Op, units: frozenset | None = None) -> ir.Expr:
        """A register's written value: a literal or one variable (L1797)."""
        if isinstance(value, ir.Const):
            if units is not None and value.unit not in units:
                self.ctx.unsupported(op, f"a value in {value.unit.value} cannot be written for Arcus, which counts "
                                         "pulses", code="G005")
                raise Skip
            return self.atom(value)
        if isinstance(value, ir.Var):
            return self.ctx.var(value)
        return self.materialize(value, getattr(op, "span", None))

    def literal(self, value: ir.Expr, op: ir.Op, what: str) -> ir.Const:
        if isinstance(value, ir.Const) and float(value.value).is_integer():
            return ir.Const(int(value.value), value.unit, value.span)
        self.ctx.diags.add("A206", self.ctx.span_of(op),
                           f"{what} takes a number written out on the PMX-4EX-SA; this program computes it at run "
                           "time: use a constant")
        raise Skip

    # conditions and terminators --------------------------------------------------------------------
    def target(self, label: str, span: Span | None) -> str:
        """A jump target inside this routine; a jump into another routine (other dialects) becomes
        a block of its own: into the main program from the setup lines, a fall-through; into a
        subroutine's entry, GOSUB then END (a transfer without return); anywhere else, reported."""
        if label in self.labels:
            return label
        ctx = self.ctx
        routine = ctx.entries.get(label)
        block = self.new_block(span)
        if routine is not None and routine.kind is ir.RoutineKind.MAIN and \
                self.routine.kind is ir.RoutineKind.IMMEDIATE:
            block.terminator = ir.FallOff(span)  # the setup lines are written before the main program
        elif routine is not None and routine.name in ctx.sub_numbers:
            block.ops.append(ir.Call(routine.name, span=span))
            block.terminator = ir.End(span)
            ctx.unsupported_at(span, f"the jump into {routine.name} is written as GOSUB "
                                     f"{ctx.sub_numbers[routine.name]} then END (Arcus has no GOTO)", code="G005")
        else:
            block.terminator = ir.End(span)
            ctx.unsupported_at(span, f"a jump to {label} inside another routine has no Arcus form (no GOTO)")
        return block.label

    def terminator(self, term: ir.Terminator | None, span: Span | None) -> None:
        block = self.block
        if isinstance(term, ir.Jump):
            block.terminator = ir.Jump(self.target(term.target, term.span), term.span)
        elif isinstance(term, ir.Branch):
            base = self.ctx.temps.live
            then, otherwise = self.target(term.then, term.span), self.target(term.otherwise, term.span)
            try:
                self.test(term.cond, then, otherwise, term.span)
            except Skip:  # reported: the condition has no Arcus form
                self.block.terminator = ir.End(term.span)
            self.ctx.temps.live = base
        elif isinstance(term, ir.GotoRoutine):
            if self.sub_number(term.routine, None, span) is not None:
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
        flag = self.ctx.temps.alloc()
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
                self.unsupported_cond(cond)
                raise Skip
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
        self.unsupported_cond(cond)
        raise Skip

    def cond_operand(self, value: ir.Expr, span: Span | None) -> ir.Expr:
        if self.is_atom(value, condition=True):
            return self.atom(value)
        return self.materialize(value, span)

    # what Arcus can name and compute ----------------------------------------------------------------
    def axis(self, axis: str, op, setting: bool = False) -> str:
        """An IR axis name as an Arcus axis letter ("*" stays "*" for global settings and stops)."""
        upper = axis.upper()
        if upper in AXES:
            return upper
        config = self.ctx.config
        if upper in ("", ir.ALL_AXES):
            return ir.ALL_AXES if setting else config.axes[0]
        if len(config.axes) and upper.isdigit() and 1 <= int(upper) <= len(config.axes):
            return config.axes[int(upper) - 1]
        self.ctx.unsupported(op, f"axis '{axis}' has no Arcus axis letter (X, Y, Z, U)")
        raise Skip

    def sub_number(self, routine: str, op, span: Span | None = None) -> int | None:
        if routine not in self.ctx.sub_numbers:
            why = f"the call target '{routine}' is not a subroutine of this program"
            if op is None:
                self.ctx.unsupported_at(span, why)
            else:
                self.ctx.unsupported(op, why)
            return None
        return self.ctx.sub_numbers[routine]

    def is_atom(self, value: ir.Expr, readable: bool = False, operation: bool = False,
                condition: bool = False) -> bool:
        """A value one Arcus statement can use as it is: a whole number, a variable, or a register
        readable where it stands (some only in an operation, some only in a condition)."""
        if isinstance(value, ir.Const):
            return float(value.value).is_integer()
        if isinstance(value, ir.Var):
            return True
        if isinstance(value, ir.DeviceRef):
            keyword = self.ctx.register(value)
            if keyword is None or not keyword.readable:
                return False
            return (readable or (operation and keyword.in_operation) or (condition and keyword.in_condition))
        return False

    def atom(self, value: ir.Expr) -> ir.Expr:
        if isinstance(value, ir.Const):
            return ir.Const(int(value.value), value.unit, value.span)
        if isinstance(value, ir.Var):
            return self.ctx.var(value)
        return value

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
        self.ctx.unsupported_at(span or getattr(value, "span", None), f"{what} has no Arcus form")

    def unsupported_cond(self, cond: ir.Cond) -> None:
        self.ctx.unsupported_at(getattr(cond, "span", None),
                                f"this condition ({type(cond).__name__}) has no Arcus form")

