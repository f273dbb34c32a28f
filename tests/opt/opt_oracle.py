"""The behavioural oracle of the optimizer tests: a small IR interpreter that records what a machine
and a host would see, and `same_behaviour`, the one comparison every test calls.

The simulator (`mcc.sim`, built in parallel) replaces `trace` here once merged: only this module
changes.

What is observable: every move, arc, slew, home, stop, wait, delay, output, print, native command,
handler installation and save, in order; each motion carries the motion settings in force (so a
setting removed because it was already in force leaves the trace unchanged, and one whose removal
would change a move does not); reads of the device (inputs, positions) are a fixed function of the
reading and of how many events came before, so two programs that do the same things in the same
order read the same values. Assignments are not events (a host reading variables is the
documented assumption of -O2's dead stores), nor are calls (outlining adds them).

Event handlers run before every motion (see `Machine.interrupt`).

A `*` axis setting is taken as a broadcast: it sets every axis (the stricter reading: a per-axis
setting after it is not redundant).
"""

from __future__ import annotations

import zlib

from mcc.compiler import ir

MASK = 0xFFFFFFFF


def wrap(value: int) -> int:
    value &= MASK
    return value - (1 << 32) if value & 0x80000000 else value


class Stop(Exception):
    pass


class Machine:
    def __init__(self, module: ir.Module, max_events: int = 200, max_steps: int = 5000):
        self.module = module
        self.vars: dict[str, int | float] = {}
        self.settings: dict[tuple, object] = {}
        self.events: list[tuple] = []
        self.max_events, self.max_steps = max_events, max_steps
        self.steps = 0
        self.depth = 0
        self.in_handler = False
        self.outcome = ""

    # -- values --------------------------------------------------------------------------------

    def event(self, *item) -> None:
        self.events.append(item)
        if len(self.events) >= self.max_events:
            raise Stop("events")

    def read(self, *what) -> int:
        return zlib.crc32(repr((what, len(self.events))).encode()) % 4

    def value(self, expr):
        if isinstance(expr, ir.Const):
            return expr.value
        if isinstance(expr, ir.Var):
            return self.vars.get(expr.name, 0)
        if isinstance(expr, ir.Status):
            return self.read(expr.meaning, expr.axis, expr.index)
        if isinstance(expr, ir.DeviceRef):
            return self.read(expr.name, expr.axis, expr.index)
        if isinstance(expr, (ir.Text, ir.LabelRef, ir.Pattern)):
            return repr(expr.value if isinstance(expr, ir.Text) else getattr(expr, "name", getattr(expr, "bits", "")))
        if isinstance(expr, ir.UnOp):
            a = self.value(expr.operand)
            if not isinstance(a, int):
                return 0
            return wrap(~a) if expr.op in ("~", "!") else wrap(-a)
        if isinstance(expr, ir.BinOp):
            a, b = self.value(expr.left), self.value(expr.right)
            if not (isinstance(a, (int, float)) and isinstance(b, (int, float))):
                return 0
            if expr.op in ("/", "%") and b == 0:
                return 0
            if isinstance(a, float) or isinstance(b, float):
                return {"+": a + b, "-": a - b, "*": a * b}.get(expr.op, 0.0) if expr.op != "/" else a / b
            table = {"+": lambda: a + b, "-": lambda: a - b, "*": lambda: a * b, "/": lambda: int(a / b),
                     "%": lambda: a - int(a / b) * b, "&": lambda: a & b, "|": lambda: a | b, "^": lambda: a ^ b,
                     "<<": lambda: a << (b & 31), ">>": lambda: a >> (b & 31)}
            return wrap(table[expr.op]()) if expr.op in table else 0
        if isinstance(expr, ir.Func):
            return 0
        if isinstance(expr, (ir.Compare, ir.Logic, ir.Not, ir.Truth, ir.InputMatch)):  # a condition as an argument
            return int(self.test(expr))
        raise TypeError(type(expr).__name__)

    def test(self, cond) -> bool:
        if isinstance(cond, ir.Compare):
            a, b = self.value(cond.left), self.value(cond.right)
            try:
                return {"=": a == b, "!=": a != b, "<": a < b, "<=": a <= b, ">": a > b, ">=": a >= b}[cond.op]
            except TypeError:
                return False
        if isinstance(cond, ir.Logic):
            left = self.test(cond.left)
            return (left and self.test(cond.right)) if cond.op == "and" else (left or self.test(cond.right))
        if isinstance(cond, ir.Not):
            return not self.test(cond.cond)
        if isinstance(cond, ir.Truth):
            return self.value(cond.expr) != 0
        if isinstance(cond, ir.InputMatch):
            return self.read("inputs", cond.pattern.bits) == 0
        raise TypeError(type(cond).__name__)

    # -- operations ----------------------------------------------------------------------------

    def set(self, slot: tuple, axis: str, value) -> None:
        if axis == ir.ALL_AXES:
            for known in [k for k in self.settings if k[0] == slot]:
                del self.settings[known]
        self.settings[(slot, axis)] = value

    def interrupt(self) -> None:
        """Event handlers run before every motion: a point every pass keeps (moves are never
        removed or reordered), so a pass that trusted a value a handler changes is caught."""
        if self.in_handler:
            return
        self.in_handler = True
        try:
            for routine in self.module.routines:
                if routine.kind is ir.RoutineKind.HANDLER:
                    self.routine(routine)
        finally:
            self.in_handler = False

    def motion(self, *item) -> None:
        self.interrupt()
        self.record_motion(*item)

    def record_motion(self, *item) -> None:
        """A motion event with the settings in force: per slot, an axis's own value only where it
        differs from the `*` value (so `*`=5 then X=5 is the same state as `*`=5 alone)."""
        state = {k: v for k, v in self.settings.items()
                 if k[1] == ir.ALL_AXES or self.settings.get((k[0], ir.ALL_AXES)) != v}
        self.event(*item, tuple(sorted(state.items(), key=repr)))

    def op(self, op) -> None:
        v = self.value
        if isinstance(op, ir.Assign):
            result = v(op.value)
            self.vars[op.target.name] = wrap(result) if isinstance(result, int) else result
        elif isinstance(op, ir.SetMotion):
            self.set((op.param.value,), op.axis, (v(op.value), getattr(op.value, "unit", None)))
        elif isinstance(op, ir.Setting):
            self.set(("setting", op.name, op.index), op.axis, (v(op.value), getattr(op.value, "unit", None)))
        elif isinstance(op, ir.Move):
            self.motion("move", op.mode.value, tuple((a, v(e)) for a, e in op.targets),
                        tuple((k, v(e)) for k, e in op.options))
        elif isinstance(op, ir.Arc):
            self.motion("arc", op.axes, tuple(v(c) for c in op.center), op.clockwise,
                        None if op.angle is None else v(op.angle))
        elif isinstance(op, ir.Slew):
            self.motion("slew", op.axis, None if op.velocity is None else v(op.velocity), op.direction)
        elif isinstance(op, ir.Home):
            self.motion("home", op.axis, op.method, op.direction, op.creep)
        elif isinstance(op, ir.Stop):
            self.event("stop", op.axis, op.ramp)
        elif isinstance(op, ir.SetPosition):
            self.event("position", op.axis, v(op.value))
        elif isinstance(op, ir.WaitMotion):
            self.event("wait", op.axis)
        elif isinstance(op, ir.Delay):
            self.event("delay", v(op.duration))
        elif isinstance(op, ir.SetOutput):
            self.event("out", op.index, v(op.value))
        elif isinstance(op, ir.WaitInput):
            while not self.test(op.cond):
                self.tick()
                self.event("poll")
        elif isinstance(op, ir.Print):
            self.event("print", tuple(v(e) for e in op.items), op.newline)
        elif isinstance(op, ir.DriveEnable):
            self.event("enable", op.axis, v(op.on))
        elif isinstance(op, ir.Call):
            if op.cond is None or self.test(op.cond):
                self.call(op.routine)
        elif isinstance(op, ir.SetHandler):
            self.event("handler", op.event, op.routine, tuple(v(a) for a in op.args))
        elif isinstance(op, ir.Save):
            self.event("save")
        elif isinstance(op, ir.Native) and op.dialect == "arcus" and op.mnemonic.upper() in ("ABS", "INC") \
                and not op.args:
            pass  # every move carries its resolved mode; the backend writes the fewest switches
        elif isinstance(op, ir.Native):
            self.event("native", op.mnemonic, op.axis, tuple(v(a) for a in op.args))
            self.vars.clear()  # its effect is not modelled: as if it could change any variable
        else:
            raise TypeError(type(op).__name__)

    # -- control -------------------------------------------------------------------------------

    def tick(self) -> None:
        self.steps += 1
        if self.steps > self.max_steps:
            raise Stop("steps")

    def call(self, name: str) -> None:
        routine = self.module.routine(name)
        if routine is None:
            self.event("external", name)
            return
        if self.depth > 50:
            raise Stop("depth")
        self.depth += 1
        try:
            self.routine(routine)
        finally:
            self.depth -= 1

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
            elif isinstance(term, ir.GotoRoutine):
                target = self.module.routine(term.routine)
                if target is None:
                    self.event("external", term.routine)
                    raise Stop("goto")
                routine, blocks = target, {b.label: b for b in target.blocks}
                block = target.blocks[0]
            else:  # Return, FallOff
                return

    def run(self) -> "Machine":
        starts = [r for r in self.module.routines if r.kind in (ir.RoutineKind.IMMEDIATE, ir.RoutineKind.POWERUP,
                                                                 ir.RoutineKind.MAIN)]
        try:
            for routine in starts:
                self.routine(routine)
            self.outcome = "end"
        except Stop as why:
            self.outcome = str(why)
        return self


def trace(module: ir.Module) -> tuple[str, list[tuple]]:
    """What running `module` shows: how it stopped and its events."""
    machine = Machine(module).run()
    return machine.outcome, machine.events


def same_behaviour(before: ir.Module, after: ir.Module) -> None:
    """Assert that `after` (an optimized copy) behaves as `before` does. A run cut short by the
    event limit compares the events both produced."""
    outcome_before, events_before = trace(before)
    outcome_after, events_after = trace(after)
    if "steps" in (outcome_before, outcome_after) or "depth" in (outcome_before, outcome_after):
        n = min(len(events_before), len(events_after))  # the step budget counts blocks, which passes merge
        assert events_after[:n] == events_before[:n]
        return
    assert (outcome_after, events_after) == (outcome_before, events_before)
