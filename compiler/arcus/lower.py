"""Lowering an Arcus syntax tree to the shared IR, matching the block structure on the way.

An Arcus program is the main program, `END`, then `SUB n ... ENDSUB` blocks (L2071). The lowering
makes one MAIN routine ("main") and one SUBROUTINE routine per SUB ("SUB1", number 1); inside a
routine IF/ELSEIF/ELSE/ENDIF and WHILE/ENDWHILE become basic blocks joined by `Branch` and `Jump`
terminators; `END` is an `End` terminator, `ENDSUB` a `Return`, `GOSUB n` a `Call`.

Block structure is matched here with a stack, not by the grammar, so that a missing ENDIF is one
diagnostic naming both ends and the rest of the file is still lowered: a closer that does not
match the innermost open block closes the blocks above the one it matches (reported once), and
blocks left open at the end of the file are closed there.

Units and names (docs/dialects/arcus.md, "Lowering to the IR"): pulses are the IR's steps
(`Module.steps_per_rev` is the profile's, 0 when unknown: one pulse per step), speeds are steps/s,
`ACC` (a ramp time in ms, used for acceleration and deceleration) is `accel_time` and `decel_time`
in seconds, delays and timers are seconds. Registers read as neutral `Status` readings (`PX` is
position, `DI3` input 3, `MSTX` the motor status bits) and the settings other controllers could
share as `Setting`s (`ECLEARX` clear_error, `EO` enable_outputs, `SYNXP` compare_position, ...).

Moves: ABS and INC select the mode of later moves; the lowering resolves them by data flow
(`modes.py`) so that every `Move` is ABSOLUTE or RELATIVE, and the switches themselves leave the IR.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Callable

from mcc.compiler import cancel, ir, units
from mcc.compiler.arcus import modes
from mcc.compiler.arcus import syntax as st
from mcc.compiler.arcus.resolve import (ASSIGN, BARE, COLON, CONDITION, CONTROL, MOVE, NUMBERED, WRITE, Resolved,
                                        Resolver)
from mcc.compiler.diagnostics import Diagnostics
from mcc.compiler import homing
from mcc.compiler.profiles import Profile
from mcc.compiler.span import Span

DIALECT = "arcus"
UNITS = {"pps": ir.Unit.STEPS_PER_S, "pulses": ir.Unit.STEPS}
def axis_sets(profile: Profile) -> tuple[ir.MotionParam, ...]:
    """The IR parameters an Arcus axis uses its own values of only as a complete set (L447-L457)."""
    return tuple(ir.MotionParam(name) for name in profile.get("arcus.axis_sets", []) or [])


MOTION = {"max_speed": ir.MotionParam.MAX_SPEED, "initial_speed": ir.MotionParam.INITIAL_SPEED}
AXES = ("X", "Y", "Z", "U")
# Registers read as neutral readings: catalog name -> ir_names.STATUS meaning. EO<bit> is the
# enable of axis <bit> ("enabled"), the indexed DI/DO are "input"/"output" n.
READINGS = {"P": "position", "E": "encoder", "PS": "velocity", "MST": "motor_status", "DI": "inputs",
            "DO": "outputs", "EO": "enable_outputs", "HSPD": "max_speed", "LSPD": "initial_speed",
            "SCV": "profile", "SYNS": "compare_state"}
INDEXED_READINGS = {"DI": "input", "DO": "output"}
# Readings kept in the dialect's milliseconds by multiplying the neutral seconds back (`V1=TR` is
# V1 = countdown * 1000): the variable gets the number the Arcus program computed with.
MS_READINGS = {"TR": "countdown", "ACC": "accel_time"}
# Writes that become neutral settings: catalog name -> (ir_names.SETTINGS name, unit of the value).
SETTINGS = {"E": ("encoder_position", ir.Unit.STEPS), "SSPD": ("speed_change", ir.Unit.STEPS_PER_S),
            "SYNC": ("compare_condition", ir.Unit.NONE), "SYNP": ("compare_position", ir.Unit.STEPS),
            "SYNT": ("compare_pulse", ir.Unit.S), "TR": ("countdown", ir.Unit.S)}
# Bare actions that become a setting written with a fixed value.
ACTIONS = {"ECLEAR": ("clear_error", 1), "SYNO": ("compare_output", 1), "SYNF": ("compare_output", 0)}
HOME_METHODS = {0: "switch", 1: "limit", 2: "switch+index", 3: "index"}  # ASCII homing modes (L656-L680)
OPENERS = {"ENDIF": "IF", "ENDWHILE": "WHILE", "ENDSUB": "SUB"}
CLOSERS = {opener: closer for closer, opener in OPENERS.items()}


def sub_name(number: int) -> str:
    return f"SUB{number}"


@dataclass
class Frame:
    """An open IF, WHILE or SUB block."""

    kind: str  # IF | WHILE | SUB
    opener: Resolved
    join: ir.Block | None = None  # IF: the block after ENDIF; WHILE: the header
    pending: ir.Branch | None = None  # the branch whose false edge is not yet placed
    else_span: Span | None = None
    routine: ir.Routine | None = None  # SUB: the subroutine; the main block to resume is `resume`
    resume: ir.Block | None = None

    @property
    def span(self) -> Span:
        return self.opener.span


@dataclass
class Program:
    """What the whole-program checks need besides the IR."""

    subs: dict[int, Resolved] = field(default_factory=dict)
    calls: list[Resolved] = field(default_factory=list)
    end: Resolved | None = None  # the top-level END of the main program
    subs_before_end: list[Resolved] = field(default_factory=list)


# The method of `Lowering` that builds the operation of a statement, per catalog `ir` name (names,
# not bound methods kept on the instance: those would make each Lowering a reference cycle that
# only the garbage collector frees, with everything it holds).
BUILDERS: dict[str, str] = {
    "max_speed": "set_motion", "initial_speed": "set_motion", "accel": "set_ramp",
    "jog": "jog", "home": "home", "stop": "stop", "abort": "stop",
    "wait_motion": "wait", "delay": "delay", "outputs": "output", "output": "output",
    "position": "position", "assign": "assign", "move": "move", "arc": "arc",
    "circle": "arc",
}


class Lowering:
    def __init__(self, tree: st.SyntaxTree, profile: Profile, diags: Diagnostics):
        self.tree = tree
        self.profile = profile
        self.diags = diags
        self.resolver = Resolver(profile, diags)
        self.cat = self.resolver.cat
        # HSPDa, LSPDa and ACCa are used only once all three are set for the axis (L447-L457): the
        # profile's `arcus.axis_sets` (Module.axis_sets, docs/IR.md)
        self.module = ir.Module(DIALECT, profile.name, path=tree.path, steps_per_rev=profile.steps_per_rev,
                                axis_sets=axis_sets(profile))
        self.main = ir.Routine("main", ir.RoutineKind.MAIN)
        self.module.routines.append(self.main)
        self.program = Program()
        self.routine = self.main
        self.labels = 0
        self.block: ir.Block | None = self.new_block()
        self.stack: list[Frame] = []
        self.programs: dict[int, Resolved] = {}  # PRG n lines (products with several programs)
        self.current_program = 0
        self.dead_warned = False
        self.last_span: Span | None = None

    # driver ------------------------------------------------------------------------------------
    def run(self) -> ir.Module:
        for index, line in enumerate(self.tree.lines):
            cancel.every(index)  # the editor server abandons a stale analysis here
            if line.statement is None:
                if line.error and line.keyword in ("IF", "ELSEIF", "WHILE"):
                    self.statement(self.placeholder(line))  # keep the block structure around a bad line
                continue
            res = self.resolver.resolve(line)
            self.statement(res)
            self.last_span = res.span
        self.finish()
        self.tree.arc_modes = modes.resolve(self.module, self.profile, self.diags)
        return self.module

    def placeholder(self, line: st.Line) -> Resolved:
        """An IF/ELSEIF/WHILE line that did not parse, as a condition that is never checked (the file
        has a syntax error, so nothing is compiled): its ENDIF or ENDWHILE still has its opener."""
        span = line.span
        zero = st.Number("0", span)
        condition = st.Condition(st.Comparison("=", zero, zero, span), span)
        stmt = st.Conditional(line.keyword, span, condition, span)
        return Resolved(line, stmt, CONDITION, self.cat.lookup(line.keyword))

    def statement(self, res: Resolved) -> None:
        shape = res.shape
        if shape == CONDITION:
            {"IF": self.open_if, "ELSEIF": self.elseif, "WHILE": self.open_while}[res.stmt.keyword](res)
        elif shape == CONTROL:
            {"ELSE": self.else_, "ENDIF": self.close, "ENDWHILE": self.close, "ENDSUB": self.close,
             "END": self.end}[res.name](res)
        elif shape == NUMBERED:
            if res.name == "PRG":
                self.open_program(res)
            elif res.name == "SUB":
                self.open_sub(res)
            elif res.name == "GOSUB":
                self.program.calls.append(res)
                if res.valid:
                    self.emit(res, ir.Call(sub_name(res.number), span=res.span))
        elif shape in (MOVE, BARE, WRITE, ASSIGN, COLON):
            builder = getattr(self, BUILDERS.get(res.keyword.ir, "native"))
            self.emit(res, builder(res))

    # blocks ------------------------------------------------------------------------------------
    def new_block(self, span: Span | None = None) -> ir.Block:
        self.labels += 1
        block = ir.Block(f"%{self.labels}", span=span)
        self.routine.blocks.append(block)
        return block

    def current(self, res: Resolved) -> ir.Block:
        """The block to add to; after the top-level END, a new unreachable one (reported)."""
        if self.block is None:
            if not self.dead_warned:
                self.diags.add("A110", res.span, "this line is never executed: it follows END and is not in a SUB "
                                                 "(move it before END, or into a SUB ... ENDSUB)")
                self.dead_warned = True
            self.block = self.new_block(res.span)
        elif self.block.span is None:
            self.block.span = res.span
        return self.block

    def emit(self, res: Resolved, op: ir.Op | list[ir.Op] | None) -> None:
        block = self.current(res)
        if isinstance(op, list):
            block.ops.extend(op)
        elif op is not None:
            block.ops.append(op)

    def terminate(self, res: Resolved | None, term: ir.Terminator) -> None:
        if res is not None:
            block = self.current(res)
        elif self.block is None:
            return
        else:
            block = self.block
        if block.terminator is None:
            block.terminator = term

    # IF / ELSEIF / ELSE / ENDIF ------------------------------------------------------------------
    def cond(self, res: Resolved) -> ir.Cond:
        comp = res.stmt.condition.first
        return ir.Compare(comp.op, self.expr(comp.left), self.expr(comp.right), comp.span)

    def open_if(self, res: Resolved) -> None:
        branch = ir.Branch(self.cond(res), "", "", res.span)
        self.terminate(res, branch)
        then = self.new_block(res.span)
        branch.then = then.label
        self.stack.append(Frame("IF", res, join=ir.Block("", span=res.span), pending=branch))
        self.block = then

    def innermost_if(self, res: Resolved, what: str) -> Frame | None:
        """The IF an ELSE/ELSEIF belongs to, or None (reported)."""
        if self.stack and self.stack[-1].kind == "IF":
            return self.stack[-1]
        inner = next((f for f in reversed(self.stack) if f.kind == "IF"), None)
        if inner is None:
            self.diags.add("A112", res.span, f"{what} without IF: there is no open IF block here")
        else:
            top = self.stack[-1]
            self.diags.add("A113", res.span,
                           f"{what} belongs to the IF of line {inner.span.line}, but the {top.kind} of line "
                           f"{top.span.line} is still open: close it with {CLOSERS[top.kind]} first",
                           notes=(f"{top.span.label}: the {top.kind} opened here",
                                  f"{inner.span.label}: the IF opened here"))
        return None

    def join_label(self, frame: Frame) -> str:
        if not frame.join.label:
            self.labels += 1
            frame.join.label = f"%{self.labels}"
        return frame.join.label

    def elseif(self, res: Resolved) -> None:
        frame = self.innermost_if(res, "ELSEIF")
        if frame is None:
            return
        if frame.else_span is not None:
            self.diags.add("A114", res.span, f"ELSEIF after the ELSE of line {frame.else_span.line}: move it "
                                             "before the ELSE (ELSE is the last branch of an IF)",
                           notes=(f"{frame.else_span.label}: the ELSE is here",
                                  f"{frame.span.label}: the IF opened here"))
            return
        self.terminate(res, ir.Jump(self.join_label(frame), res.span))
        test = self.new_block(res.span)
        frame.pending.otherwise = test.label
        branch = ir.Branch(self.cond(res), "", "", res.span)
        test.terminator = branch
        self.block = self.new_block(res.span)
        branch.then = self.block.label
        frame.pending = branch

    def else_(self, res: Resolved) -> None:
        frame = self.innermost_if(res, "ELSE")
        if frame is None:
            return
        if frame.else_span is not None:
            self.diags.add("A114", res.span, f"a second ELSE in the IF of line {frame.span.line} (the first is at "
                                             f"line {frame.else_span.line}): an IF has at most one ELSE",
                           notes=(f"{frame.else_span.label}: the first ELSE is here",
                                  f"{frame.span.label}: the IF opened here"))
            return
        self.terminate(res, ir.Jump(self.join_label(frame), res.span))
        self.block = self.new_block(res.span)
        frame.pending.otherwise = self.block.label
        frame.pending = None
        frame.else_span = res.span

    def close_if(self, frame: Frame, span: Span) -> None:
        label = self.join_label(frame)
        self.terminate(None, ir.Jump(label, span))
        if frame.pending is not None:
            frame.pending.otherwise = label
        frame.join.span = span
        self.routine.blocks.append(frame.join)
        self.block = frame.join

    # WHILE / ENDWHILE ------------------------------------------------------------------------------
    def open_while(self, res: Resolved) -> None:
        header = self.new_block(res.span)
        self.terminate(res, ir.Jump(header.label, res.span))
        branch = ir.Branch(self.cond(res), "", "", res.span)
        header.terminator = branch
        body = self.new_block(res.span)
        branch.then = body.label
        self.stack.append(Frame("WHILE", res, join=header, pending=branch))
        self.block = body

    def close_while(self, frame: Frame, span: Span) -> None:
        self.terminate(None, ir.Jump(frame.join.label, span))
        self.block = self.new_block(span)
        frame.pending.otherwise = self.block.label

    # SUB / ENDSUB / END ------------------------------------------------------------------------------
    def open_sub(self, res: Resolved) -> None:
        if self.stack:
            outer = self.stack[0]
            self.diags.add("A115", res.span,
                           f"SUB inside the {outer.kind} of line {outer.span.line}: subroutines cannot be nested; "
                           f"close the {outer.kind} first and put subroutines after END",
                           notes=(f"{outer.span.label}: the {outer.kind} opened here",))
            while self.stack:
                self.close_frame(self.stack.pop(), res.span)
        number = res.number
        if res.valid and number in self.program.subs:
            first = self.program.subs[number]
            self.diags.add("A107", res.number_span or res.span,
                           f"SUB {number} is already defined at line {first.span.line}: give each subroutine its "
                           "own number", notes=(f"{first.span.label}: the first SUB {number}",))
        elif res.valid:
            self.program.subs[number] = res
        if self.program.end is None and res.valid:
            self.program.subs_before_end.append(res)
        name = sub_name(number) if res.valid and self.program.subs.get(number) is res else f"%SUB{number}.{self.labels}"
        routine = ir.Routine(name, ir.RoutineKind.SUBROUTINE, span=res.span, number=number)
        self.module.routines.append(routine)
        resume = self.block if self.program.end is None else None
        self.stack.append(Frame("SUB", res, routine=routine, resume=resume))
        self.routine = routine
        self.block = self.new_block(res.span)
        self.dead_warned = False

    def close_sub(self, frame: Frame, span: Span) -> None:
        self.terminate(None, ir.Return(span))
        self.routine = self.main
        self.block = frame.resume
        self.dead_warned = False

    def open_program(self, res: Resolved) -> None:
        """PRG n (products that run several programs at once, `[arcus] programs`): PRG 0 is the main
        program; each other program is a PROGRAM routine that runs beside it (docs/IR.md). Programs
        are top-level blocks, each ended by its END; the subroutines after the last END are shared."""
        if self.stack:
            outer = self.stack[0]
            self.diags.add("A115", res.span,
                           f"PRG inside the {outer.kind} of line {outer.span.line}: a program block starts at the top "
                           f"level; close the {outer.kind} first", notes=(f"{outer.span.label}: the {outer.kind} opened here",))
            while self.stack:
                self.close_frame(self.stack.pop(), res.span)
        number = res.number
        if res.valid and number in self.programs:
            first = self.programs[number]
            self.diags.add("A107", res.number_span or res.span,
                           f"PRG {number} is already defined at line {first.span.line}: give each program its own number",
                           notes=(f"{first.span.label}: the first PRG {number}",))
            res.valid = False
        if self.block is not None and self.routine.kind is ir.RoutineKind.PROGRAM or \
                (self.routine is self.main and self.block is not None and self.programs):
            open_one = next(iter(p for n, p in self.programs.items() if self.current_program == n), None)
            self.diags.add("A109", res.span,
                           f"PRG {number} starts before the END of program {self.current_program}: end each program "
                           "with END before the next PRG (2ED p.61, ACE p.74)",
                           notes=(f"{open_one.span.label}: program {self.current_program} starts here",)
                           if open_one is not None else ())
            self.terminate(res, ir.End(res.span))
        if res.valid:
            self.programs[number] = res
            self.current_program = number
            if number == 0 and self.program.end is None:
                return  # the main program: the statements before its END
        # a bad or repeated number still opens a program, so that its lines are read as one (no A110)
        name = f"PRG{number}" if res.valid else f"%PRG{number}.{self.labels}"
        routine = ir.Routine(name, ir.RoutineKind.PROGRAM, span=res.span, number=number)
        self.module.routines.append(routine)
        self.routine = routine
        self.block = self.new_block(res.span)
        self.dead_warned = False

    def end(self, res: Resolved) -> None:
        self.terminate(res, ir.End(res.span))
        if not self.stack and self.routine.kind is ir.RoutineKind.PROGRAM:
            self.block = None
            self.routine = self.main
        elif not self.stack and self.routine is self.main:
            if self.program.end is None:
                self.program.end = res
            self.block = None
        else:
            self.block = self.new_block(res.span)  # unreachable until the enclosing block closes

    # closing blocks ------------------------------------------------------------------------------------
    def close(self, res: Resolved) -> None:
        kind = OPENERS[res.name]
        position = next((i for i in range(len(self.stack) - 1, -1, -1) if self.stack[i].kind == kind), None)
        if position is None:
            if self.stack:  # e.g. ENDWHILE while only an IF is open: name the block that is open
                top = self.stack[-1]
                self.diags.add("A112", res.span,
                               f"{res.name} without {kind}: the block open here is the {top.kind} of line "
                               f"{top.span.line}, closed by {CLOSERS[top.kind]}",
                               notes=(f"{top.span.label}: the {top.kind} opened here",))
            else:
                self.diags.add("A112", res.span, f"{res.name} without {kind}: there is no open {kind} block here")
            return
        if position != len(self.stack) - 1:
            top = self.stack[-1]
            opener = self.stack[position]
            self.diags.add("A113", res.span,
                           f"{res.name} closes the {kind} of line {opener.span.line}, but the {top.kind} of line "
                           f"{top.span.line} is still open: add {CLOSERS[top.kind]} before this line",
                           notes=(f"{top.span.label}: the {top.kind} opened here",
                                  f"{opener.span.label}: the {kind} opened here"))
            while len(self.stack) - 1 > position:
                self.close_frame(self.stack.pop(), res.span)
        self.close_frame(self.stack.pop(), res.span)

    def close_frame(self, frame: Frame, span: Span) -> None:
        if frame.kind == "IF":
            self.close_if(frame, span)
        elif frame.kind == "WHILE":
            self.close_while(frame, span)
        else:
            self.close_sub(frame, span)

    def finish(self) -> None:
        end_span = self.last_span
        while self.stack:
            frame = self.stack.pop()
            closer = CLOSERS[frame.kind]
            self.diags.add("A111", frame.opener.stmt.span if frame.kind != "SUB" else frame.span,
                           f"this {frame.kind} is never closed: add {closer} where the block ends",
                           notes=(f"{end_span.label if end_span else frame.span.label}: the file ends here",))
            self.close_frame(frame, end_span or frame.span)
        if self.block is not None and self.block.terminator is None:
            self.block.terminator = ir.FallOff(self.last_span)
        for routine in self.module.routines:
            for block in routine.blocks:
                if block.terminator is None:
                    block.terminator = ir.FallOff(block.span) if routine.kind is ir.RoutineKind.MAIN \
                        else ir.Return(block.span)
        self.main.span = self.main.blocks[0].span if self.main.blocks else None
        program = self.program
        if program.end is not None:
            for res in program.subs_before_end:
                self.diags.add("A108", res.span,
                               f"SUB {res.number} comes before the END of line {program.end.span.line}: the main "
                               "program would run into it; move the subroutines after END (L2071)",
                               notes=(f"{program.end.span.label}: END is here",))
        elif program.subs_before_end:
            first = program.subs_before_end[0]
            self.diags.add("A109", first.span,
                           "the program has subroutines but no END: the main program runs on into SUB "
                           f"{first.number}; add END before the first SUB (L2071)")

    # operations ------------------------------------------------------------------------------------
    def axis(self, res: Resolved) -> str:
        """The axis letter written, "*" for the global form of a setting (HSPD), else ""."""
        return res.match.axis or (ir.ALL_AXES if res.keyword.axis == "optional" else "")

    def unit(self, res: Resolved) -> ir.Unit:
        return UNITS.get(res.keyword.unit, ir.Unit.NONE)

    def set_motion(self, res: Resolved) -> ir.Op:
        return ir.SetMotion(MOTION[res.keyword.ir], self.axis(res), self.expr(res.value, self.unit(res)), res.span)

    def set_ramp(self, res: Resolved) -> list[ir.Op]:
        """ACC is one ramp time for speeding up and slowing down (L1789-L1805): both IR ramp times."""
        value = self.seconds(self.expr(res.value))
        return [ir.SetMotion(param, self.axis(res), value, res.span)
                for param in (ir.MotionParam.ACCEL_TIME, ir.MotionParam.DECEL_TIME)]

    @staticmethod
    def seconds(value: ir.Expr) -> ir.Expr:
        """A value written in ms as seconds: a literal converted, a variable scaled by 0.001."""
        if isinstance(value, ir.Const):
            return ir.Const(units.ms_to_s(value.value), ir.Unit.S, value.span)
        return ir.BinOp("*", value, ir.Const(1 / units.MS_PER_S), value.span if hasattr(value, "span") else None)

    def jog(self, res: Resolved) -> ir.Op:
        return ir.Slew(res.match.axis, direction=res.match.direction, span=res.span)

    def home(self, res: Resolved) -> ir.Op:
        method = HOME_METHODS.get(int(res.keyword.get("home_mode", 0)), "switch")
        return homing.home_op(self.profile, self.module.steps_per_rev, res.match.axis, method, res.match.direction,
                              res.span)

    def stop(self, res: Resolved) -> ir.Op:
        return ir.Stop(res.match.axis or ir.ALL_AXES, ramp=res.keyword.ir == "stop", span=res.span)

    def wait(self, res: Resolved) -> ir.Op:
        return ir.WaitMotion(res.match.axis, res.span)

    def delay(self, res: Resolved) -> ir.Op:
        return ir.Delay(self.seconds(self.expr(res.value)), res.span)

    def output(self, res: Resolved) -> ir.Op:
        return ir.SetOutput(res.match.index, self.expr(res.value), res.span)

    def position(self, res: Resolved) -> ir.Op:
        return ir.SetPosition(res.match.axis, self.expr(res.value, ir.Unit.STEPS), res.span)

    def assign(self, res: Resolved) -> ir.Op:
        target = res.stmt.target
        return ir.Assign(self.variable(res.spelled, target.span), self.expr(res.value), res.span)

    def move(self, res: Resolved) -> ir.Op:
        targets = tuple((t.axis, self.expr(t.value, ir.Unit.STEPS)) for t in res.targets)
        return ir.Move(ir.MoveMode.MODAL, targets, span=res.span)

    def arc(self, res: Resolved) -> ir.Op:
        values = [ir.Const(n.value, ir.Unit.STEPS, n.span) for n in res.operands]
        angle = None
        if res.keyword.ir == "arc":
            angle = ir.Const(res.operands[2].value / 1000, ir.Unit.DEGREES, res.operands[2].span)
        axes = tuple(self.cat.limit("axes.arc_circle_axes", ["X", "Y"]))
        return ir.Arc((axes[0], axes[1]), (values[0], values[1]), clockwise=res.match.suffix == "P", angle=angle,
                      span=res.span)

    def native(self, res: Resolved) -> ir.Op:
        """A keyword with no builder: a neutral setting when it has a meaning others could share,
        else Native (ABS/INC only until the move modes are resolved, then they leave the IR)."""
        name, axis = res.keyword.name, res.match.axis
        if name in SETTINGS and res.shape == WRITE:
            setting, unit = SETTINGS[name]
            value = self.expr(res.value, unit)
            if unit is ir.Unit.S:
                value = self.seconds(self.expr(res.value))
            return ir.Setting(setting, axis, value, res.span)
        if name in ACTIONS and res.shape == BARE:
            setting, value = ACTIONS[name]
            return ir.Setting(setting, axis, ir.Const(value), res.span)
        if name == "SCV" and res.shape == WRITE:
            return ir.SetMotion(ir.MotionParam.PROFILE, axis, self.expr(res.value), res.span)
        if name == "EO" and res.shape == WRITE:
            if res.match.index is not None and 1 <= res.match.index <= len(AXES):
                return ir.DriveEnable(AXES[res.match.index - 1], self.expr(res.value), res.span)
            if self.profile.get("arcus.enable_outputs", "outputs") == "drive":
                return self.drive_enables(res)
            return ir.Setting("enable_outputs", ir.ALL_AXES, self.expr(res.value), res.span)
        args: tuple = ()
        if res.shape == WRITE:
            args = (self.expr(res.value, self.unit(res)),)
        return ir.Native(DIALECT, res.spelled, args, form="=" if res.shape == WRITE else "",
                         axis=res.match.axis, span=res.span)

    def drive_enables(self, res: Resolved) -> list[ir.Op]:
        """EO=<value> where each enable output switches one axis's motor current (profile `[arcus]
        enable_outputs = "drive"`: PMX-2ED-SA p.26 §7.5, Table 7.1; ACE-SDE p.31 §6.5): a drive
        enable per axis of the product, bit 0 the first axis. A number gives each axis its bit; a
        variable gives a single axis its value, and each of several axes its bit ((V & 2^i) / 2^i)."""
        axes = tuple(a for a in self.profile.axes if a in AXES) or AXES
        value = self.expr(res.value)
        out: list[ir.Op] = []
        for bit, axis in enumerate(axes):
            if isinstance(value, ir.Const):
                on: ir.Expr = ir.Const((int(value.value) >> bit) & 1, ir.Unit.NONE, value.span)
            elif len(axes) == 1:
                on = value
            else:
                on = ir.BinOp("/", ir.BinOp("&", value, ir.Const(1 << bit), res.span), ir.Const(1 << bit), res.span)
            out.append(ir.DriveEnable(axis, on, res.span))
        return out

    # expressions -------------------------------------------------------------------------------------
    def variable(self, name: str, span: Span) -> ir.Var:
        if name not in self.module.variables:
            self.module.variables[name] = ir.Variable(name, ir.VarType.INT32, span=span)
        return ir.Var(name, span)

    def expr(self, node: st.Node, unit: ir.Unit = ir.Unit.NONE) -> ir.Expr:
        if isinstance(node, st.Number):
            return ir.Const(node.value, unit, node.span)
        if isinstance(node, st.Ref):
            info = self.resolver.ref(node)
            if info is None:
                return ir.DeviceRef(DIALECT, node.part.key, span=node.span)
            if info.is_variable:
                return self.variable(info.spelled, node.span)
            keyword, match = info.keyword, info.match
            axis = match.axis or (ir.ALL_AXES if keyword.axis == "optional" else "")
            if keyword.get("neutral", True) is False:  # the product's register means something else (MST bits)
                return ir.DeviceRef(DIALECT, keyword.name, keyword.ir, axis, match.index, node.span)
            return self.reading(keyword.name, axis, match.index, node.span) or \
                ir.DeviceRef(DIALECT, keyword.name, keyword.ir, axis, match.index, node.span)
        if isinstance(node, st.Unary):
            return ir.UnOp("~" if node.op == "~" else node.op, self.expr(node.operand), node.span)
        if isinstance(node, st.Binary):
            return ir.BinOp(node.op, self.expr(node.left), self.expr(node.right), node.span)
        raise TypeError(f"unexpected node {type(node).__name__}")

    def reading(self, name: str, axis: str, index: int | None, span: Span) -> ir.Expr | None:
        """A register read as a neutral reading (None: the register has none)."""
        if index is not None and name in INDEXED_READINGS:
            return ir.Status(INDEXED_READINGS[name], "", index, span)
        if name == "EO" and index is not None:
            return ir.Status("enabled", AXES[index - 1], None, span) if 1 <= index <= len(AXES) else None
        if name in READINGS:
            return ir.Status(READINGS[name], axis, None, span)
        if name in MS_READINGS:
            status = ir.Status(MS_READINGS[name], axis, None, span)
            return ir.BinOp("*", status, ir.Const(units.MS_PER_S), span)
        return None
