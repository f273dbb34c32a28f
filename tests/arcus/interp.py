"""A tiny interpreter of the IR, for the Arcus tests only: it runs a module and records what the
machine would see (moves with their resolved mode, outputs, delays, waits, calls' effects) so that
a program and its compiled Arcus form can be compared by behaviour, not by text.

Device reads return a value fixed by the register and the number of events so far, so two programs
that do the same things in the same order read the same inputs however often they poll.
"""

from __future__ import annotations

from mcc.compiler import ir

MASK = 0xFFFFFFFF


def wrap(value: int) -> int:
    value &= MASK
    return value - (1 << 32) if value & 0x80000000 else value


class Stop(Exception):
    pass


class Machine:
    def __init__(self, module: ir.Module, max_events: int = 60, max_steps: int = 3000):
        self.module = module
        self.vars: dict[str, int] = {}
        self.events: list[tuple] = []
        self.mode = "?"
        self.max_events = max_events
        self.max_steps = max_steps
        self.steps = 0
        self.outcome = ""

    def event(self, *item) -> None:
        self.events.append(item)
        if len(self.events) >= self.max_events:
            raise Stop("events")

    def read(self, ref: ir.DeviceRef | ir.Status) -> int:
        """A device reading, the same for an Arcus register and its neutral meaning (DI3, input 3)."""
        return hash((ref.meaning, ref.axis, ref.index, len(self.events))) % 4

    def seconds(self, expr) -> float:
        """A value that may be fractional (seconds, a ramp time): constants keep their fraction."""
        if isinstance(expr, ir.Const):
            return float(expr.value)
        if isinstance(expr, ir.BinOp) and expr.op == "*" and isinstance(expr.right, ir.Const):
            return self.seconds(expr.left) * float(expr.right.value)
        return float(self.value(expr))

    def value(self, expr) -> int:
        if isinstance(expr, ir.Const):
            return int(round(expr.value)) if isinstance(expr.value, float) else int(expr.value)
        if isinstance(expr, ir.Var):
            return self.vars.get(expr.name.upper(), 0)
        if isinstance(expr, (ir.DeviceRef, ir.Status)):
            return self.read(expr)
        if isinstance(expr, ir.UnOp):
            operand = self.value(expr.operand)
            return wrap(~operand) if expr.op in ("~", "!") else wrap(-operand)
        if isinstance(expr, ir.BinOp):
            a, b = self.value(expr.left), self.value(expr.right)
            op = expr.op
            if op in ("/", "%") and b == 0:
                return 0
            result = {"+": lambda: a + b, "-": lambda: a - b, "*": lambda: a * b,
                      "/": lambda: int(a / b), "%": lambda: a - int(a / b) * b, "&": lambda: a & b,
                      "|": lambda: a | b, "<<": lambda: a << (b & 31), ">>": lambda: a >> (b & 31)}[op]()
            return wrap(result)
        raise TypeError(type(expr).__name__)

    def test(self, cond) -> bool:
        if isinstance(cond, ir.Compare):
            a, b = self.value(cond.left), self.value(cond.right)
            return {"=": a == b, "!=": a != b, "<": a < b, "<=": a <= b, ">": a > b, ">=": a >= b}[cond.op]
        if isinstance(cond, ir.Logic):
            return self.test(cond.left) and self.test(cond.right) if cond.op == "and" else \
                self.test(cond.left) or self.test(cond.right)
        if isinstance(cond, ir.Not):
            return not self.test(cond.cond)
        if isinstance(cond, ir.Truth):
            return self.value(cond.expr) != 0
        raise TypeError(type(cond).__name__)

    def op(self, op) -> None:
        if isinstance(op, ir.Assign):
            self.vars[op.target.name.upper()] = wrap(self.value(op.value))
        elif isinstance(op, ir.Move):
            mode = {"absolute": "ABS", "relative": "INC"}.get(op.mode.value, self.mode)
            self.event("move", mode, tuple((a, self.value(v)) for a, v in op.targets))
        elif isinstance(op, ir.Native) and op.mnemonic.upper() in ("ABS", "INC") and not op.args:
            self.mode = op.mnemonic.upper()
        elif isinstance(op, ir.Native):
            self.event("native", op.mnemonic.upper(), tuple(self.value(a) for a in op.args))
        elif isinstance(op, ir.SetOutput):
            self.event("out", op.index, self.value(op.value))
        elif isinstance(op, ir.Delay):
            self.event("delay", round(self.seconds(op.duration), 3))
        elif isinstance(op, ir.WaitMotion):
            self.event("wait", op.axis)
        elif isinstance(op, ir.SetMotion):
            self.event("set", op.param.value, op.axis, round(self.seconds(op.value), 6))
        elif isinstance(op, ir.Setting):
            self.event("setting", op.name, op.axis, round(self.seconds(op.value), 6))
        elif isinstance(op, ir.DriveEnable):
            self.event("enable", op.axis, self.value(op.on))
        elif isinstance(op, ir.Call):
            if op.cond is None or self.test(op.cond):
                self.call(op.routine)
        elif isinstance(op, ir.WaitInput):
            while not self.test(op.cond):
                self.tick()
        else:
            self.event(type(op).__name__)

    def tick(self) -> None:
        self.steps += 1
        if self.steps > self.max_steps:
            raise Stop("steps")

    def call(self, name: str) -> None:
        routine = self.module.routine(name)
        if routine is None:
            raise Stop("bad call")
        self.routine(routine)

    def routine(self, routine: ir.Routine) -> None:
        blocks = {b.label: b for b in routine.blocks}
        block = routine.blocks[0] if routine.blocks else None
        while block is not None:
            self.tick()
            for op in block.ops:
                self.op(op)
            term = block.terminator
            if isinstance(term, ir.Jump):
                block = blocks[term.target]
            elif isinstance(term, ir.Branch):
                block = blocks[term.then if self.test(term.cond) else term.otherwise]
            elif isinstance(term, ir.End):
                raise Stop("end")
            else:
                return

    def run(self) -> "Machine":
        main = next((r for r in self.module.routines if r.kind is ir.RoutineKind.MAIN), None)
        try:
            if main is not None:
                self.routine(main)
            self.outcome = "end"
        except Stop as why:
            self.outcome = str(why)
        return self
