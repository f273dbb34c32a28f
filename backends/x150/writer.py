"""Writing IR as X150 command text: the canonical form of the X150 backend.

The canonical form (docs/dialects/x150.md, "Backend"): upper case, one command per line, no spaces
inside a command (`GOTO2` is written `XG2`, `1OUTLXX10X1`), the device address in front, the `B`
prefix on immediate `*` commands stored in a sequence, no comments (a program of another dialect
gets a comment block at the top that states the assumptions of the conversion). Each sequence is
written `XEn XDn ... XT`.

What the writer converts (docs/CROSS.md, "into x150"):

- units: positions from the source's steps (`Module.steps_per_rev`) into the target's user steps
  (the resolution the program sets with CUR, else the profile's `steps_per_rev`), refused when a
  position falls between two target steps; speeds into rev/s and accelerations into rev/s²,
  rounded to 0.0001; a ramp time into an acceleration with the speeds in force
  (`mcc.compiler.in_force`);
- moves: `D<n>` + `G` with the fewest MPA/MPI and MN/MC switches (a slew is `MC H± G`);
- control flow: rebuilt with the structurer every backend shares (`mcc.backends.structure`):
  IF..ELSE..NIF, WHILE..NWHILE, REPEAT..UNTIL, and `Ln..N` for the X150 counted loops;
- axes: an X150 program keeps its device addresses; another dialect's axes map in order onto the
  profile's axes, and a program with more axes than the profile is refused at the first command
  that needs the extra one.
"""

from __future__ import annotations

import dataclasses
import math
import re
from dataclasses import dataclass, field
from fractions import Fraction

from mcc.backends import enable_outputs, resolution
from mcc.backends.input_setup import InputSetup
from mcc.backends.structure import EndNode, IfNode, RepeatNode, Simple, WhileNode, structure
from mcc.compiler.x150 import naming, neutral
from mcc.compiler import homing
from mcc.compiler import ir, ir_names, units
from mcc.compiler.diagnostics import Diagnostics
from mcc.compiler import in_force
from mcc.compiler.in_force import InForce, lookup
from mcc.compiler.profiles import Profile
from mcc.compiler.span import Span
from mcc.compiler.x150 import catalog as cat

DIALECT = "x150"
# the home and limit switches are inputs of their own ("the HOME input", parker-x150.md L3841)
DEDICATED_INPUTS = frozenset({"home", "limit_plus", "limit_minus"})
HANDLER_COMMANDS = {"power": "XP", "fault": "XFK", "when": "XWHEN"}
ARITHMETIC = "+-*/"
MAX_CONDITION_NODES = 32  # far above any writable condition; bounds the work on odd input
LOOP_PREFIX = "%L"  # the X150 frontend's hidden L-loop counters (written as Ln .. N)
DISTANCE = "%D"  # the X150 frontend's distance register per device (written as D, H, H+, H-)
HIDDEN = (LOOP_PREFIX, DISTANCE)
RATE_STEP = 0.0001  # rev/s and rev/s^2 are written to four decimals (V's smallest value, L4542)
READINGS = {"position": "POS", "encoder": "ABS"}  # neutral readings an X150 chain can read (L4591-L4592)
STOPS = (ir.End, ir.GotoRoutine, ir.Return)  # terminators written in place: HALT, XG, XRT
MODE_COMMANDS = {"MPA", "MPI", "MN", "MC", "MQ", "D", "H", "H+", "H-"}


def number(value) -> str:
    """A number as the controller reads it: integers plain, decimals shortest, E notation (L152-L161)."""
    if isinstance(value, bool):
        value = int(value)
    if isinstance(value, Fraction):
        value = int(value) if value.denominator == 1 else float(value)
    if isinstance(value, int):
        return str(value)
    if not math.isfinite(value):
        return repr(value)
    if value == int(value) and abs(value) < 1e15:
        return str(int(value))
    text = repr(float(value))
    if "e" in text:
        mantissa, exponent = text.split("e")
        return f"{mantissa}E{exponent}"
    return text


RATE_MNEMONICS = {"speed": "V", "acceleration": "A"}  # the catalog entries that bound rate()
SETTING_RATES = {ir.Unit.STEPS_PER_S: ("speed", "rev/s"), ir.Unit.STEPS_PER_S2: ("acceleration", "rev/s^2")}


@dataclass
class Line:
    text: str
    sources: tuple[Span, ...] = ()
    sequence: str | None = None  # the routine whose stored body this line belongs to (XD excluded)


@dataclass
class Written:
    lines: list[Line] = field(default_factory=list)
    diagnostics: Diagnostics = field(default_factory=Diagnostics)
    sequence_bytes: dict[str, int] = field(default_factory=dict)  # routine -> bytes stored
    header: list[str] = field(default_factory=list)  # the assumptions of a cross-dialect conversion


class CannotWrite(Exception):
    def __init__(self, message: str, code: str = "X202"):
        super().__init__(message)
        self.message = message
        self.code = code


State = dict  # ("pos"|"move"|"D", axis) -> the mode or D text known to be in force
# s: how much later a move may end on X150, which starts it from standstill, than in a source that
# starts it at its initial speed (one tick, the validation's time resolution; profile `[x150]
# start_speed_drift`)
START_SPEED_DRIFT = 0.001


def meet(a: State, b: State) -> State:
    return {k: v for k, v in a.items() if b.get(k) == v}


def register_direction(value) -> int | None:
    """The sign an H+ (abs, 1) or H- (minus abs, -1) gives the distance register; None otherwise."""
    if isinstance(value, ir.Func) and value.name == "abs":
        return 1
    if isinstance(value, ir.UnOp) and isinstance(value.operand, ir.Func) and value.operand.name == "abs":
        return -1
    return None


def signed_text(distance: str | None, sign: int | None) -> str | None:
    """A written constant distance with its sign changed by H (`sign` None: reversed), H+ (1) or
    H- (-1); None when it is not a non-zero constant (D0 has no side to change to)."""
    if distance is None or not re.fullmatch(r"-?\d+(\.\d+)?", distance) or float(distance) == 0:
        return None
    magnitude = distance.lstrip("-")
    negative = not distance.startswith("-") if sign is None else sign < 0
    return "-" + magnitude if negative else magnitude


def waited_moves(module: ir.Module) -> set[int]:
    """The moves (by id) the program waits for at once: the next operation waits for their axis."""
    found: set[int] = set()
    for _, block in module.blocks():
        for op, after in zip(block.ops, block.ops[1:]):
            if isinstance(op, ir.Move) and isinstance(after, ir.WaitMotion) \
                    and all(after.axis in (axis, ir.ALL_AXES) for axis, _ in op.targets):
                found.add(id(op))
    return found


def homing_waits(module: ir.Module) -> dict[int, int]:
    """The waits that directly follow a homing move on its axis, by id, to the id of their homing
    move: X150's GH runs the next command only once homing has ended (L1715), so GH is both."""
    found: dict[int, int] = {}
    for _, block in module.blocks():
        for op, after in zip(block.ops, block.ops[1:]):
            if isinstance(op, ir.Home) and isinstance(after, ir.WaitMotion) and after.axis in (op.axis, ir.ALL_AXES):
                found[id(after)] = id(op)
    return found


class Writer:
    def __init__(self, module: ir.Module, profile: Profile):
        module = self.module = without_trace_reports(module)
        self.profile = profile
        self.cat = cat.load()
        self.out = Written()
        self.native = module.dialect == DIALECT
        self.settled = ir.settled_ops(module)  # where no move can run: a pause means the same in both dialects
        self.source_spr = module.steps_per_rev or profile.steps_per_rev
        self.resolution = profile.steps_per_rev or self.source_spr
        self.speed_var: int | None = None  # the VARn holding a speed in rev/s (speed_variable)
        self.cur = self.device_resolutions()
        self.chosen_cur = self.chosen_resolution()  # a CUR the output sets so positions convert exactly
        if self.chosen_cur is not None:
            self.resolution = self.chosen_cur
        self.factor = units.ratio(self.source_spr, self.resolution)
        self.axes = self.axis_map()
        self.input_setup = InputSetup(module, DEDICATED_INPUTS)  # MCode IS lines X150 has inputs of its own for
        self.in_force = InForce(module)
        self.numbers = self.sequence_numbers()
        self.variables = self.variable_numbers()
        self.read_counters: set[str] = set()  # per routine: hidden L counters written as variables
        self.entries = {r.blocks[0].label: r.name for r in module.routines if r.blocks}
        self.touches = self.mode_touching()
        self.waited = waited_moves(module)
        self.homing_waits = homing_waits(module)
        self.homing_ops = set(self.homing_waits.values())
        self.routine: ir.Routine | None = None
        self.device: int | None = None
        self.in_sequence = False
        self.state: State = {}
        self.forces: dict[int, dict] = {}  # id(op) -> the motion settings in force before it
        # id(value) of an initial speed setting -> why X150 cannot leave it out (X216)
        self.start_speeds_refused: dict[int, str] = {}
        self.power_up_start = self.source_start_speed()  # the source product's own, when the program sets none
        self.previous: ir.Op | None = None  # the operation written last
        self.upcoming: ir.Op | None = None  # the operation written next in the same list, if simple
        self.rest: list = []  # the nodes after the one being written, in the same list
        self.reported: set[tuple[int, str]] = set()

    # -- the target's step and axes -----------------------------------------------------------------
    def device_resolutions(self) -> dict[str, int]:
        """An X150 program's CUR per device (the first one it sets: the frontend converted every
        distance with it). Another dialect's resolution is its own microstepping: the output keeps
        the profile's CUR and converts the positions."""
        found: dict[str, int] = {}
        if not self.native:
            return found
        for _, block in self.module.blocks():
            for op in block.ops:
                if isinstance(op, ir.SetMotion) and op.param is ir.MotionParam.RESOLUTION \
                        and isinstance(op.value, ir.Const) and isinstance(op.value.value, int):
                    found.setdefault(op.axis, op.value.value)
        return found

    def chosen_resolution(self) -> int | None:
        """The user resolution the output sets (CUR, parker-x150.md L731-L747: 1-32,767 user steps per
        revolution, the motor's travel per revolution unchanged) when the profile's would not convert
        the program's positions exactly and the program does not fix its own (backends/resolution.py).
        None: the profile's resolution serves, or no CUR does better."""
        if self.native or not self.module.steps_per_rev or not self.profile.get("cross.choose_resolution", True):
            return None
        info = self.cat.lookup("CUR")
        top = int(max((hi for _, hi in (info.intervals or ())), default=32767)) if info is not None else 32767
        return resolution.choose(int(self.source_spr), int(self.resolution), list(range(1, top + 1)),
                                 resolution.positions(self.module))

    def resolution_of(self, axis: str) -> int:
        return self.cur.get(axis, self.cur.get(ir.ALL_AXES, self.resolution))

    def factor_of(self, axis: str) -> Fraction:
        return units.ratio(self.source_spr, self.resolution_of(axis))

    def uniform(self) -> bool:
        """Every device counts positions in the IR's steps (no rescaling inside calculations)."""
        return all(self.factor_of(a) == 1 for a in [ir.ALL_AXES, *self.cur])

    def axis_map(self) -> dict[str, str]:
        """Source axis -> X150 device address. An X150 program keeps its addresses; another dialect's
        axes take the profile's axes in order of first use (the extra ones map to nothing)."""
        if self.native:
            return {}
        found: list[str] = []
        enables: list[str] = []  # an axis only enabled (Arcus EO2) takes a device only when nothing moves
        for _, block in self.module.blocks():
            for op in block.ops:
                for axis in op_axes(op):
                    seen = enables if isinstance(op, ir.DriveEnable) else found
                    if axis and axis != ir.ALL_AXES and axis not in seen:
                        seen.append(axis)
        found = found or enables
        targets = list(self.profile.axes) or ["1"]
        return {axis: targets[i] for i, axis in enumerate(found) if i < len(targets)}

    def axis(self, axis: str, span: Span | None = None) -> str:
        """The X150 address for a source axis ("" for every device)."""
        if self.native or axis in ("", ir.ALL_AXES):
            return axis
        if axis not in self.axes:
            targets = list(self.profile.axes) or ["1"]
            raise CannotWrite(f"axis {axis} is one axis more than profile {self.profile.name} drives "
                              f"({len(targets)} axis: {', '.join(map(str, targets))}); a single X150 device is "
                              "one axis: split the program per axis, or compile with --profile naming a profile "
                              "with more axes", "X204")
        return self.axes[axis]

    # -- sequence numbers --------------------------------------------------------------------------
    def sequence_numbers(self) -> dict[str, int]:
        """Every non-immediate routine's sequence number (routines of other dialects get free ones)."""
        numbers: dict[str, int] = {}
        used = set()
        for routine in self.module.routines:
            if routine.kind is ir.RoutineKind.IMMEDIATE:
                continue
            n = naming.sequence_number(routine.name) or routine.number
            if self.native and n:
                numbers[routine.name] = n
                used.add(n)
        free = (n for n in range(1, 65) if n not in used)
        for routine in self.module.routines:
            if routine.kind is not ir.RoutineKind.IMMEDIATE and routine.name not in numbers:
                n = routine.number if routine.number and routine.number not in used and 1 <= routine.number <= 64 \
                    else next(free, 0)
                used.add(n)
                numbers[routine.name] = n
        for name in self.module.externals:
            numbers.setdefault(name, naming.sequence_number(name) or 0)
        return numbers

    def variable_numbers(self) -> dict[str, int]:
        """VARn keeps its number; variables of other dialects get the free VAR numbers in order."""
        numbers = {name: variable_number(name) for name in self.module.variables if variable_number(name)}
        used = set(numbers.values())
        self.free_vars = [n for n in range(1, 51) if n not in used]
        for name in self.module.variables:
            if name not in numbers and not name.startswith(HIDDEN):
                numbers[name] = self.free_vars.pop(0) if self.free_vars else 0
        return numbers

    def var_number(self, name: str) -> int:
        number = self.variables.get(name) or variable_number(name)
        if not number and name.startswith(LOOP_PREFIX):
            number = self.counter_variable(name)
        return number

    def counter_variable(self, name: str) -> int:
        """An L loop's hidden counter that the structure leaves as a variable (the loop leaves from
        its middle, so it is not written as `Ln .. N`): it is kept in the highest free VARn."""
        if not self.free_vars:
            return 0
        number = self.variables[name] = self.free_vars.pop()
        declared = self.module.variables.get(name)
        span = (declared.span if declared else None) or self.fallback_span()
        if span is not None:
            self.out.diagnostics.add("X215", span, f"this L loop leaves from its middle, so it is written as a "
                                                   f"loop counting down VAR{number}, which nothing else in the "
                                                   f"program uses: make sure the host and other sequences do not "
                                                   f"use VAR{number} either")
        return number

    def number_of(self, name: str) -> int:
        if name in self.numbers:
            return self.numbers[name]
        return naming.sequence_number(name) or 0

    def mode_touching(self) -> set[str]:
        """Routines that may change a move mode or the D register (themselves or through calls)."""
        direct: dict[str, bool] = {}
        calls: dict[str, set[str]] = {}
        for routine in self.module.routines:
            touched = False
            called: set[str] = set()
            for block in routine.blocks:
                for op in block.ops:
                    if isinstance(op, (ir.Move, ir.Slew)) or (isinstance(op, ir.Native)
                                                              and op.mnemonic in MODE_COMMANDS):
                        touched = True
                    elif isinstance(op, ir.Call):
                        called.add(op.routine)
            direct[routine.name] = touched
            calls[routine.name] = called
        return ir.callers_of({name for name, touched in direct.items() if touched} | set(self.module.externals),
                             calls)

    # -- module and routines -----------------------------------------------------------------------
    def write_module(self) -> Written:
        if not self.native:
            self.out.header = self.header()
        if self.chosen_cur is not None:  # an immediate command (L734), before any sequence is stored
            self.routine, self.in_sequence = None, False
            for device in self.save_addresses():  # CUR is device specific like SV (Universal, L734)
                self.emit(f"{device}CUR{self.chosen_cur}", self.first_span())
        for _, _, op, state in self.each_op():
            self.forces[id(op)] = state
            if isinstance(op, ir.Move):
                for axis, _ in op.targets:
                    self.check_start_speed(state, axis)
        selected = set()
        for routine in self.module.routines:
            for block in routine.blocks:
                for op in block.ops:
                    if isinstance(op, ir.SetHandler) and op.event == "power" and op.routine:
                        selected.add(op.routine)
        first = True
        for routine in self.ordered():
            self.write_routine(routine, first)
            first = False
        for routine in self.module.routines:  # a power-up routine from another dialect: select it
            if routine.kind is ir.RoutineKind.POWERUP and routine.name not in selected:
                self.routine, self.in_sequence = routine, False
                self.emit(f"XP{self.number_of(routine.name)}", routine.span)
        return self.out

    def each_op(self):
        for routine in self.module.routines:
            yield from self.in_force.walk(routine)

    def header(self) -> list[str]:
        module, profile = self.module, self.profile
        axes = ", ".join(f"{s} -> {t}" for s, t in self.axes.items()) or "none"
        source = f"{module.steps_per_rev} steps/rev" if module.steps_per_rev else "steps/rev not stated: taken as the target's"
        return [
            f"; compiled by mcc from {module.dialect} (profile {module.profile}, {source}) "
            f"for {profile.name} ({self.resolution} user steps/rev, CUR)",
            f"; positions x {self.factor} (target/source steps); speeds in rev/s, accelerations in rev/s^2",
            "; modes: MN/MC and MPA/MPI are written before the first move of each sequence; axes " + axes,
        ]

    def ordered(self) -> list[ir.Routine]:
        """X150 programs keep their stream order. A program of another dialect is written as its
        variables' initial values, then every sequence definition, then its immediate commands,
        so no sequence runs before it is stored."""
        routines = self.module.routines
        initial = [ir.Assign(ir.Var(v.name), v.init, v.span) for v in self.module.variables.values()
                   if v.init is not None and not v.name.startswith(HIDDEN)]
        first = [ir.Routine("initial values", ir.RoutineKind.IMMEDIATE, [ir.Block("%init", initial, ir.FallOff())])] \
            if initial else []
        if self.native:  # an X150 program's variables start as the device has them (0 after power-up)
            return routines
        return first + [r for r in routines if r.kind is not ir.RoutineKind.IMMEDIATE] + \
            [r for r in routines if r.kind is ir.RoutineKind.IMMEDIATE]

    def write_routine(self, routine: ir.Routine, first: bool = False) -> None:
        self.routine = routine
        self.device = naming.device_of(routine.name) if self.native else None
        self.in_sequence = routine.kind is not ir.RoutineKind.IMMEDIATE
        self.state = {}  # nothing assumed: the first move of each routine writes its modes
        prefix = str(self.device) if self.device is not None else ""
        start, end_of_start = ends(routine.span)
        if self.in_sequence:
            n = self.number_of(routine.name)
            if not 1 <= n <= 64:
                self.out.diagnostics.add("X203", routine.span or self.fallback_span(),
                                         f"routine {routine.name} needs a sequence number, but all 64 are in use")
            self.emit(f"{prefix}XE{n}", start, stored=False)
            self.emit(f"{prefix}XD{n}", end_of_start, stored=False)
        # tail_copy=0: an XG or XRT written twice would sit inside an IF (an IF left open by XG, X112)
        done = structure(self.legal(routine), self.flag, self.dispatch_var, tail_copy=0, stops=STOPS, repeat=True)
        if done.fallback is not None:
            self.out.diagnostics.add("X201", routine.span or self.fallback_span(),
                                     f"{done.fallback} in {routine.name}: X150 sequences have no labels, so only "
                                     "L..N, IF..ELSE..NIF, WHILE..NWHILE and REPEAT..UNTIL can be written; "
                                     "restructure this part")
            if self.in_sequence:
                self.emit(f"{prefix}XT", self.closing_span(routine, done.exit_span))
            return
        body = lift_gotos(done.body)
        self.read_counters = counters_read(body)
        self.nodes(body)
        if self.in_sequence:
            self.emit(f"{prefix}XT", self.closing_span(routine, done.exit_span))

    def legal(self, routine: ir.Routine) -> ir.Routine:
        """A copy whose jumps to the start of another routine (MCode BR across programs) are XG:
        X150 has no labels, only whole sequences to go to."""
        own = {b.label for b in routine.blocks}
        blocks = []
        for block in routine.blocks:
            term = block.terminator
            if isinstance(term, ir.Jump) and term.target not in own and term.target in self.entries:
                term = ir.GotoRoutine(self.entries[term.target], term.span)
            blocks.append(ir.Block(block.label, block.ops, term, block.span, block.named))
        return ir.Routine(routine.name, routine.kind, blocks, routine.span, routine.number, routine.origin)

    def closing_span(self, routine: ir.Routine, exit_span: Span | None) -> Span | None:
        """Where XT comes from: the routine's own end (its FallOff, even after an XG), else the last block."""
        for block in reversed(routine.blocks):
            if isinstance(block.terminator, ir.FallOff) and block.terminator.span is not None:
                return block.terminator.span
        return exit_span or routine.span

    def flag(self, depth: int) -> ir.Var | None:
        """A loop flag: a free VARn (X150 has no other storage)."""
        if not self.free_vars:
            return None
        n = self.free_vars.pop(0)
        name = f"%flag{n}"
        self.variables[name] = n
        return ir.Var(name)

    def dispatch_var(self) -> ir.Var:
        return ir.Var("%dispatch")  # never written: a routine that needs it is refused (X201)

    def first_span(self) -> Span:
        """The first source line with an operation (where the chosen CUR is reported, if at all)."""
        for _, block in self.module.blocks():
            for op in block.ops:
                if getattr(op, "span", None) is not None:
                    return op.span
        return self.fallback_span()

    def fallback_span(self) -> Span:
        return Span(self.module.path or "<module>", 1, 1, 1, 1)

    def emit(self, text: str, *spans: Span | None, stored: bool = True) -> None:
        """Add a line; `stored` lines of a sequence count against its memory (XEn and XDn do not)."""
        sequence = self.routine.name if self.in_sequence and stored else None
        self.out.lines.append(Line(text, tuple(s for s in spans if s is not None), sequence))
        if sequence is not None:
            self.out.sequence_bytes[sequence] = self.out.sequence_bytes.get(sequence, 0) + len(text) + 1

    def refuse(self, exc: CannotWrite, span: Span | None) -> None:
        span = span or (self.routine.span if self.routine else None) or self.fallback_span()
        key = (span.start, exc.message)
        if key not in self.reported:
            self.reported.add(key)
            self.out.diagnostics.add(exc.code, span, exc.message)

    # -- the structured tree -------------------------------------------------------------------------
    def nodes(self, nodes: list) -> None:
        merged = 0
        for index, node in enumerate(nodes):
            if merged:
                merged -= 1
                continue
            if isinstance(node, Simple):
                if self.is_loop_count(node, nodes, index) or self.dead_count(node):
                    continue
                group = level_run(nodes, index)
                if len(group) > 1 and any(self.input_setup.needs_none(op) for op in group):
                    group = [group[0]]  # written one by one, the lines X150 needs no set-up for left out
                if len(group) > 1:  # several input/output levels: one INL/OUTL pattern, as written
                    merged = len(group) - 1
                    try:
                        self.emit(self.levels(group), *(op.span for op in group))
                    except CannotWrite as exc:
                        self.refuse(exc, node.op.span)
                    continue
                following = nodes[index + 1] if index + 1 < len(nodes) else None
                self.upcoming = following.op if isinstance(following, Simple) else None
                self.rest = nodes[index + 1:]
                try:
                    self.write_op(node.op)
                except CannotWrite as exc:
                    self.refuse(exc, node.op.span)
                self.upcoming, self.rest = None, []
            elif isinstance(node, IfNode):
                self.if_node(node.arms, node.orelse, node.spans, node.else_span, node.end_span)
            elif isinstance(node, WhileNode):
                self.loop(node, "WHILE")
            elif isinstance(node, RepeatNode):
                self.loop(node, "REPEAT", nodes[index - 1] if index else None)
            elif isinstance(node, EndNode):
                self.write_term(node.term, node.span)

    @staticmethod
    def is_loop_count(node: Simple, nodes: list, index: int) -> bool:
        """`%Lk = n` just before an L loop is written as the loop's `Ln`."""
        op = node.op
        return (isinstance(op, ir.Assign) and op.target.name.startswith(LOOP_PREFIX) and index + 1 < len(nodes)
                and isinstance(nodes[index + 1], RepeatNode) and counted(nodes[index + 1]) == op.target.name)

    def dead_count(self, node: Simple) -> bool:
        """The count of an X150 L loop that never comes back to its N (its body always leaves by XRT
        or XG): the loop runs once, and its hidden counter is never read."""
        op = node.op
        return isinstance(op, ir.Assign) and op.target.name.startswith(LOOP_PREFIX) \
            and not isinstance(op.value, ir.BinOp) and op.target.name not in self.read_counters

    def if_node(self, arms: list, orelse: list, spans: list, else_span, end_span) -> None:
        cond, body = arms[0]
        span = spans[0] if spans else None
        if isinstance(cond, ir.Not) and not self.writable(cond):
            # X150 has no NOT: `if not c: A elif ...: B else: C` is IF(c) <elif ... else C> ELSE A NIF
            rest_body = [IfNode(arms[1:], orelse, spans[1:], else_span, end_span)] if arms[1:] else orelse
            arms, orelse = [(cond.cond, rest_body)], body
            cond, body = arms[0]
        try:
            self.emit(f"{self.address()}IF({self.cond(cond)})", span)
        except CannotWrite as exc:
            self.refuse(exc, span)
        entry = dict(self.state)
        self.nodes(body)
        after = self.state
        self.state = dict(entry)
        rest = arms[1:]
        if rest or orelse:
            self.emit(f"{self.address()}ELSE", else_span or (spans[1] if len(spans) > 1 else None) or end_span or span)
            if rest:  # elif: an IF inside the ELSE
                self.if_node(rest, orelse, spans[1:], else_span, end_span)
            else:
                self.nodes(orelse)
        self.state = meet(after, self.state)
        self.emit(f"{self.address()}NIF", end_span or span)

    def conditional_call(self, cond, call: str, span) -> None:
        """X150 has no conditional call (MCode `CL K1, I1=1`): IF(c) XRn NIF, or IF(c) ELSE XRn NIF for a
        negated condition X150 cannot write (it has no NOT)."""
        negated = isinstance(cond, ir.Not) and not self.writable(cond)
        test = self.cond(cond.cond if negated else cond)
        prefix = self.address()
        self.emit(f"{prefix}IF({test})", span)
        if negated:
            self.emit(f"{prefix}ELSE", span)
        self.emit(call, span)
        self.emit(f"{prefix}NIF", span)

    def writable(self, cond) -> bool:
        try:
            self.cond(cond)
        except CannotWrite:
            return False
        return True

    def loop(self, node, kind: str, before=None) -> None:
        """WHILE/REPEAT/L: the body is written with the state known on every iteration (written again
        with less known when the body changes a mode it started with)."""
        entry = dict(self.state)
        for _ in range(3):
            mark = (len(self.out.lines), dict(self.out.sequence_bytes), len(self.out.diagnostics.items),
                    set(self.reported))
            self.state = dict(entry)
            self.loop_once(node, kind, before)
            end = meet(entry, self.state)
            if end == entry:
                break
            del self.out.lines[mark[0]:]
            self.out.sequence_bytes = mark[1]
            del self.out.diagnostics.items[mark[2]:]
            self.reported = mark[3]
            entry = end
        self.state = meet(entry, self.state)

    def loop_once(self, node, kind: str, before) -> None:
        if kind == "WHILE" and is_true(node.cond):  # an endless loop: L without a count (L0, L2328)
            self.emit(self.address() + "L", node.span)
            self.nodes(node.body)
            self.emit(self.address() + "N", node.end_span or node.span)
            return
        if kind == "WHILE" and isinstance(node.cond, ir.Not) and not self.writable(node.cond) \
                and self.writable(node.cond.cond):
            # X150 has no NOT: WHILE(NOT c) B runs as IF(c) ELSE REPEAT B UNTIL(c) NIF
            test, prefix = self.cond(node.cond.cond), self.address()
            for text in (f"IF({test})", "ELSE", "REPEAT"):
                self.emit(prefix + text, node.span)
            self.nodes(node.body)
            for text in (f"UNTIL({test})", "NIF"):
                self.emit(prefix + text, node.end_span or node.span)
            return
        if kind == "WHILE":
            try:
                self.emit(f"{self.address()}WHILE({self.cond(node.cond)})", node.span)
            except CannotWrite as exc:
                self.refuse(exc, node.span)
            self.nodes(node.body)
            self.emit(f"{self.address()}NWHILE", node.end_span or node.span)
            return
        counter = counted(node)
        if counter is not None and isinstance(before, Simple) and isinstance(before.op, ir.Assign) \
                and before.op.target.name == counter:
            count = before.op.value
            try:
                text = "L" if isinstance(count, ir.Const) and count.value == 0 else "L" + self.value(count)
            except CannotWrite as exc:
                self.refuse(exc, before.op.span)
                text = "L"
            self.emit(self.address() + text, before.op.span or node.span)
            self.nodes(unnested(node.body)[:-1])
            self.emit(self.address() + "N", node.end_span or node.span)
            return
        self.emit(f"{self.address()}REPEAT", node.span)
        self.nodes(node.body)
        try:
            self.emit(f"{self.address()}UNTIL({self.cond(node.until)})", node.end_span or node.span)
        except CannotWrite as exc:
            self.refuse(exc, node.end_span or node.span)

    def address(self, axis: str = ir.ALL_AXES) -> str:
        if self.device is not None:
            return str(self.device)
        axis = self.axis(axis)
        return axis if axis.isdigit() else ""

    def save_addresses(self) -> list[str]:
        """Where `Save` goes: SV is device specific (L181; unaddressed it is X117), so it keeps an
        address: the sequence's device, else each device of the profile (`1SV` for the built-in
        profiles' one device; issue 23: `1SV` in an unaddressed stream was written `SV`)."""
        if self.device is not None:
            return [str(self.device)]
        devices = [str(axis) for axis in self.profile.axes if str(axis).isdigit()]
        return devices or [""]

    def target(self, name: str) -> tuple[str, int]:
        """The address and number to write for a command naming routine `name`."""
        device = naming.device_of(name) if self.native else None
        prefix = self.address() if self.device is not None else (str(device) if device is not None else "")
        return prefix, self.number_of(name)

    def write_term(self, term, span) -> None:
        span = getattr(term, "span", None) or span
        if isinstance(term, ir.GotoRoutine):
            prefix, n = self.target(term.routine)
            self.emit(f"{prefix}XG{n}", span)
        elif isinstance(term, ir.Return):
            self.emit(self.address() + "XRT", span)
        else:
            self.emit(self.address() + "HALT", span)

    # -- operations ------------------------------------------------------------------------------------
    def write_op(self, op) -> None:
        try:
            self.write_one(op)
        finally:
            self.previous = op

    def write_one(self, op) -> None:
        """One handler per operation of the table (compiler/ir_ops.py), `WRITE_METHODS`; an operation
        without one has no X150 equivalent and is refused at its line (tests/ir/test_handlers.py)."""
        method = WRITE_METHODS.get(type(op))
        if method is None:
            raise CannotWrite(f"{describe_op(op)} has no X150 equivalent", "G003")
        method(self, op)

    def _write_native(self, op: ir.Native) -> None:
        if op.dialect != DIALECT:
            raise CannotWrite(f"{op.dialect} command {op.mnemonic} has no X150 equivalent; rewrite this part "
                              "with X150 commands or compile to its own dialect", "G003")
        self.emit(self.native_text(op), op.span)
        if op.mnemonic in ("MN", "MC", "MQ"):  # the move mode written: a move in it needs no repeat
            key = self.address(op.axis) or ir.ALL_AXES
            self.state = {k: v for k, v in self.state.items() if k[0] != "move"}
            self.state[("move", key)] = op.mnemonic
        elif op.mnemonic in MODE_COMMANDS:
            self.state = {}

    def _write_stop(self, op: ir.Stop) -> None:
        if op.ramp:  # SB stops in its turn, like the IR's Stop; S acts on receipt and clears the buffer
            self.emit(self.address(op.axis) + "SB", op.span)
        elif not self.in_sequence:
            self.emit(self.address(op.axis) + "K", op.span)
        elif not self.native and id(op) in self.settled:
            pass  # no move can run here: the source's abort stops nothing (docs/CROSS.md, "Abort")
        else:
            raise CannotWrite("X150 cannot store a kill in a sequence (K is never saved); stop with a "
                              "ramp, or send K from the host", "G003")

    def _write_delay(self, op: ir.Delay) -> None:
        self.emit(self.address() + "T" + self.seconds(op.duration), op.span)

    def _write_wait_input(self, op: ir.WaitInput) -> None:
        self.emit(self.address() + self.wait(op.cond), op.span)

    def _write_home(self, op: ir.Home) -> None:
        for line in self.home(op):
            self.emit(self.address(op.axis) + line, op.span)

    def _write_wait_motion(self, op: ir.WaitMotion) -> None:
        if id(op) in self.homing_waits:
            return  # GH has waited already
        # in MN the command after G runs when the move has ended (MQ exists to change that, L2631)
        key = self.address(op.axis) or ir.ALL_AXES
        if self.known("move", key) != "MN":
            self.emit(self.address(op.axis) + "TRIP", op.span)

    def _write_output(self, op: ir.SetOutput) -> None:
        self.emit(self.address() + "O" + self.outputs(op), op.span)

    def _write_drive_enable(self, op: ir.DriveEnable) -> None:
        if not self.native and enable_outputs.undriven(self.module, op, set(self.axes)):
            self.out.diagnostics.add("G060", op.span or self.fallback_span(),
                                     f"the enable of axis {op.axis} is left out: this program never moves axis "
                                     f"{op.axis}, which profile {self.profile.name} does not drive (ST enables "
                                     "the drive itself, parker-x150.md L4010-L4031)")
            return
        if not isinstance(op.on, ir.Const):
            raise CannotWrite("X150 enables (ST0) or shuts down (ST1) the drive with a constant only")
        # ST is buffered and only enables/disables; OFF would also kill and dump the buffer (L2789)
        self.emit(self.address(op.axis) + ("ST0" if op.on.value else "ST1"), op.span)

    def _write_set_position(self, op: ir.SetPosition) -> None:
        if not (isinstance(op.value, ir.Const) and op.value.value == 0):
            raise CannotWrite("X150 sets the position counter to zero only (PZ); setting it to another value "
                              "has no equivalent", "G003")
        self.emit(self.address(op.axis) + "PZ", op.span)

    def _write_assign(self, op: ir.Assign) -> None:
        if op.target.name.startswith(DISTANCE):
            self.register(op)
        else:
            self.emit(self.address() + self.assign(op), op.span)

    def _write_save(self, op: ir.Save) -> None:
        if self.in_sequence:
            raise CannotWrite("X150 saves with SV, an immediate command that a sequence cannot store "
                              "(\"Immediate, Device Specific\", L4087): save from the host, after the "
                              "definitions", "G003")
        for device in self.save_addresses():
            self.emit(device + "SV", op.span)

    def _write_call(self, op: ir.Call) -> None:
        prefix, n = self.target(op.routine)
        call = f"{prefix}XR{n}"
        other = naming.device_of(op.routine) if self.native else None
        if self.device is not None and other is not None and other != self.device:
            # a sequence of another device, run from device a's stream or sequence: device a sends
            # the command string to it over the daisy chain (the quote command, L5593, L5614)
            call = f'{self.device}"{other}XR{n}"'
        if op.cond is None:
            self.emit(call, op.span)
        else:
            self.conditional_call(op.cond, call, op.span)
        if op.routine in self.touches:
            self.state = {}

    def _write_print(self, op: ir.Print) -> None:
        prefix = "" if report_command(op) else self.address(op.axis) if op.axis else self.address()
        self.emit(prefix + self.print_text(op), op.span)

    def _write_setting(self, op: ir.Setting) -> None:
        if op.name == "enable_outputs" and not self.native:
            self.enable_outputs(op, op.span)
        elif not self.input_setup.needs_none(op):
            self.emit(self.setting(op), op.span)

    def _write_host_control(self, op: ir.Pause | ir.Resume | ir.Step) -> None:
        self.emit(self.host_control(op), op.span)

    def host_control(self, op: ir.Pause | ir.Resume | ir.Step) -> str:
        """PS (buffered, pauses command execution, L3151), C and #n (immediate, never saved: only
        the host stream sends them, L291, L5548)."""
        address = self.address(op.axis)
        if isinstance(op, ir.Pause):
            if op.stop_motion and id(op) not in self.settled:
                raise CannotWrite("X150's PS pauses command execution and lets a move in progress run on; the source "
                                  "stops the move at the pause: wait for the move to end before the pause", "G003")
            return address + "PS"
        what = "C (continue, L291)" if isinstance(op, ir.Resume) else "# (single step, L5548)"
        if self.in_sequence:
            raise CannotWrite(f"X150 never saves {what} in a sequence: only the host sends it", "G003")
        if isinstance(op, ir.Resume):
            return address + "C"
        if not isinstance(op.count, ir.Const) or not float(op.count.value).is_integer() \
                or not 1 <= op.count.value <= 255:
            count = f"{op.count.value:g} commands" if isinstance(op.count, ir.Const) else "a count known only at run time"
            raise CannotWrite(f"X150 steps 1-255 commands with #n (L5548); stepping {count} has no equivalent",
                              "G003")
        count = int(op.count.value)
        return address + "#" + (str(count) if count != 1 else "")

    def home(self, op: ir.Home) -> list[str]:
        """GH n: seek the home input at n rev/s, the sign giving the direction (L1701-L1715). X150
        homes on its home input only, at a speed of its own, and waits for the end of homing."""
        if op.method != "switch" or op.direction not in (1, -1):
            how = f"by {op.method}" + (" without a direction" if op.direction not in (1, -1) else "")
            raise CannotWrite(f"X150 homes on the home switch in + or - (GH); homing {how} has no equivalent", "G003")
        refused = homing.refusal(op, self.profile, self.source_spr)
        if refused:  # GH zeroes at the switch edge after creeping back at GHF (L1715, L1722)
            raise CannotWrite(refused, "G003")
        speed = op.speed
        if speed is None:  # another dialect's homing seeks at the max speed in force: GH at that speed
            speed = lookup(self.forces.get(id(op), {}), ir.MotionParam.MAX_SPEED, op.axis)
        if not isinstance(speed, ir.Const):
            raise CannotWrite("X150 homes at a speed written in GH n, and the max speed this homing move seeks at "
                              "is not known here: set it with a constant before the homing move", "G003")
        if id(op) not in self.homing_ops:
            raise CannotWrite("X150 runs the next command only when GH has found home (L1715), and the source goes "
                              "on while homing: wait for the end of the homing move in the source", "G003")
        text = self.ranged("GH", self.rate(speed, "speed"), "homing speed", "rev/s")
        lines: list[str] = []
        if op.speed is None:  # another dialect's homing ramps at the acceleration in force; X150's at GA
            accel = lookup(self.forces.get(id(op), {}), ir.MotionParam.ACCEL, op.axis)
            if not isinstance(accel, ir.Const):
                raise CannotWrite("X150 homing ramps at its own acceleration (GA), and the acceleration this homing "
                                  "move ramps at is not known here: set it with a constant before the homing move",
                                  "G003")
            lines.append("GA" + self.ranged("GA", self.rate(accel, "acceleration"), "homing acceleration", "rev/s^2"))
        return lines + ["GH" + ("-" if op.direction < 0 else "") + text]

    def motion(self, op: ir.SetMotion) -> None:
        param, span = op.param, op.span
        prefix = self.address(op.axis)
        if param is ir.MotionParam.MAX_SPEED and not self.native and isinstance(op.value, ir.Var) \
                and self.var_number(op.value.name):
            self.emit(prefix + "V" + self.speed_variable(op.value), span)
            again = self.ramp_again(op)
            if again is not None:
                self.emit(prefix + "A" + again, span)
        elif param is ir.MotionParam.MAX_SPEED:
            self.emit(prefix + "V" + self.rate(op.value, "speed"), span)
            again = self.ramp_again(op)
            if again is not None:
                self.emit(prefix + "A" + again, span)
        elif param in (ir.MotionParam.ACCEL, ir.MotionParam.ACCEL_TIME):
            text = self.rate(op.value, "acceleration") if param is ir.MotionParam.ACCEL else self.ramp(op)
            self.decel_still_same(op)
            self.emit(prefix + "A" + text, span)
        elif param in (ir.MotionParam.DECEL, ir.MotionParam.DECEL_TIME):
            self.same_as_accel(op)
        elif param is ir.MotionParam.RESOLUTION:
            if not self.native:
                return  # the source's microstepping: the output converts positions to the profile's CUR
            if not (isinstance(op.value, ir.Const) and op.value.value == self.resolution_of(op.axis)):
                raise CannotWrite(f"the resolution of device {op.axis} changes within the program; X150 output "
                                  f"keeps one CUR per device ({self.resolution_of(op.axis)} user steps/rev)", "G003")
            self.emit(prefix + ("B" if self.in_sequence else "") + "CUR" + number(op.value.value), span)
        elif param is ir.MotionParam.INITIAL_SPEED:
            if id(op.value) in self.start_speeds_refused:
                raise CannotWrite(self.start_speeds_refused[id(op.value)], "X216")
            self.out.diagnostics.add("X205", span or self.fallback_span(),
                                     "X150 moves start from standstill: it has no initial (start) speed, so "
                                     "this one is left out and each move ramps from 0 at A")
        elif param is ir.MotionParam.PROFILE:
            if not (isinstance(op.value, ir.Const) and op.value.value == 0):
                raise CannotWrite("X150 ramps are trapezoidal only; an S-curve profile has no equivalent", "G003")
        else:
            raise CannotWrite(f"X150 has no command for the {param.value.replace('_', ' ')}", "G003")

    def check_start_speed(self, state: dict, axis: str) -> None:
        """X150 starts every move from standstill (it has no initial speed, docs/dialects/x150.md). A
        source move that starts at v0 > 0 and ramps at a ends later on X150, by at most 2 * v0 / a
        (the ramp from 0 to v0 at each end; less on a short move). Where that exceeds the profile's
        `[x150] start_speed_drift` (one tick, 1 ms, by default), the initial speed in force is refused
        at its own line (X216) rather than written as a program the validation then refuses (S010).
        The acceleration is the one in force, or a ramp time's with the speeds in force."""
        start = lookup(state, ir.MotionParam.INITIAL_SPEED, axis)
        if start is None:
            start = self.power_up_start
        if start is None or id(start) in self.start_speeds_refused or not isinstance(start.value, (int, float)) \
                or start.value <= 0:
            return
        v0 = float(start.value)
        accel = lookup(state, ir.MotionParam.ACCEL, axis)
        ramp = lookup(state, ir.MotionParam.ACCEL_TIME, axis)
        top = lookup(state, ir.MotionParam.MAX_SPEED, axis)
        rate = None
        if accel is not None and float(accel.value) > 0:
            rate = float(accel.value)
        elif ramp is not None and top is not None and float(ramp.value) > 0 and float(top.value) > v0:
            rate = (float(top.value) - v0) / float(ramp.value)
        limit = float(self.profile.get("x150.start_speed_drift", START_SPEED_DRIFT) if self.profile else
                      START_SPEED_DRIFT)
        speed = f"{number(v0)} {start.unit.value}"
        if rate is None:
            self.start_speeds_refused[id(start)] = (
                f"X150 starts every move from standstill and has no initial speed; with the initial speed {speed} "
                "and an acceleration not known here, how much later its moves would end cannot be bounded: set "
                "the initial speed to 0 (or its lowest) or the acceleration with a constant")
            return
        drift = 2 * v0 / rate
        if drift > limit and start is self.power_up_start:
            self.start_speeds_refused[id(start)] = (
                f"the source starts its moves at its product's power-up initial speed, {speed} (the program sets "
                f"none), and X150 from standstill: this move would end up to {drift * 1000:.3g} ms later (2 x "
                f"initial speed / acceleration), more than the {limit * 1000:g} ms the profile allows ([x150] "
                f"start_speed_drift); set the initial speed in the source to {number(round(rate * limit / 2, 3))} "
                f"{start.unit.value} or less before the first move, or compile to a target with a start speed")
        elif drift > limit:
            self.start_speeds_refused[id(start)] = (
                f"X150 starts every move from standstill and has no initial speed: a move starting at {speed} "
                f"would end up to {drift * 1000:.3g} ms later (2 x initial speed / acceleration), more than the "
                f"{limit * 1000:g} ms the profile allows ([x150] start_speed_drift); lower the initial speed to "
                f"{number(round(rate * limit / 2, 3))} {start.unit.value} or less, or compile to a target "
                "with a start speed")

    def first_move_refused(self) -> int | None:
        """The first move (by id, in writing order) that starts at the refused power-up initial speed:
        the refusal is reported there once (the speed has no line of its own)."""
        if not hasattr(self, "_first_move_refused"):
            self._first_move_refused = next((id(op) for _, _, op, _ in self.each_op() if isinstance(op, ir.Move)),
                                            None)
        return self._first_move_refused

    def source_start_speed(self) -> ir.Const | None:
        """The initial speed another product starts its moves at when the program sets none: its
        profile's power-up value (MCode VI 1000 steps/s, lexium-mcode.txt L662-L666), which
        `in_force.with_power_up` does not write for X150 (it has none, `in_force.FIXED`). The first
        move it would make end later than `[x150] start_speed_drift` is refused (X216)."""
        if self.native or any(isinstance(op, ir.SetMotion) and op.param is ir.MotionParam.INITIAL_SPEED
                              for _, block in self.module.blocks() for op in block.ops):
            return None
        from mcc.compiler.in_force import source_profile
        from mcc.compiler.profiles import power_up

        source = source_profile(self.module, self.profile) if self.profile is not None else None
        if source is None:
            return None
        value = power_up(source, self.source_spr).get("initial_speed", 0.0)
        return ir.Const(value, ir.Unit.STEPS_PER_S) if value > 0 else None

    def ranged(self, mnemonic: str, text: str, what: str, unit: str) -> str:
        """`text` when the catalog's range for `mnemonic` takes it (a (VARn) is checked on the device)."""
        try:
            value = float(text)
        except ValueError:
            return text
        info = self.cat.lookup(mnemonic)
        if info is not None and not info.in_range(value):
            allowed = ", ".join(f"{number(lo)}" if lo == hi else f"{number(lo)} to {number(hi)}"
                                for lo, hi in info.intervals or ())
            raise CannotWrite(f"the {what} {text} {unit} is outside what X150 {mnemonic} accepts ({allowed} {unit}, "
                              f"{info.manual}); the source's value has no X150 equivalent", "X207")
        return text

    def ramp(self, op: ir.SetMotion) -> str:
        """A ramp time as X150's acceleration: (max speed - initial speed) / time, with the speeds in
        force where it is set (values known only at run time are refused: X150 cannot compute A)."""
        state = self.forces.get(id(op), {})
        high = lookup(state, ir.MotionParam.MAX_SPEED, op.axis)
        if not isinstance(op.value, ir.Const) or high is None:
            raise CannotWrite("this ramp time becomes an X150 acceleration only with the speeds in force, which "
                              "are not known here (set the maximum speed with a constant before it)", "X206")
        return self.ramp_accel(op.value, high, lookup(state, ir.MotionParam.INITIAL_SPEED, op.axis))

    def ramp_accel(self, time: ir.Const, high: ir.Const, low: ir.Const | None) -> str:
        accel = units.accel_from_ramp(float(time.value), float(low.value) if low else 0.0, float(high.value))
        if accel is None:
            raise CannotWrite(f"a ramp time of {number(time.value)} s has no finite acceleration", "X206")
        return self.rate(ir.Const(accel, ir.Unit.STEPS_PER_S2), "acceleration")

    def ramp_again(self, op: ir.SetMotion) -> str | None:
        """The A to write again after a change of the max speed, when the source ramps in a time
        (Arcus ACC): X150's A is an acceleration (rev/s^2, L199), the ramp time a time, so the same
        time at the new speed is another acceleration (issue 23: the A of the old speed was kept,
        and a move after `HSPD` doubled ramped half as fast). None when no ramp time is in force or
        an acceleration set as such (MCode A, X150 A) is: it does not change with the speed."""
        state = self.forces.get(id(op), {})
        if lookup(state, ir.MotionParam.ACCEL, op.axis) is not None:
            return None
        time = lookup(state, ir.MotionParam.ACCEL_TIME, op.axis)
        if time is None:  # none set yet (or not the same on every path: docs/dialects/x150.md, Limitations)
            return None
        if not isinstance(time, ir.Const) or not isinstance(op.value, ir.Const):
            raise CannotWrite("a ramp time with a speed known only at run time has no X150 acceleration: X150 "
                              "cannot compute A", "X206")
        return self.ramp_accel(time, op.value, lookup(state, ir.MotionParam.INITIAL_SPEED, op.axis))

    def same_as_accel(self, op: ir.SetMotion) -> None:
        """X150 decelerates at A: a deceleration equal to the acceleration in force needs nothing."""
        before = self.previous
        if isinstance(before, ir.SetMotion) and before.axis == op.axis and before.value == op.value and \
                (before.param, op.param) in ((ir.MotionParam.ACCEL, ir.MotionParam.DECEL),
                                             (ir.MotionParam.ACCEL_TIME, ir.MotionParam.DECEL_TIME)):
            return  # the A just written (how X150's own A lowers: ACCEL then DECEL of the same value)
        state = self.forces.get(id(op), {})
        if op.param is ir.MotionParam.DECEL:
            accel = lookup(state, ir.MotionParam.ACCEL, op.axis)
            if isinstance(op.value, ir.Const) and accel is not None and accel.value == op.value.value:
                return
        else:
            accel = lookup(state, ir.MotionParam.ACCEL_TIME, op.axis)
            if isinstance(op.value, ir.Const) and accel is not None and accel.value == op.value.value:
                return
        raise CannotWrite("X150 decelerates at the acceleration A; a deceleration that differs from the "
                          "acceleration in force has no equivalent", "G003")

    def decel_still_same(self, op: ir.SetMotion) -> None:
        """A new acceleration is also X150's deceleration: refused when the source's deceleration in
        force (set before, e.g. MCode `A=100000 D=100000 A=1000000`) stays another value. Not when
        the deceleration is set next to the same value (how X150's own A lowers: ACCEL then DECEL),
        and not when no deceleration is known here (the check at the DECEL or the validation has it)."""
        decel_param = ir.MotionParam.DECEL if op.param is ir.MotionParam.ACCEL else ir.MotionParam.DECEL_TIME
        follower = self.rest[0].op if self.rest and isinstance(self.rest[0], Simple) else None
        if isinstance(follower, ir.SetMotion) and follower.param is decel_param and follower.axis == op.axis:
            return  # the deceleration is set right after: same_as_accel checks it there
        decel = lookup(self.forces.get(id(op), {}), decel_param, op.axis)
        if isinstance(decel, ir.Const) and isinstance(op.value, ir.Const) and decel.value != op.value.value:
            raise CannotWrite("X150 decelerates at the acceleration A: this acceleration would also change the "
                              f"deceleration, which stays {number(decel.value)} in the source; set the "
                              "deceleration to the same value after it in the source, or compile to a target with "
                              "a deceleration of its own", "G003")

    def move(self, op: ir.Move) -> None:
        start = self.power_up_start
        if start is not None and id(start) in self.start_speeds_refused and id(op) == self.first_move_refused():
            raise CannotWrite(self.start_speeds_refused[id(start)], "X216")
        if len(op.targets) != 1:
            raise CannotWrite(f"X150 moves one axis per device; a move of {len(op.targets)} axes together "
                              "(linear interpolation) has no equivalent", "X204")
        if op.mode not in (ir.MoveMode.ABSOLUTE, ir.MoveMode.RELATIVE):
            raise CannotWrite("this move's mode (absolute or relative) is whatever is in force on the source device, "
                              "which X150 cannot know: the source frontend must resolve it (issue 8)", "G003")
        axis, target = op.targets[0]
        prefix = self.address(axis)
        key = self.address(axis) or ir.ALL_AXES
        first, last = ends(op.span)
        register = isinstance(target, ir.Var) and target.name.startswith(DISTANCE)
        distance = "" if register else self.position(target, axis)
        # A computed distance `D(VARn)` goes before the mode switches, where the X150 frontend's
        # distance register reads it back (so the output compiles again to the same text); a
        # constant one after them, as the manual's examples write it
        computed = not isinstance(target, ir.Const)
        if computed and not register:
            self.distance(prefix, key, distance, first)
        # MN: the next command runs when the move has ended; MQ: at once (L2631). The IR says which by
        # the WaitMotion that follows the move, or not
        self.set_mode("move", key, "MN" if id(op) in self.waited else "MQ", prefix, first)
        self.set_mode("pos", key, "MPA" if op.mode is ir.MoveMode.ABSOLUTE else "MPI", prefix, first)
        if not computed:
            self.distance(prefix, key, distance, first)
        self.emit(prefix + "G", last)

    def overwritten(self, name: str) -> bool:
        """The register `name` is set again, later in this list, before any operation reads it: the
        value written now is never used (an optimizer may leave such a store; the output compiled
        again would drop it, so writing it would make compile(compile(p)) differ)."""
        for node in self.rest:
            if not isinstance(node, Simple):
                return False
            op = node.op
            if isinstance(op, (ir.Call, ir.Native, ir.SetHandler)):
                return False
            reads = {e.name for expr in ir.op_exprs(op) for e in ir.walk_expr(expr) if isinstance(e, ir.Var)}
            if name in reads:
                return False
            if isinstance(op, ir.Assign) and op.target.name == name:
                return True
        return False

    def distance(self, prefix: str, key: str, distance: str, span) -> None:
        if self.known("D", key) != distance:
            self.emit(prefix + "D" + distance, span)
            self.record("D", key, distance)
            self.record("sign", key, None)

    def register(self, op: ir.Assign) -> None:
        """The X150 frontend's distance register: `D<n>`, or `H` / `H+` / `H-` for its sign."""
        axis = op.target.name[len(DISTANCE):]
        prefix = self.address(axis)
        key = prefix or ir.ALL_AXES
        value = op.value
        upcoming = self.upcoming
        if isinstance(upcoming, ir.Slew) and upcoming.velocity is None and (self.address(upcoming.axis) or
                                                                             ir.ALL_AXES) == key \
                and register_direction(value) == (-1 if upcoming.direction < 0 else 1):
            return  # the slew after it writes this H+/H- itself, after its MC (as the X150 source has it)
        if self.overwritten(op.target.name):
            return  # set again before anything reads it (an H the optimizer folded into D-8000)
        if isinstance(value, ir.Const) and isinstance(upcoming, ir.Move) and len(upcoming.targets) == 1 \
                and (self.address(upcoming.targets[0][0]) or ir.ALL_AXES) == key \
                and isinstance(upcoming.targets[0][1], ir.Const) \
                and upcoming.targets[0][1].value == value.value:
            return  # the move after it writes this D itself, after its modes (where a source's D is read)
        sign = self.known("sign", key)
        old = self.known("D", key)
        self.record("D", key, None)
        self.record("sign", key, None)
        # H, H+, H- change the sign of a D the output wrote: the value they leave is known, so a
        # move by it writes no D again (which, compiled again, would make the H dead: issue 23)
        if isinstance(value, ir.UnOp) and isinstance(value.operand, ir.Var):
            self.emit(prefix + "H", op.span)
            if sign is not None:
                self.record("sign", key, -sign)
            self.record("D", key, signed_text(old, None))
        elif isinstance(value, ir.Func) and value.name == "abs":
            self.emit(prefix + "H+", op.span)
            self.record("sign", key, 1)
            self.record("D", key, signed_text(old, 1))
        elif isinstance(value, ir.UnOp) and isinstance(value.operand, ir.Func):
            self.emit(prefix + "H-", op.span)
            self.record("sign", key, -1)
            self.record("D", key, signed_text(old, -1))
        else:
            distance = self.position(value, axis)
            self.emit(prefix + "D" + distance, op.span)
            self.record("D", key, distance)
            if isinstance(value, ir.Const) and value.value:
                self.record("sign", key, 1 if value.value > 0 else -1)

    def slew(self, op: ir.Slew) -> None:
        prefix = self.address(op.axis)
        key = prefix or ir.ALL_AXES
        direction = op.direction
        if op.velocity is not None:
            if not isinstance(op.velocity, ir.Const):
                raise CannotWrite("X150 runs continuously at a constant speed: a velocity computed at run time "
                                  "has no equivalent", "X206")
            value = float(op.velocity.value)
            direction = 1 if value >= 0 else -1
            self.emit(prefix + "V" + self.rate(ir.Const(abs(value), ir.Unit.STEPS_PER_S), "speed"), op.span)
        self.set_mode("move", key, "MC", prefix, op.span)
        sign = -1 if direction < 0 else 1
        if self.known("sign", key) != sign:
            self.emit(prefix + ("H-" if sign < 0 else "H+"), op.span)
            self.record("D", key, None)
            self.record("sign", key, sign)
        self.emit(prefix + "G", op.span)

    def set_mode(self, kind: str, key: str, mode: str, prefix: str, span) -> None:
        if self.known(kind, key) == mode:
            return
        self.emit(prefix + mode, span)
        self.record(kind, key, mode)

    def known(self, kind: str, key: str):
        """What the output last set for `kind` ("move", "pos", "D", "sign") on device `key`, else
        for every device ("*"); None when not known."""
        return self.state.get((kind, key), self.state.get((kind, ir.ALL_AXES)))

    def record(self, kind: str, key: str, value) -> None:
        """`kind` is now `value` on device `key` (None: not known). A command for every device
        ("*") replaces what each device had; a device's own replaces what every device had, so the
        state never holds both and an unaddressed G is never taken to find device 1 in the mode
        an earlier unaddressed command set when `1MPI` has changed it since (issue 23)."""
        if key == ir.ALL_AXES:
            for other in [k for k in self.state if k[0] == kind]:
                del self.state[other]
        else:
            self.state.pop((kind, ir.ALL_AXES), None)
            self.state.pop((kind, key), None)
        if value is not None:
            self.state[(kind, key)] = value

    def setting(self, op: ir.Setting) -> str:
        """A neutral setting in its X150 command (the B prefix inside a sequence where the command
        takes one); a setting X150 has no command for is refused by name."""
        prefix = self.address(op.axis)
        name = op.name
        if name in neutral.SETTING_COMMANDS:
            mnemonic = neutral.SETTING_COMMANDS[name]
            info = self.cat.lookup(mnemonic)
            if self.in_sequence and info.exec == "I":
                raise CannotWrite(f"X150 {mnemonic} ({name.replace('_', ' ')}) is an immediate command that a "
                                  "sequence cannot store; send it from the host", "G003")
            unit = ir_names.SETTINGS[name].unit
            if unit in SETTING_RATES:  # a speed or acceleration setting (IV, GHF, GA) in rev/s or rev/s^2
                what, written = SETTING_RATES[unit]
                value = self.ranged(mnemonic, self.rate(op.value, what), name.replace("_", " "), written)
            else:
                written = units.from_ir(op.value, neutral.SCALES[mnemonic]) if mnemonic in neutral.SCALES else op.value
                value = self.value(written)
                self.ranged(mnemonic, value, name.replace("_", " "), "")
            return prefix + ("B" if self.in_sequence and info.b_prefixable else "") + mnemonic + value
        index = op.index or 0
        if name in ("input_function", "output_function"):
            letters = neutral.INPUT_LETTERS if name == "input_function" else neutral.OUTPUT_LETTERS
            function = op.value.value if isinstance(op.value, ir.Text) else None
            top = neutral.USER_INPUTS if name == "input_function" else neutral.OUTPUTS
            if function not in letters or not 1 <= index <= top:
                raise CannotWrite(f"X150 has no {'input' if name == 'input_function' else 'output'} function "
                                  f"'{function}' for line {index} (IN/OUT letters, L2058, L2974)", "G003")
            return prefix + ("IN" if name == "input_function" else "OUT") + str(index) + letters[function]
        if name in LEVELS:
            top = LEVEL_COUNTS[name]
            if not (isinstance(op.value, ir.Const) and op.value.value in (0, 1) and 1 <= index <= top):
                raise CannotWrite(f"X150 sets the active level of its 7 dedicated inputs, inputs 1-10 and outputs "
                                  f"1-6 to a constant 0 or 1 (INL/OUTL); this {name.replace('_', ' ')} has no "
                                  "equivalent", "G003")
            bits = "X" * (index - 1) + str(int(op.value.value))
            return prefix + level_command(name, bits)
        raise CannotWrite(f"the setting '{name}' ({describe_setting(name)}) has no X150 command", "G003")

    def levels(self, group: list) -> str:
        """Active levels of several inputs (or outputs) of one device as one INL/OUTL pattern."""
        bits = {name: ["X"] * LEVEL_COUNTS[name] for name in {op.name for op in group}}
        for op in group:
            text = self.setting(op)
            bits[op.name][op.index - 1] = text[-1] if op.name != "switch_active_high" else text[-2]
        head = self.address(group[0].axis)
        if "switch_active_high" in bits:   # one INL: the dedicated group, `_`, the user inputs (L2136)
            user = "".join(bits.get("input_active_high", [])).rstrip("X")
            return head + "INL" + "".join(bits["switch_active_high"]).rstrip("X") + "_" + user
        return head + level_command(group[0].name, "".join(bits[group[0].name]).rstrip("X"))

    def handler(self, op: ir.SetHandler) -> None:
        command = HANDLER_COMMANDS.get(op.event)
        if command is None:
            raise CannotWrite(f"X150 has no '{op.event}' handler (only power-up XP, fault XFK and WHEN)", "G003")
        if op.once or op.gated or op.takes_over != (op.event == "fault"):
            raise CannotWrite(f"a '{op.event}' handler that behaves otherwise than X150's {command} (which stays "
                              "armed; a fault sequence takes over the program, L2305)", "G003")
        if op.routine is not None:
            prefix, n = self.target(op.routine)
            self.emit(f"{prefix}{command}{n}", op.span)
        elif op.event == "when" and op.args:
            self.emit(f"{self.address()}WHEN({self.cond(op.args[0])})", op.span)
        else:
            self.emit(f"{self.address()}{command}0", op.span)

    # -- operands ------------------------------------------------------------------------------------
    def position(self, expr, axis: str = ir.ALL_AXES) -> str:
        """A distance or position in the target's user steps (exact, or refused)."""
        factor = self.factor_of(axis)
        if isinstance(expr, ir.Const):
            scaled = units.scale_steps(expr.value, factor)
            if not scaled.exact:
                raise CannotWrite(
                    f"the position {number(expr.value)} steps falls between two X150 steps: the source has "
                    f"{self.source_spr} steps/rev, the target {self.resolution_of(axis)} (x{factor}); compile "
                    "with --profile naming a user profile whose steps_per_rev makes it whole", "X207")
            return number(scaled.value)
        if isinstance(expr, ir.Var) and self.var_number(expr.name):
            if factor != 1:
                raise CannotWrite(f"a position held in {expr.name} cannot be rescaled from "
                                  f"{self.source_spr} to {self.resolution_of(axis)} steps/rev", "X207")
            return f"(VAR{self.var_number(expr.name)})"
        raise CannotWrite(f"an X150 distance is a number or (VARn); {describe(expr)} cannot be written here")

    def rate(self, expr, what: str) -> str:
        """A speed (steps/s) in rev/s or an acceleration (steps/s^2) in rev/s^2."""
        if isinstance(expr, ir.Const):
            revs = units.steps_to_revs(expr.value, self.source_spr)
            value = units.round_to(revs, RATE_STEP)
            if value == 0 and expr.value != 0:
                raise CannotWrite(f"the {what} {number(expr.value)} {expr.unit.value} is below the X150's "
                                  f"resolution of {RATE_STEP} rev/s", "X207")
            info = self.cat.lookup(RATE_MNEMONICS[what])
            if info is not None and not info.in_range(value):
                raise CannotWrite(f"the {what} {number(expr.value)} {expr.unit.value} is {number(value)} "
                                  f"rev/s{'^2' if what == 'acceleration' else ''} at {self.source_spr} steps/rev, "
                                  f"outside what X150 {RATE_MNEMONICS[what]} accepts ({info.manual or 'catalog'})",
                                  "X207")
            return number(value)
        # X150 V(VARn)/A(VARn): the variable holds rev/s (rev/s^2): the IR says VARn * steps per rev
        if isinstance(expr, ir.BinOp) and expr.op == "*" and isinstance(expr.left, ir.Var) \
                and isinstance(expr.right, ir.Const) and self.var_number(expr.left.name) \
                and expr.right.value == self.source_spr:
            return f"(VAR{self.var_number(expr.left.name)})"
        raise CannotWrite(f"an X150 {what} is a number or (VARn) in rev/s; {describe(expr)} cannot be written here",
                          "X202")

    def speed_variable(self, var: ir.Var) -> str:
        """Another dialect's speed held in a variable, in steps/s (Arcus `HSPD=V1`, arcus-pmx-4ex-sa.txt
        L2230-L2233): X150's V(VARn) takes rev/s (parker-x150.md L4542), so the speed goes through a
        free VARn that holds it per revolution (`VAR2=VAR1/4000`, decimal: L4569-L4573), then V(VAR2).
        That VARn is the program's no longer (refused when none is free)."""
        if not self.free_vars:
            raise CannotWrite(f"an X150 speed is a number or (VARn) in rev/s; the speed in {var.name} (steps/s) "
                              "needs a free VARn to hold it in rev/s, and all 50 are in use", "X202")
        if self.speed_var is None:
            self.speed_var = self.free_vars.pop()
        self.emit(f"VAR{self.speed_var}=VAR{self.var_number(var.name)}/{self.source_spr}", var.span)
        return f"(VAR{self.speed_var})"

    def value(self, expr) -> str:
        if isinstance(expr, ir.Const) and isinstance(expr.value, (int, float)):
            return number(expr.value)
        if isinstance(expr, ir.Var) and self.var_number(expr.name):
            return f"(VAR{self.var_number(expr.name)})"
        raise CannotWrite(f"an X150 value is a number or (VARn); {describe(expr)} cannot be written here")

    def seconds(self, expr) -> str:
        if isinstance(expr, ir.Const) and expr.unit is ir.Unit.MS:
            return number(expr.value / 1000)
        return self.value(expr)

    def outputs(self, op: ir.SetOutput) -> str:
        """`O` with one position per output (X keeps an output as it is, L3009)."""
        value = op.value
        if isinstance(value, ir.Pattern) and op.index is None:
            return value.bits
        if op.index is not None and isinstance(value, ir.Const) and value.value in (0, 1) and 1 <= op.index <= 6:
            return "X" * (op.index - 1) + str(int(value.value))
        if op.index is None and isinstance(value, ir.Const):
            return self.output_bank(value)
        if op.index is not None and not 1 <= op.index <= neutral.OUTPUTS:
            raise CannotWrite(f"output {op.index}: X150 has outputs 1-{neutral.OUTPUTS} (O, parker-x150.md L2731-L2753, "
                              f"L2779): use one of those in the source", "G003")
        raise CannotWrite("X150 sets outputs 1-6 to 0 or 1 with a constant pattern (O); this output change has "
                          "no equivalent", "G003")

    def enable_outputs(self, op: ir.Setting, span) -> None:
        """Another product's enable outputs as one mask (Arcus `EO=3`, arcus-pmx-4ex-sa.txt L748): for
        each axis the profile drives, its bit as ST0 (1: enabled) or ST1 (0: shut down), parker-x150.md
        L4010-L4031; the bits of axes the program never uses are drives X150 does not have
        (backends/enable_outputs.py). ST takes a constant: a mask computed at run time is refused."""
        driven = dict(self.axes) or {enable_outputs.source_axes(self.module)[0]: ""}
        for axis, address in driven.items():
            bit = enable_outputs.bit_of(self.module, axis)
            value = enable_outputs.enable_value(op.value, bit) if bit is not None else None
            if not isinstance(value, ir.Const):
                raise CannotWrite(f"X150 enables (ST0) or shuts down (ST1) the drive with a constant only (L4010-"
                                  f"L4031); this enable of axis {axis} (bit {bit} of the enable outputs) is known "
                                  "only at run time: set it with a number (EO=1, EO1=0)", "G003")
            self.emit((address if str(address).isdigit() else "") + ("ST0" if value.value else "ST1"), span)

    def output_bank(self, value: ir.Const) -> str:
        """A number for every output of the source at once (Arcus DO=7, MCode OT=5; output 1 in bit
        0: arcus-pmx-4ex-sa.txt L752, L1951; lexium-mcode.txt L851) as the O pattern of the outputs
        that source has (`[machine.outputs] count`, up to X150's 6: parker-x150.md L2731-L2753):
        DO=7 is O111000 (the PMX-4EX-SA's outputs 4-6 go off too), OT=5 is O101 (X150's outputs
        4-6 are left as they are, as the MCode drive has none). A value that turns on an output
        X150 lacks (DO=64) is refused: nothing on X150 would do what it does."""
        number_ = value.value
        if not (isinstance(number_, int) or float(number_).is_integer()) or number_ < 0:
            raise CannotWrite(f"the value {number(number_)} for every output at once is no pattern of outputs", "G003")
        bits = int(number_)
        source = in_force.source_profile(self.module, self.profile)
        count = source.get("machine.outputs.count", 0) if source is not None else 0
        if not isinstance(count, int) or isinstance(count, bool) or count <= 0:
            raise CannotWrite(f"the value {bits} sets every output of the source's bank at once; the source "
                              "product's outputs are not known (`[machine.outputs] count` in its profile), so "
                              "X150's pattern (O, L2731-L2753) cannot be chosen: set the outputs one by one", "G003")
        beyond = [n + 1 for n in range(neutral.OUTPUTS, max(bits.bit_length(), count)) if bits >> n & 1]
        if beyond:
            raise CannotWrite(f"the value {bits} turns on output {beyond[0]}, and X150 has outputs "
                              f"1-{neutral.OUTPUTS} (O, L2731-L2753): use outputs 1-{neutral.OUTPUTS} in the source",
                              "G003")
        return "".join(str(bits >> n & 1) for n in range(min(count, neutral.OUTPUTS)))

    def wait(self, cond) -> str:
        """TRE (until the inputs match) or TRN (until they do not) with one X150 pattern."""
        bits = neutral.from_cond(cond)
        if bits is not None:
            return "TRE" + bits
        if isinstance(cond, ir.Not) and (bits := neutral.from_cond(cond.cond)) is not None:
            return "TRN" + bits
        raise CannotWrite("X150 waits only for an input pattern (TRE/TRN)", "G003")

    def print_text(self, op: ir.Print) -> str:
        """The quote command sends ASCII 33-126 as written, '_' as a space (L5589), no line end."""
        item = op.items[0] if len(op.items) == 1 else None
        report = report_command(op)
        if report is not None:
            axis = neutral.report_axis(op) if report == "PR" else neutral.levels_report_of(op)[1] \
                if report in ("INL", "OUTL") else neutral.identity_report_of(op) if report == "QS" else item.axis
            if report == "PR" and self.factor_of(axis or ir.ALL_AXES) != 1:
                raise CannotWrite(f"X150 reports the position in its own user steps (PR); the source counts "
                                  f"{self.source_spr} steps/rev, the target {self.resolution}", "X207")
            return self.address(op.axis or axis or ir.ALL_AXES) + report
        sent = neutral.transmit_of(op)
        if sent is not None:
            return self.transmit(*sent)
        if op.formats:
            raise CannotWrite("X150 sends a formatted value only as TX (a text, then a variable with its decimals, "
                              "L4463-L4483) or as its reports (PR, INL, OUTL, QS); this print has no equivalent",
                              "G003")
        if any(isinstance(i, ir.Status) and i.meaning == "position" for i in op.items):
            raise CannotWrite("X150 sends a position only as its report, the sign always written (PR: *+4000, "
                              "*-25600, L3141); this print sends it in another form, which the host would read "
                              "differently", "G003")
        text = item.value if isinstance(item, ir.Text) and not op.signed else ""
        if text and not op.newline and len(text) <= 50 and all(c == " " or 33 <= ord(c) <= 126 for c in text) \
                and '"' not in text and "_" not in text:
            return '"' + text.replace(" ", "_") + '"'
        raise CannotWrite("X150 transmits up to 50 characters of quoted text without quotes, underscores or a "
                          "line end (\"...\", L5589); this print has no equivalent", "G003")

    def transmit(self, name: str, sign: bool, decimals: int, text: str) -> str:
        """TXn,m,p,x (L4463-L4483): x is the rest of the command, printable ASCII without a comma."""
        n = self.var_number(name)
        if not n:
            raise CannotWrite(f"X150 transmits only VAR1-VAR50 (TX); {name} has no equivalent", "G003")
        if not text or len(text) > 40 or any(not 33 <= ord(c) <= 126 or c in ',";' for c in text) or decimals > 5:
            raise CannotWrite("X150 transmits a variable after a text of printable characters without a comma, a "
                              "quote or a semicolon, with up to 5 decimals (TX, L4463-L4483); this print has no "
                              "equivalent", "G003")
        return f"TX{n},{1 if sign else 0},{decimals},{text}"

    def assign(self, op: ir.Assign) -> str:
        n = self.var_number(op.target.name)
        if not n:
            raise CannotWrite(f"X150 has only VAR1-VAR50; {op.target.name} has no equivalent", "G003")
        return f"VAR{n}={self.chain(op.value)}"

    def chain(self, expr) -> str:
        """A left-to-right chain (X150 has no precedence and no parentheses, L4638)."""
        rights = []
        while isinstance(expr, ir.BinOp) and expr.op in ARITHMETIC:
            if isinstance(expr.right, ir.BinOp):
                raise CannotWrite("X150 evaluates strictly left to right without parentheses; split this "
                                  "expression over several VARn= assignments")
            rights.append((expr.op, expr.right))
            expr = expr.left
        text = self.operand(expr)
        for op, right in reversed(rights):
            text += op + self.operand(right)
        return text

    def operand(self, expr) -> str:
        if isinstance(expr, ir.Const):
            if expr.unit not in (ir.Unit.NONE, ir.Unit.STEPS) or (expr.unit is ir.Unit.STEPS and not self.uniform()):
                raise CannotWrite(f"the {expr.unit.value or 'plain'} constant {number(expr.value)} in a calculation "
                                  "cannot be converted to X150 units")
            return number(expr.value)
        if isinstance(expr, ir.Var) and self.var_number(expr.name):
            return f"VAR{self.var_number(expr.name)}"
        if isinstance(expr, ir.Status) and expr.meaning in READINGS and expr.index is None:
            if self.factor_of(expr.axis or ir.ALL_AXES) != 1:
                raise CannotWrite(f"the {expr.meaning} cannot be rescaled from {self.source_spr} to "
                                  f"{self.resolution} steps/rev inside a calculation", "X207")
            return READINGS[expr.meaning]
        if isinstance(expr, ir.DeviceRef) and expr.dialect == DIALECT and expr.name in self.cat.sources:
            return expr.name
        if isinstance(expr, ir.UnOp) and expr.op == "-" and isinstance(expr.operand, ir.Const):
            return number(-expr.operand.value)
        raise CannotWrite(f"{describe(expr)} cannot be an X150 operand (VARn, a number, POS, ABS, ...)")

    def cond(self, cond) -> str:
        """A condition with the relations X150 has (> < =), at most two terms (L2009)."""
        if sum(1 for _ in ir.walk_expr(cond)) > MAX_CONDITION_NODES:
            raise CannotWrite(f"this condition has far more than the {self.cat.max_terms} terms an X150 condition "
                              "takes: split it over nested IFs")
        terms: list[str] = []
        joins: list[str] = []
        self.terms(expand(cond), terms, joins)
        if len(terms) > self.cat.max_terms or len(set(joins)) > 1:
            raise CannotWrite(f"this condition needs {len(terms)} X150 terms ({' '.join(joins)}); a condition has "
                              f"at most {self.cat.max_terms} joined by AND or OR: split it over nested IFs")
        out = terms[0]
        for join, term in zip(joins, terms[1:]):
            out += f" {join} {term}"
        return out

    def terms(self, cond, terms: list[str], joins: list[str]) -> None:
        if (bits := neutral.from_cond(cond)) is not None:  # input levels joined by and: one pattern
            terms.append("IN" + bits)
        elif isinstance(cond, ir.Logic):
            self.terms(cond.left, terms, joins)
            joins.append(cond.op.upper())
            self.terms(cond.right, terms, joins)
        elif isinstance(cond, ir.Compare) and cond.op in self.cat.relational:
            terms.append(self.operand(cond.left) + cond.op + self.operand(cond.right))
        else:
            raise CannotWrite(f"{describe(cond)} is not an X150 condition (VARn>x, VARn<x, VARn=x, IN<pattern>, "
                              "joined by AND or OR)")

    # -- native commands -----------------------------------------------------------------------------
    def native_text(self, op: ir.Native) -> str:
        mnemonic = op.mnemonic
        prefix = self.address(op.axis)
        if mnemonic == "!":
            return "!" + self.value(op.args[0]) if op.args else "!"
        info = self.cat.lookup(mnemonic)
        if info is None:
            raise CannotWrite(f"'{mnemonic}' is not an X150 command")
        buffered = "B" if op.form == "B" or (self.in_sequence and info.b_prefixable) else ""
        return prefix + buffered + mnemonic + self.argument(info, op.args)

    def argument(self, info: cat.Command, args: tuple) -> str:
        if not args:
            return ""
        kind = info.arg
        first = args[0]
        if kind in ("number", "int", "sequence"):
            return self.value(first)
        if isinstance(first, ir.Pattern):
            return first.bits
        if kind in ("in_func", "out_func"):
            return number(first.value) + args[1].value
        if kind == "string":
            return ("" if info.name == '"' else '"') + first.value + '"'
        if kind == "variable":
            n = self.var_number(first.name)
            return f"{n}" + (f"={self.chain(args[1])}" if len(args) > 1 else "")
        if kind == "condition":
            return f"({self.cond(first)})"
        if kind in ("composite", "raw"):
            return self.fields(info, args)
        raise CannotWrite(f"cannot write the argument of {info.name}")

    def fields(self, info: cat.Command, args: tuple) -> str:
        parts = []
        for spec, arg in zip(info.fields, args):
            parts.append(number(arg.value).rjust(spec.digits, "0") if spec.digits else number(arg.value))
        text = info.separator.join(parts)
        if info.tail and len(args) > len(info.fields):
            text += info.separator + args[len(info.fields)].value
        return text


def ends_with(nodes: list, kind=STOPS) -> bool:
    """The list never falls through: it ends in a stop (of `kind`)."""
    return bool(nodes) and isinstance(nodes[-1], EndNode) and isinstance(nodes[-1].term, kind)


def lift_gotos(nodes: list) -> list:
    """The tree with no XG written inside an IF where it can be avoided: an XG out of an IF leaves
    the IF open, and the target sequence must then begin with NIF (L1794, X112). An IF arm that ends
    in `XGn` loses it to after the NIF when the other path never reaches that point: the other arm
    ends in a stop (HALT, XRT, XG), or, with no ELSE, the rest of the list does (it becomes the
    ELSE). Bottom-up, so an XG lifted out of an inner IF can be lifted out of the outer one."""
    out: list = []
    nodes = [_lift_children(node) for node in nodes]
    index = 0
    while index < len(nodes):
        node = nodes[index]
        index += 1
        if not (isinstance(node, IfNode) and len(node.arms) == 1):
            out.append(node)
            continue
        cond, body = node.arms[0]
        orelse = node.orelse
        rest = nodes[index:]
        goto = None
        if ends_with(body, ir.GotoRoutine) and not orelse and rest and ends_with(rest):
            orelse, index = rest, len(nodes)  # the rest runs only when c is false: the ELSE
        if ends_with(body, ir.GotoRoutine) and orelse and (ends_with(orelse) and not same_goto(body, orelse)):
            goto, body = body[-1], body[:-1]
        elif ends_with(orelse, ir.GotoRoutine) and body and ends_with(body) and not same_goto(body, orelse):
            goto, orelse = orelse[-1], orelse[:-1]
        elif ends_with(body, ir.GotoRoutine) and same_goto(body, orelse):  # both arms go to one sequence
            goto, body, orelse = body[-1], body[:-1], orelse[:-1]
        if goto is None:
            out.append(IfNode([(cond, body)], orelse, node.spans, node.else_span, node.end_span) if orelse
                       is not node.orelse else node)
            continue
        if body or orelse:  # an IF left empty tests a condition for nothing (X150 conditions only read)
            out.append(IfNode([(cond, body)], orelse, node.spans, node.else_span, node.end_span))
        out.append(goto)
    return out


def _lift_children(node):
    if isinstance(node, IfNode):
        return IfNode([(c, lift_gotos(b)) for c, b in node.arms], lift_gotos(node.orelse), node.spans,
                      node.else_span, node.end_span)
    if isinstance(node, (WhileNode, RepeatNode)):
        return dataclasses.replace(node, body=lift_gotos(node.body))
    return node


def same_goto(a: list, b: list) -> bool:
    return ends_with(a, ir.GotoRoutine) and ends_with(b, ir.GotoRoutine) and a[-1].term.routine == b[-1].term.routine


def is_true(cond) -> bool:
    return isinstance(cond, ir.Compare) and cond.op == "=" and isinstance(cond.left, ir.Const) \
        and isinstance(cond.right, ir.Const) and cond.left.value == cond.right.value


def counters_read(nodes: list) -> set[str]:
    """The hidden L-loop counters a structured routine reads other than as `Ln .. N` (such a counter
    is written as a variable, and its count must be written too). An explicit stack, not a
    recursive closure: a check or compile makes no reference cycles (docs/PERFORMANCE.md)."""
    found: set[str] = set()
    exprs: list = []
    stack = list(nodes)
    while stack:
        node = stack.pop()
        if isinstance(node, Simple):
            exprs.extend(ir.op_exprs(node.op))
        elif isinstance(node, IfNode):
            for cond, body in node.arms:
                exprs.append(cond)
                stack.extend(body)
            stack.extend(node.orelse)
        elif isinstance(node, WhileNode):
            exprs.append(node.cond)
            stack.extend(node.body)
        elif isinstance(node, RepeatNode):
            if counted(node):
                stack.extend(unnested(node.body)[:-1])
            else:
                exprs.append(node.until)
                stack.extend(node.body)
    for expr in exprs:
        found.update(e.name for e in ir.walk_expr(expr) if isinstance(e, ir.Var) and e.name.startswith(LOOP_PREFIX))
    return found


def unnested(body: list) -> list:
    """`IF(c) .. (never falls through) ELSE rest NIF` as `IF(c) .. NIF rest`: the same program, with
    what follows the IF at the loop's level again (so an L loop's closing `N` is found after it)."""
    if body and isinstance(body[-1], IfNode) and body[-1].orelse \
            and all(ends_with(arm) for _, arm in body[-1].arms):
        last = body[-1]
        return body[:-1] + [IfNode(last.arms, [], last.spans, None, last.end_span)] + unnested(last.orelse)
    return body


def counted(node: RepeatNode) -> str | None:
    """The counter of an X150 L loop: `until %Lk = 0` after a body ending in `%Lk = %Lk - 1`."""
    until = node.until
    body = unnested(node.body)
    if not (isinstance(until, ir.Compare) and until.op == "=" and isinstance(until.left, ir.Var)
            and until.left.name.startswith(LOOP_PREFIX) and isinstance(until.right, ir.Const)
            and until.right.value == 0 and body):
        return None
    last = body[-1]
    name = until.left.name
    if isinstance(last, Simple) and isinstance(last.op, ir.Assign) and last.op.target.name == name \
            and isinstance(last.op.value, ir.BinOp) and last.op.value.op == "-" \
            and isinstance(last.op.value.left, ir.Var) and last.op.value.left.name == name:
        return name
    return None


def op_axes(op) -> tuple[str, ...]:
    if isinstance(op, ir.Move):
        return tuple(axis for axis, _ in op.targets)
    if isinstance(op, ir.Arc):
        return op.axes
    axis = getattr(op, "axis", "")
    return (axis,) if isinstance(axis, str) and not isinstance(op, ir.Native) else ()


def ends(span: Span | None) -> tuple[Span | None, Span | None]:
    """The first and the last character of a span: a Move made of `D..` and `G` (or a sequence's `XE`
    and `XD`) maps each written line back to its own source line."""
    if span is None or span.line == span.end_line:
        return span, span
    first = Span(span.file, span.line, span.column, span.line, span.column + 1, span.start, span.start + 1)
    last = Span(span.file, span.end_line, max(1, span.end_column - 1), span.end_line, span.end_column,
                max(span.start, span.end - 1), span.end)
    return first, last


SPLIT = {"!=": ("<", ">"), "<=": ("<", "="), ">=": (">", "=")}  # as two terms joined by OR
NEGATED = {"<": ">=", ">": "<=", "=": "!=", "!=": "=", "<=": ">", ">=": "<"}


def expand(cond):
    """The condition with NOT pushed into comparisons and != <= >= split into X150's > < = terms."""
    if isinstance(cond, ir.Not):
        inner = cond.cond
        if isinstance(inner, ir.Not):
            return expand(inner.cond)
        if isinstance(inner, ir.Compare) and inner.op in NEGATED:
            if neutral.level(inner) is not None:
                return ir.Compare(NEGATED[inner.op], inner.left, inner.right, inner.span)
            return expand(ir.Compare(NEGATED[inner.op], inner.left, inner.right, inner.span))
        if isinstance(inner, ir.Logic):  # De Morgan
            flipped = "or" if inner.op == "and" else "and"
            return ir.Logic(flipped, expand(ir.Not(inner.left)), expand(ir.Not(inner.right)), inner.span)
        return cond
    if isinstance(cond, ir.Compare) and cond.op in SPLIT and neutral.level(cond) is None:
        first, second = SPLIT[cond.op]
        return ir.Logic("or", ir.Compare(first, cond.left, cond.right, cond.span),
                        ir.Compare(second, cond.left, cond.right, cond.span), cond.span)
    if isinstance(cond, ir.Logic):
        return ir.Logic(cond.op, expand(cond.left), expand(cond.right), cond.span)
    return cond


def variable_number(name: str) -> int:
    if name.upper().startswith("VAR") and name[3:].isdigit():
        return int(name[3:])
    return 0


def describe(expr) -> str:
    if isinstance(expr, ir.Var):
        return f"the variable {expr.name}"
    if isinstance(expr, ir.DeviceRef):
        return f"the {expr.dialect} reading {expr.name}"
    if isinstance(expr, ir.Status):
        return f"the reading '{expr.meaning}'"
    if isinstance(expr, ir.Not):
        return "this negated condition"
    return f"this {type(expr).__name__.lower()}"


LEVELS = ("input_active_high", "output_active_high", "switch_active_high")
LEVEL_COUNTS = {"input_active_high": neutral.USER_INPUTS, "output_active_high": neutral.OUTPUTS,
                "switch_active_high": len(neutral.DEDICATED)}


def level_command(name: str, bits: str) -> str:
    """INL_<user inputs>, INL<dedicated inputs>_ (L2136: LMT+ ... INDEX, then I1-I10) or OUTL<outputs>."""
    return {"input_active_high": "INL_" + bits, "switch_active_high": "INL" + bits + "_"}.get(name, "OUTL" + bits)


def level_run(nodes: list, index: int) -> list:
    """The level settings of one kind and device that follow each other from `index`, each line once."""
    first = nodes[index].op
    if not (isinstance(first, ir.Setting) and first.name in LEVELS):
        return [first]
    group = [first]
    for node in nodes[index + 1:]:
        op = node.op if isinstance(node, Simple) else None
        # INL's dedicated levels and its user inputs' make one INL (`INLXXXX10X_1XX1X0XX`)
        names = (first.name, "input_active_high") if first.name == "switch_active_high" else (first.name,)
        if not (isinstance(op, ir.Setting) and op.name in names and op.axis == first.axis
                and (op.name, op.index) not in {(o.name, o.index) for o in group}):
            break
        group.append(op)
    return group


# The readings X150 reports with a command of their own, a line each: PR (*-25600, L3141, the print
# `neutral.position_report` makes), the setting queries 1FOL (FOLLOWING PERCENT = n%, L1569), 1INL and
# 1OUTL (*bbbbbbb_bbbbbbbbbb, L2134)
REPORTS = {"following_ratio": "FOL"}


def report_command(op: ir.Print) -> str | None:
    """The X150 report a print is, when it is a line with one such reading alone, or the shape the
    lowering gives INL, OUTL (compiler/x150/neutral.levels_report) and QS (identity_report)."""
    if neutral.report_axis(op) is not None:
        return "PR"
    levels = neutral.levels_report_of(op)
    if levels is not None:
        return levels[0]
    if neutral.identity_report_of(op) is not None:
        return "QS"
    if op.formats:
        return None
    if len(op.items) == 1 and isinstance(op.items[0], ir.Status) and op.items[0].index is None and op.newline \
            and not op.signed:
        return REPORTS.get(op.items[0].meaning)
    return None


def without_trace_reports(module: ir.Module) -> ir.Module:
    """The module without its trace reports (`Print.traced`): an X150 in trace mode reports each
    command it runs by itself (XTR, L5384-L5433), so they are not written. A copy when it has some."""
    if not any(isinstance(op, ir.Print) and op.traced for _, block in module.blocks() for op in block.ops):
        return module
    copy = ir.copy_module(module)
    for _, block in copy.blocks():
        block.ops[:] = [op for op in block.ops if not (isinstance(op, ir.Print) and op.traced)]
    return copy


def describe_setting(name: str) -> str:
    info = ir_names.SETTINGS.get(name)
    return info.meaning if info is not None else "not a neutral setting"


def describe_op(op) -> str:
    names = {ir.Arc: "an arc or circle (interpolation of two axes)", ir.Home: "a homing move",
             ir.Setting: "the setting", ir.Slew: "a slew"}
    text = names.get(type(op), type(op).__name__)
    if isinstance(op, ir.Setting):
        text += f" '{op.name}'"
    return text


def write(module: ir.Module, profile: Profile) -> Written:
    return Writer(module, profile).write_module()


# One handler per operation of the table (compiler/ir_ops.py) that X150 can write; the others (an
# arc: X150 moves one axis per device) are refused at their line by `Writer.write_one`.
WRITE_METHODS = {
    ir.Native: Writer._write_native,
    ir.SetMotion: Writer.motion,
    ir.Move: Writer.move,
    ir.Slew: Writer.slew,
    ir.Stop: Writer._write_stop,
    ir.Delay: Writer._write_delay,
    ir.WaitInput: Writer._write_wait_input,
    ir.Home: Writer._write_home,
    ir.WaitMotion: Writer._write_wait_motion,
    ir.SetOutput: Writer._write_output,
    ir.DriveEnable: Writer._write_drive_enable,
    ir.SetPosition: Writer._write_set_position,
    ir.Assign: Writer._write_assign,
    ir.Save: Writer._write_save,
    ir.Call: Writer._write_call,
    ir.SetHandler: Writer.handler,
    ir.Print: Writer._write_print,
    ir.Setting: Writer._write_setting,
    ir.Pause: Writer._write_host_control,
    ir.Resume: Writer._write_host_control,
    ir.Step: Writer._write_host_control,
}
