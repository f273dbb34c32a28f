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

import functools

from mcc.backends import int32
from mcc.backends.arcus import convert
from mcc.backends.arcus.context import Context
from mcc.backends.arcus.convert import Refused
from mcc.backends.arcus.target import DIALECT, HOME_KEYWORDS, MOTION_IR
from mcc.backends.structure import NEGATE, negate
from mcc.compiler import homing
from mcc.compiler import in_force, ir, units
from mcc.compiler.arcus import catalog as arcus_catalog
from mcc.compiler.span import Span

ARCUS_BINARY = {"+", "-", "*", "/", "%", "&", "|", "<<", ">>"}
COMPARE_SPELLING = {"==": "=", "<>": "!="}
CONSTANT_TESTS = {"=": lambda a, b: a == b, "!=": lambda a, b: a != b, "<": lambda a, b: a < b,
                  "<=": lambda a, b: a <= b, ">": lambda a, b: a > b, ">=": lambda a, b: a >= b}
POSITION_UNITS = frozenset({ir.Unit.NONE, ir.Unit.STEPS})  # what Arcus positions may be given in
RAMP_PARAMS = (ir.MotionParam.ACCEL_TIME, ir.MotionParam.DECEL_TIME, ir.MotionParam.ACCEL, ir.MotionParam.DECEL)
SPEED_PARAMS = (ir.MotionParam.MAX_SPEED, ir.MotionParam.INITIAL_SPEED)
MOTION_NAMES = {ir.MotionParam.MAX_SPEED: "HSPD", ir.MotionParam.INITIAL_SPEED: "LSPD"}
SPEED_NAMES = ("HSPD", "LSPD", "SSPD")
RAMP_TOLERANCE_MS = 1  # two ramp times this close are the same ACC (Arcus writes whole ms)
HANDLERS: dict[type, str] = {}  # operation class -> the name of its Legalizer method (op_<class>)


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
        self.source_ops: list[ir.Op] = []

    def run(self) -> ir.Routine:
        for block in self.routine.blocks:
            self.block = ir.Block(block.label, span=block.span, named=block.named)
            self.out.blocks.append(self.block)
            self.source_ops = block.ops
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
            kind = type(op)
            name = HANDLERS.get(kind)
            if name is None:
                name = HANDLERS[kind] = "op_" + kind.__name__.lower()
            handler = getattr(self, name, None)
            if handler is None:
                ctx.unsupported(op, f"{describe(op)} has no Arcus statement")
            else:
                handler(op)
        except Refused as refused:
            ctx.unsupported(op, str(refused))
        except Skip:
            pass
        temps.live = base

    def op_assign(self, op: ir.Assign) -> None:
        if self.ctx.module.dialect != DIALECT and (too_big := int32.overflow(self.ctx.module, op)):
            raise Refused(too_big)
        target = self.ctx.var(op.target)
        magnitude = signed_abs(op.value)
        if magnitude is not None:
            self.assign_abs(target, *magnitude, op.span)
            return
        self.assign(target, self.arcus(op.value), op.span)

    def assign_abs(self, target: ir.Var, inner: ir.Expr, negative: bool, span: Span | None) -> None:
        """target = abs(inner) (or -abs(inner), X150 H-/H+ on the distance, parker-x150.md L1854)
        without an abs function: target = inner, then IF target<0 (>0) target = target*-1 ENDIF
        (one operator per assignment, arcus-pmx-4ex-sa.txt L2671-L2677)."""
        value = self.arcus(inner)
        if not (isinstance(value, ir.Var) and self.ctx.var(value).name == target.name):
            self.assign(target, value, span)
        flip, after = self.new_block(span), self.new_block(span)
        self.test(ir.Compare(">" if negative else "<", target, ir.Const(0)), flip.label, after.label, span)
        self.block = flip
        self.assign(target, ir.BinOp("*", target, ir.Const(-1)), span)
        self.block.terminator = ir.Jump(after.label, span)
        self.block = after

    def op_setmotion(self, op: ir.SetMotion) -> None:
        param = op.param
        axis = self.axis(op.axis, op, setting=True)
        if param is ir.MotionParam.PROFILE:
            value = self.value(self.arcus(op.value), op)
            for letter in (self.ctx.config.axes if axis == ir.ALL_AXES else (axis,)):
                self.emit(ir.Native(DIALECT, f"SCV{letter}", (value,), "=", letter, op.span))
            return
        if param in RAMP_PARAMS:
            self.ramp(op, axis)
            return
        if param is ir.MotionParam.RESOLUTION and isinstance(op.value, ir.Const) \
                and op.value.value == self.ctx.module.steps_per_rev:
            # the steps the IR already counts in (X150 CUR, MCode MS): the output counts its pulses
            # in them too (the header's assumption), so the statement has nothing left to say
            raise Skip
        if MOTION_IR.get(param) is None:
            raise Refused(f"the {param.value.replace('_', ' ')} setting has no Arcus statement (Arcus has HSPD, LSPD, "
                          "ACC and SCV)")
        self.check_unit(op.value, ir.Unit.STEPS_PER_S, param.value.replace("_", " "))
        value = self.ranged(MOTION_NAMES[param], self.ctx.scale.rate(self.arcus(op.value)), op)
        self.emit(ir.SetMotion(param, axis, self.value(value, op), op.span))
        if param in SPEED_PARAMS:
            self.ramp_after_speed(op, axis)

    # ramps: Arcus has one ramp time (ACC, ms) for speeding up and slowing down ------------------------
    def state(self, op) -> dict:
        return self.ctx.in_force_before(op)

    def ramp(self, op: ir.SetMotion, axis: str) -> None:
        """ACC for a ramp time, or for an acceleration with the speeds in force (in_force.py)."""
        param = op.param
        state = self.ramp_state(op)
        if param in (ir.MotionParam.ACCEL_TIME, ir.MotionParam.DECEL_TIME):
            self.check_unit(op.value, ir.Unit.S, param.value.replace("_", " "))
            value = convert.ms(op.value, "ramp time") if isinstance(op.value, ir.Const) else \
                self.ms_value(op.value, op)
        else:
            self.check_unit(op.value, ir.Unit.STEPS_PER_S2, param.value)
            if not isinstance(op.value, ir.Const):
                raise Refused(f"the {param.value}eration is computed at run time and Arcus sets a ramp time (ACC, ms) "
                              "that depends on it and on the speeds: set it with a constant")
            ramp = ramp_ms(op.value.value, state, op.axis)
            if ramp is None:
                if self.speeds_follow(op):
                    return  # written when the speeds are set (ramp_after_speed), just below
                raise Refused(f"the {param.value}eration of {op.value.value:g} steps/s^2 is set with speeds that are "
                              "not known here, and Arcus sets a ramp time (ACC) that depends on them: set the "
                              "initial and maximum speeds before it (or just after it, before any move)")
            value = ir.Const(ramp, ir.Unit.NONE, op.value.span)
        if param in (ir.MotionParam.DECEL_TIME, ir.MotionParam.DECEL):
            up = accel_ramp_ms(state, op.axis)
            if isinstance(value, ir.Const) and up is not None and abs(up - value.value) <= RAMP_TOLERANCE_MS:
                return  # the ACC written for the acceleration already ramps down the same way
            if isinstance(value, ir.Var) and self.same_ramp_var(op, state):
                return
            raise Refused(f"the {param.value.replace('_', ' ')} differs from the acceleration ramp in force, and Arcus "
                          "ramps down in the same time it ramps up (one ACC): set both to the same ramp")
        self.emit(ir.SetMotion(ir.MotionParam.ACCEL, axis, self.value(value, op), op.span))

    def speeds_follow(self, op: ir.SetMotion) -> bool:
        """Both speeds are set to constants after `op` in its block, before anything else that moves,
        calls or ends it: the deferred ramp is then written with them (a join or a call would lose it)."""
        ops = self.source_ops
        index = next((i for i, o in enumerate(ops) if o is op), len(ops))
        fixed = in_force.FIXED.get(self.ctx.module.dialect, {})  # X150: the initial speed is always 0
        wanted = {p for p in (ir.MotionParam.INITIAL_SPEED, ir.MotionParam.MAX_SPEED) if (p, ir.ALL_AXES) not in fixed}
        for later in ops[index + 1:]:
            if isinstance(later, (ir.Move, ir.Arc, ir.Slew, ir.Home, ir.Call, ir.Native)):
                return False
            if isinstance(later, ir.SetMotion) and later.param in wanted and later.axis in (op.axis, ir.ALL_AXES) \
                    and isinstance(later.value, ir.Const):
                wanted.discard(later.param)
                if not wanted:
                    return True
        return False

    def ramp_state(self, op: ir.SetMotion) -> dict:
        """The settings in force before a ramp setting, as far as `ramp` reads them. A ramp time
        reads none, and a deceleration time just after an acceleration time of the same axis reads
        only the ramp time that operation set when no acceleration in steps/s^2 exists anywhere
        (the state the data flow would give has it under the same key): the program's data-flow
        analysis is not needed for the usual `ACC=n` of an Arcus program."""
        param = op.param
        if param is ir.MotionParam.ACCEL_TIME:
            return {}
        if param is ir.MotionParam.DECEL_TIME and not self.ctx.sets_accel:
            before = self.previous(op)
            if isinstance(before, ir.SetMotion) and before.param is ir.MotionParam.ACCEL_TIME \
                    and before.axis == op.axis and isinstance(before.value, ir.Const):
                return {(ir.MotionParam.ACCEL_TIME, op.axis): before.value}
        return self.state(op)

    def previous(self, op: ir.Op) -> ir.Op | None:
        """The operation just before `op` in its source block, if any."""
        ops = self.source_ops
        index = next((i for i, o in enumerate(ops) if o is op), None)
        return ops[index - 1] if index else None

    def same_ramp_var(self, op: ir.SetMotion, state: dict) -> bool:
        """DECEL_TIME = v*0.001 just after ACCEL_TIME = v*0.001 (how Arcus `ACC=V3` lowers)."""
        ops = self.source_ops
        index = next((i for i, o in enumerate(ops) if o is op), None)
        if not index:
            return False
        before = ops[index - 1]
        return isinstance(before, ir.SetMotion) and before.param is ir.MotionParam.ACCEL_TIME and \
            before.axis == op.axis and before.value == op.value

    def ramp_after_speed(self, op: ir.SetMotion, axis: str) -> None:
        """A speed changed while an acceleration in steps/s^2 is in force: the ramp time changes."""
        if not self.ctx.sets_accel:
            return  # no acceleration in steps/s^2 is ever in force
        state = dict(self.state(op))
        if lookup(state, ir.MotionParam.ACCEL, op.axis) is None:
            return
        state[(op.param, op.axis)] = op.value if isinstance(op.value, ir.Const) else None
        accel = lookup(state, ir.MotionParam.ACCEL, op.axis)
        ramp = ramp_ms(accel.value, state, op.axis) if isinstance(op.value, ir.Const) else None
        if ramp is None:
            partner = ir.MotionParam.INITIAL_SPEED if op.param is ir.MotionParam.MAX_SPEED else \
                ir.MotionParam.MAX_SPEED
            if lookup(state, partner, op.axis) is None:
                return  # the ramp is written once the other speed is set
            raise Refused(f"the speed changes while an acceleration of {accel.value:g} steps/s^2 is in force: Arcus "
                          "needs the ramp time (ACC) again, which depends on a speed computed at run time")
        self.emit(ir.SetMotion(ir.MotionParam.ACCEL, axis, ir.Const(ramp), op.span))

    def ranged(self, name: str, value: ir.Expr, op, index: int | None = None) -> ir.Expr:
        """A constant inside the range the PMX-4EX-SA accepts for `name` (catalog `range`): a speed
        just under the minimum (0 pulses/s) is written as the minimum with warning G005; anything
        else outside is refused. Ranges the catalog only warns about are left to the check."""
        if not isinstance(value, ir.Const):
            return value
        keyword = self.ctx.cat.lookup(name, index=index)
        bounds = keyword.range if keyword is not None else None
        if bounds is None or keyword.get("range_check", "error") != "error":
            return value
        low, high = bounds
        if low <= value.value <= high:
            return value
        if name in SPEED_NAMES and 0 <= value.value < low:
            self.ctx.diags.add("G005", self.ctx.span_of(op),
                               f"the speed {value.value:g} is below the PMX-4EX-SA's minimum of {low} pulse/s "
                               f"({name}): written as {low}")
            return ir.Const(low, value.unit, value.span)
        raise Refused(f"{value.value:g} is outside what the PMX-4EX-SA accepts for {name} ({low} to {high})")

    def ramp_known(self, op) -> None:
        """A move under an acceleration in steps/s^2 needs the speeds that make it a ramp time."""
        if not self.ctx.sets_accel:
            return  # no acceleration in steps/s^2 is ever in force
        state = self.state(op)
        for axis, _ in getattr(op, "targets", ()):
            if lookup(state, ir.MotionParam.ACCEL_TIME, axis) is not None:
                continue
            accel = lookup(state, ir.MotionParam.ACCEL, axis)
            if accel is not None and ramp_ms(accel.value, state, axis) is None:
                raise Refused(f"the move runs with an acceleration of {accel.value:g} steps/s^2 and speeds that are not "
                              "known here, and Arcus sets a ramp time (ACC) that depends on them: set the initial "
                              "and maximum speeds before the move")
            self.decel_known(state, axis)

    def decel_known(self, state: dict, axis: str) -> None:
        """A deceleration in force must ramp down in the ACC written for the acceleration: Arcus has
        one ramp time for both. A deceleration set while the speeds were unknown wrote nothing, so it
        is checked again at the move, with the speeds in force there."""
        if lookup(state, ir.MotionParam.DECEL_TIME, axis) is not None:
            return  # a ramp time: checked (or written) where it was set
        decel = lookup(state, ir.MotionParam.DECEL, axis)
        if decel is None:
            return
        down = ramp_ms(decel.value, state, axis)
        if down is None:
            raise Refused(f"the move runs with a deceleration of {decel.value:g} steps/s^2 and speeds that are not "
                          "known here, and Arcus sets a ramp time (ACC) that depends on them: set the initial "
                          "and maximum speeds before the move")
        up = accel_ramp_ms(state, axis)
        if up is None or abs(up - down) > RAMP_TOLERANCE_MS:
            raise Refused(f"the deceleration of {decel.value:g} steps/s^2 differs from the acceleration ramp in force, "
                          "and Arcus ramps down in the same time it ramps up (one ACC): set both to the same ramp")

    def ms_value(self, value: ir.Expr, op) -> ir.Expr:
        return self.value(convert.ms(self.arcus(value), "ramp time"), op)

    def check_unit(self, value: ir.Expr, unit: ir.Unit, what: str) -> None:
        if isinstance(value, ir.Const) and value.unit not in (unit, ir.Unit.NONE):
            raise Refused(f"the {what} is given in '{value.unit.value}', not in {unit.value} as the IR requires")

    def op_move(self, op: ir.Move) -> None:
        if op.mode not in (ir.MoveMode.ABSOLUTE, ir.MoveMode.RELATIVE):
            raise Refused("the move is in 'whatever mode is in force' and the source did not say which: Arcus "
                          "needs it absolute or relative")
        for _, value in op.targets:
            self.check_unit(value, ir.Unit.STEPS, "move target")
        self.ramp_known(op)
        targets = tuple((self.axis(axis, op), self.value(self.ctx.scale.steps(self.arcus(value)), op,
                                                         units=POSITION_UNITS))
                        for axis, value in op.targets)
        if op.options:
            self.ctx.unsupported(op, "move options (MCode MA p2/p3) have no Arcus form; the move is written "
                                     "without them", severity_note=True)
        self.emit(ir.Move(op.mode, targets, span=op.span))

    def op_arc(self, op: ir.Arc) -> None:
        if tuple(op.axes) != ("X", "Y"):
            self.ctx.unsupported(op, "Arcus ARC/CIR move the X and Y axes only")
            raise Skip
        center = tuple(self.literal(self.ctx.scale.steps(c), op, "ARC/CIR centre") for c in op.center)
        angle = None
        if op.angle is not None:
            self.check_unit(op.angle, ir.Unit.DEGREES, "ARC angle")
            if not isinstance(op.angle, ir.Const):
                self.literal(op.angle, op, "ARC angle")
            millidegrees = op.angle.value * 1000
            if abs(millidegrees - round(millidegrees)) > 1e-6:
                raise Refused(f"the arc angle {op.angle.value:g} degrees is not a whole number of 1/1000 degree")
            angle = ir.Const(round(millidegrees), ir.Unit.NONE, op.angle.span)
        self.emit(ir.Arc(op.axes, center, op.clockwise, angle, op.span))

    def op_slew(self, op: ir.Slew) -> None:
        if op.velocity is not None:
            self.slew_at(op)
            return
        if op.direction not in (1, -1):
            self.ctx.unsupported(op, "Arcus jogs at the current HSPD in a direction (JOGX+); a slew at a "
                                     "given velocity has no statement")
            raise Skip
        self.emit(ir.Slew(self.axis(op.axis, op), direction=op.direction, span=op.span))

    def slew_at(self, op: ir.Slew) -> None:
        """A slew at a constant velocity (MCode `SL v`: slew at v, accelerating at A, lexium-mcode.txt
        L5393-L5404) as JOG (arcus-pmx-4ex-sa.txt L2302-L2310: jogging "using current high speed, low
        speed, and acceleration"): HSPD = |v| and ACC the ramp from LSPD to |v| at the acceleration
        in force, then JOG in v's direction, then HSPD and ACC in force written back, so what moves
        after it keeps its speeds (the jog runs on at its own: a speed change while moving is SSPD's,
        "On-The-Fly Speed Change", L509-L533). Only where no motion can run (`ir.settled_ops`):
        changing a running motion's speed is an on-the-fly change. Refused when the velocity is computed at run time, not above
        the initial speed, or the acceleration, the speeds or the deceleration do not allow it."""
        velocity = op.velocity
        if not isinstance(velocity, ir.Const) or velocity.value == 0:
            raise Refused("Arcus jogs at HSPD (JOGX+): a slew at a velocity computed at run time has no statement")
        self.check_unit(velocity, ir.Unit.STEPS_PER_S, "slew velocity")
        others_move = any(isinstance(o, (ir.Move, ir.Arc, ir.Slew, ir.Home)) for r in self.ctx.module.routines
                          if r.kind is ir.RoutineKind.IMMEDIATE and r.name != self.routine.name
                          for b in r.blocks for o in b.ops)  # commands sent first may leave a move running
        if id(op) not in self.ctx.settled_ops or others_move:
            raise Refused("the slew may change the speed of a motion still running, which Arcus does on the fly only "
                          "(SSPD, within a speed window); wait for the motion to end (H) before the slew")
        state = dict(self.state(op))
        speed = abs(float(velocity.value))
        accel = lookup(state, ir.MotionParam.ACCEL, op.axis)
        initial = lookup(state, ir.MotionParam.INITIAL_SPEED, op.axis)
        top = lookup(state, ir.MotionParam.MAX_SPEED, op.axis)
        if accel is None or initial is None or top is None or lookup(state, ir.MotionParam.ACCEL_TIME, op.axis):
            raise Refused("Arcus jogs at HSPD with the ramp time ACC: the slew's acceleration and the speeds in force "
                          "are not known here (set the initial speed, maximum speed and acceleration with constants)")
        if speed <= max(float(initial.value), lowest_speed()):
            raise Refused(f"the slew at {speed:g} steps/s is not above the initial speed {float(initial.value):g}, "
                          "and Arcus jogs from LSPD up to HSPD")
        own = any((param, op.axis) in state for param in (*SPEED_PARAMS, ir.MotionParam.ACCEL))
        axis = self.axis(op.axis if own else ir.ALL_AXES, op, setting=True)
        jog = dict(state)
        jog[(ir.MotionParam.MAX_SPEED, op.axis if own else ir.ALL_AXES)] = ir.Const(speed, ir.Unit.STEPS_PER_S)
        jog[(ir.MotionParam.MAX_SPEED, op.axis)] = ir.Const(speed, ir.Unit.STEPS_PER_S)
        self.decel_known(jog, op.axis)
        ramp, back = ramp_ms(accel.value, jog, op.axis), ramp_ms(accel.value, state, op.axis)
        if ramp is None or back is None:
            raise Refused("Arcus jogs at HSPD with the ramp time ACC, which the slew's acceleration does not give here")
        changes = speed != float(top.value)
        if changes:
            hspd = self.ranged("HSPD", self.ctx.scale.rate(ir.Const(speed, ir.Unit.STEPS_PER_S)), op)
            self.emit(ir.SetMotion(ir.MotionParam.MAX_SPEED, axis, hspd, op.span))
            self.emit(ir.SetMotion(ir.MotionParam.ACCEL, axis, ir.Const(ramp), op.span))
        self.emit(ir.Slew(self.axis(op.axis, op), direction=1 if velocity.value > 0 else -1, span=op.span))
        if changes:
            hspd = self.ranged("HSPD", self.ctx.scale.rate(top), op)
            self.emit(ir.SetMotion(ir.MotionParam.MAX_SPEED, axis, hspd, op.span))
            self.emit(ir.SetMotion(ir.MotionParam.ACCEL, axis, ir.Const(back), op.span))

    def op_save(self, op: ir.Save) -> None:
        """A save sent as a command (MCode `S` after the final PG saves the program on load,
        lexium-mcode.txt L5250-L5263): the PMX-4EX-SA writes a standalone program to flash when it is
        downloaded (arcus-pmx-4ex-sa.txt L844, L1032), and the output sets what the source set before
        its program in the program itself, so nothing is left to save; written as nothing, with a
        warning. A save inside a program (it keeps values the run computed) stays refused, and so
        does an X150 `SV` for now: its stream's stretches of immediate commands are written as
        programs of their own, which the save would no longer keep from being written."""
        if self.routine.kind is not ir.RoutineKind.IMMEDIATE or self.ctx.module.dialect != "mcode":
            raise Refused("saving to non-volatile memory while the program runs has no Arcus statement (the "
                          "PMX-4EX-SA stores settings to flash from the PC only, STORE)")
        self.ctx.unsupported(op, "the save is left out: the PMX-4EX-SA writes the program to flash when it is "
                                 "downloaded (L844); store its settings to flash from the PC if it must keep them",
                             severity_note=True)
        raise Skip

    def op_home(self, op: ir.Home) -> None:
        modes = {int(k.get("home_mode")) for k in self.ctx.cat.keywords if k.ir == "home" and k.get("home_mode") is not None}
        if HOME_KEYWORDS.get(op.method) not in modes or op.direction not in (1, -1):
            self.ctx.unsupported(op, f"homing by '{op.method}' without a direction has no Arcus statement "
                                     "(HOME, ZHOME and ZOME home in + or - on the switch, switch+index or index)")
            raise Skip
        if op.speed is not None:  # X150 GH n
            self.ctx.unsupported(op, "homing at a speed of its own has no Arcus statement (HOME seeks at the high "
                                     "speed HSPD; set HSPD to that speed around the homing move in the source)")
            raise Skip
        refused = homing.refusal(op, self.ctx.profile, self.ctx.module.steps_per_rev)
        if refused:  # HOME zeroes at the switch and brakes past it (L662): another homing moves the zero
            self.ctx.unsupported(op, refused)
            raise Skip
        self.emit(homing.home_op(self.ctx.profile, self.ctx.profile.steps_per_rev, self.axis(op.axis, op), op.method,
                                 op.direction, op.span))

    def op_stop(self, op: ir.Stop) -> None:
        self.emit(ir.Stop(self.axis(op.axis, op, setting=True), op.ramp, op.span))

    def op_waitmotion(self, op: ir.WaitMotion) -> None:
        self.emit(ir.WaitMotion(self.axis(op.axis, op, setting=True), op.span))

    def op_delay(self, op: ir.Delay) -> None:
        self.check_unit(op.duration, ir.Unit.S, "delay")
        if not isinstance(op.duration, ir.Const):
            self.literal(op.duration, op, "DELAY")
        self.emit(ir.Delay(self.literal(self.ranged("DELAY", convert.ms(op.duration, "delay"), op), op, "DELAY"),
                           op.span))

    def op_setoutput(self, op: ir.SetOutput) -> None:
        if op.index is not None and not 1 <= op.index <= 8:
            self.ctx.unsupported(op, f"output {op.index}: the PMX-4EX-SA has DO1-DO8")
            raise Skip
        if isinstance(op.value, ir.Pattern):  # 0/1 set that output, X leaves it (output 1 first)
            bits = [(i + 1, int(b)) for i, b in enumerate(op.value.bits) if b in "01"]
            if any(index > 8 for index, _ in bits):
                raise Refused(f"the output pattern {op.value.bits} sets outputs beyond DO8")
            for index, bit in bits:
                self.emit(ir.SetOutput(index, ir.Const(bit), op.span))
            return
        value = self.ranged("DO", self.arcus(op.value), op, index=op.index)
        self.emit(ir.SetOutput(op.index, self.value(value, op), op.span))

    def op_setposition(self, op: ir.SetPosition) -> None:
        self.check_unit(op.value, ir.Unit.STEPS, "position")
        self.emit(ir.SetPosition(self.axis(op.axis, op), self.value(self.ctx.scale.steps(self.arcus(op.value)), op,
                                                                    units=POSITION_UNITS), op.span))

    def op_setting(self, op: ir.Setting) -> None:
        """A neutral setting the PMX-4EX-SA has, in its spelling; the others are refused by name."""
        ctx = self.ctx
        if ctx.input_setup.needs_none(op):
            raise Skip  # a home/limit/general line: the PMX-4EX-SA's own input, nothing to set up
        if op.name in ("output_function", "output_active_high") and op.index in ctx.plain_outputs:
            raise Skip  # a general output, active high: what DOn is (ctx.plain_outputs)
        if op.name in ("clear_error", "compare_output"):
            axis = self.axis(op.axis, op)
            on = isinstance(op.value, ir.Const) and op.value.value != 0
            if op.name == "clear_error":
                if not on:
                    raise Skip  # writing 0 clears nothing
                self.emit(ir.Native(DIALECT, f"ECLEAR{axis}", (), "", axis, op.span))
            elif isinstance(op.value, ir.Const):
                self.emit(ir.Native(DIALECT, f"SYN{axis}{'O' if on else 'F'}", (), "", axis, op.span))
            else:
                raise Refused("the position-compare output is switched by a value computed at run time; Arcus has "
                              "only SYN<axis>O and SYN<axis>F")
            return
        if op.name == "input_active_high" and op.index is not None:
            raise Refused(f"the program reads input {op.index} at a level of its own; the PMX-4EX-SA reads "
                          f"DI{op.index} as wired and sets no input level in a program (POX, from the host, sets "
                          "the home, alarm and limit polarity only, L700-L704)")
        if op.name not in convert.SETTINGS:
            raise Refused(f"the setting '{op.name}' has no Arcus statement")
        name, kind = convert.SETTINGS[op.name]
        keyword = ctx.cat.lookup(name)
        axis = self.axis(op.axis, op) if keyword.get("axis") == "required" else ""
        value = self.arcus(op.value)
        if kind == "steps":
            value = ctx.scale.steps(value)
        elif kind == "rate":
            value = ctx.scale.rate(value)
        elif kind == "ms":
            value = convert.ms(value, op.name.replace("_", " "))
        value = self.ranged(name, value, op)
        value = self.literal(value, op, name) if keyword.literal_only else self.value(value, op)
        self.emit(ir.Native(DIALECT, keyword.spell(axis), (value,), "=", axis, op.span))

    def op_driveenable(self, op: ir.DriveEnable) -> None:
        axis = self.axis(op.axis, op, setting=True)
        value = self.arcus(op.on)
        if axis == ir.ALL_AXES:
            if not isinstance(value, ir.Const):
                raise Refused("enabling every drive from a value computed at run time has no Arcus form")
            mask = (1 << len(self.ctx.config.axes)) - 1 if value.value else 0
            self.emit(ir.Native(DIALECT, "EO", (ir.Const(mask),), "=", "", op.span))
            return
        bit = convert.Axes.LETTERS.index(axis) + 1
        bits = self.ctx.cat.lookup("EO", index=bit)
        if bits is None or bits.index_range is None:
            # a product with one enable output and no EO<bit> (ACE-SDE p.31 §6.5): EO itself
            value = self.ranged("EO", value, op)
            self.emit(ir.Native(DIALECT, "EO", (self.value(value, op),), "=", "", op.span))
            return
        value = self.ranged("EO", value, op, index=bit)
        self.emit(ir.Native(DIALECT, f"EO{bit}", (self.value(value, op),), "=", "", op.span))

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
            self.ctx.unsupported(op, f"the {op.dialect} command {op.mnemonic or '(unnamed)'} has no counterpart "
                                     "on the PMX-4EX-SA")
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
        temp = self.ctx.temps.alloc(span)
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
                                         "pulses")
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
        try:
            cond = self.normal(self.arcus(cond))
        except Refused as refused:
            self.ctx.unsupported_at(span or getattr(cond, "span", None), str(refused))
            raise Skip from None
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
        flag = self.ctx.temps.alloc(span)
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
        if isinstance(cond, ir.InputMatch):
            return self.normal(input_match(cond))
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
        """An IR axis as the target's axis letter ("*" stays "*" for global settings and stops)."""
        ctx = self.ctx
        letter = ctx.axes.letter(axis)
        if letter == ir.ALL_AXES:
            return ir.ALL_AXES if setting else ctx.config.axes[0]
        if letter is None:
            raise Refused(f"axis '{axis}' has no axis left on the target: the program uses {ctx.axes.count} axes "
                          f"and the profile has {len(ctx.config.axes)} ({', '.join(ctx.config.axes)})")
        return letter

    # neutral readings as Arcus registers --------------------------------------------------------------
    def arcus(self, node):
        """An expression or condition with its neutral readings as Arcus registers (refused: Refused)."""
        if type(node) in LEAVES:
            return node  # a number or a variable: most values are
        if isinstance(node, ir.Status):
            letter = self.ctx.axes.letter(node.axis) if node.axis else ""
            if letter is None:
                raise Refused(f"axis '{node.axis}' of the reading '{node.meaning}' has no axis left on the target")
            found = convert.reading(node, letter)
            if found is None:
                where = f" of axis {node.axis}" if node.axis not in ("", ir.ALL_AXES) else ""
                index = f" {node.index}" if node.index is not None else ""
                raise Refused(f"the reading '{node.meaning}{index}'{where} has no Arcus register")
            return found
        if isinstance(node, ir.DeviceRef) and node.dialect != DIALECT:
            raise Refused(f"the {node.dialect} register {node.name} has no Arcus counterpart")
        if isinstance(node, ir.BinOp):
            register = convert.ms_register(node, lambda a: self.ctx.axes.letter(a) or "")
            if register is not None:
                return register
            return ir.BinOp(node.op, self.arcus(node.left), self.arcus(node.right), node.span)
        if isinstance(node, ir.UnOp):
            return ir.UnOp(node.op, self.arcus(node.operand), node.span)
        if isinstance(node, ir.Func):
            raise Refused(f"the function {node.name} has no Arcus form")
        if isinstance(node, ir.Compare):
            return ir.Compare(node.op, self.arcus(node.left), self.arcus(node.right), node.span)
        if isinstance(node, ir.Logic):
            return ir.Logic(node.op, self.arcus(node.left), self.arcus(node.right), node.span)
        if isinstance(node, ir.Not):
            return ir.Not(self.arcus(node.cond), node.span)
        if isinstance(node, ir.Truth):
            return ir.Truth(self.arcus(node.expr), node.span)
        return node

    def sub_number(self, routine: str, op, span: Span | None = None) -> int | None:
        if routine not in self.ctx.sub_numbers:
            why = f"the call target '{routine}' is not a subroutine of this program"
            if routine in self.ctx.module.externals:  # stored on the source's controller (an X150 sequence)
                why = (f"the call target '{routine}' is stored on the source's controller and not defined in this "
                       f"file (a converted program has only what the file defines: add the definition of "
                       f"{routine} to the file)")
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
            if type(value.value) is int:
                return value  # already a whole number (an IR value is never changed: share it)
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



LEAVES = (ir.Const, ir.Var)


def input_match(cond: ir.InputMatch) -> ir.Cond:
    """Inputs matching a 0/1/X pattern (input 1 first) as comparisons of DI bits joined by AND."""
    bits = [(i + 1, int(b)) for i, b in enumerate(cond.pattern.bits) if b in "01"]
    if any(index > 8 for index, _ in bits):
        raise Refused(f"the input pattern {cond.pattern.bits} tests inputs beyond DI8")
    tests: list[ir.Cond] = [ir.Compare("=", ir.DeviceRef(DIALECT, "DI", "input", "", index), ir.Const(bit), cond.span)
                            for index, bit in bits]
    if not tests:
        return ir.Compare("=", ir.Const(1), ir.Const(1), cond.span)
    result = tests[0]
    for test in tests[1:]:
        result = ir.Logic("and", result, test, cond.span)
    return result


def describe(op) -> str:
    """An operation as a user reads it in a refusal."""
    names = {"WaitInput": "waiting for an input", "Print": "printing", "SetHandler": "an event handler",
             "Save": "saving to non-volatile memory", "Slew": "a slew",
             "Pause": "pausing the program (the PMX-4EX-SA is paused from the PC only, SR=2, L1631)",
             "Resume": "resuming a paused program (the PC sends SR=3, L1634)",
             "Step": "a single step (the PMX-4EX-SA has no single-step mode)"}
    name = type(op).__name__
    if isinstance(op, ir.SetHandler):
        return f"an event handler (on {op.event})"
    return names.get(name, name)


def lookup(state: dict, param: ir.MotionParam, axis: str) -> ir.Const | None:
    found = state.get((param, axis))
    if found is None and axis != ir.ALL_AXES:
        found = state.get((param, ir.ALL_AXES))
    return found if isinstance(found, ir.Const) else None


def ramp_ms(accel: float, state: dict, axis: str) -> int | None:
    """The Arcus ramp time (whole ms, at least 1) of an acceleration with the speeds in force."""
    initial = lookup(state, ir.MotionParam.INITIAL_SPEED, axis)
    maximum = lookup(state, ir.MotionParam.MAX_SPEED, axis)
    if initial is None or maximum is None:
        return None
    # from the LSPD written: a start speed under the minimum is written as the minimum (`ranged`)
    low = max(initial.value, lowest_speed()) if initial.value >= 0 else initial.value
    ramp = units.ramp_from_accel(accel, low, maximum.value)
    if ramp is None:
        return None
    return max(1, round(units.s_to_ms(ramp)))


@functools.cache
def lowest_speed() -> float:
    """The lowest LSPD the PMX-4EX-SA accepts (catalog `range`)."""
    keyword = arcus_catalog.load().lookup("LSPD")
    bounds = keyword.range if keyword is not None else None
    return float(bounds[0]) if bounds else 0.0


def accel_ramp_ms(state: dict, axis: str) -> float | None:
    """The ramp time (ms) the acceleration in force gives: a ramp time, or an acceleration with speeds."""
    ramp = lookup(state, ir.MotionParam.ACCEL_TIME, axis)
    if ramp is not None:
        return units.s_to_ms(ramp.value)
    accel = lookup(state, ir.MotionParam.ACCEL, axis)
    return ramp_ms(accel.value, state, axis) if accel is not None else None


def signed_abs(value: ir.Expr) -> tuple[ir.Expr, bool] | None:
    """(x, negative) when `value` is abs(x) or -abs(x), else None."""
    negative = False
    if isinstance(value, ir.UnOp) and value.op == "-":
        value, negative = value.operand, True
    if isinstance(value, ir.Func) and value.name == "abs" and len(value.args) == 1:
        return value.args[0], negative
    return None
