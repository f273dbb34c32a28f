"""Lowering an X150 syntax tree to the shared IR.

- Each unit (structure.py) becomes a routine, in stream order: a sequence `XDn ... XT` a routine
  named SEQn (SEQn@a when defined for device a, see naming.py) with `number = n`; each stretch of
  commands outside sequences an IMMEDIATE routine. A sequence selected by XP is the POWERUP
  routine, by XFK or XWHEN a HANDLER, one run by XR/GOSUB a SUBROUTINE, any other MAIN.
- The structured constructs become blocks (docs/dialects/x150.md, "IR mapping"):
  `IF(c) .. ELSE .. NIF` a Branch to then/else blocks that jump to a join block;
  `WHILE(c) .. NWHILE` a head block holding only the Branch, the body jumping back to it;
  `REPEAT .. UNTIL(c)` a body whose last block branches back while c is false;
  `Ln .. N` a hidden counter `%Lk` (a declared int32 variable): `%Lk = n` before the body, and at
  N `%Lk = %Lk - 1` then a Branch back while `%Lk != 0`, so `L`/`L0` (infinite, L2328) never
  reaches zero. The blocks are laid out in source order; the backend rebuilds the constructs from
  these shapes.
- XR/GOSUB → Call, XG/GOTO → GotoRoutine, XRT → Return, XT → FallOff (the executable end),
  XP/XFK/XWHEN → SetHandler("power"/"fault"/"when", SEQn), WHEN(c) → SetHandler("when", args=(c,)).
- Motion, in the IR's units (docs/IR.md): A/V → SetMotion in steps/s² and steps/s (rev × the
  module's steps per revolution, the program's first CUR); CUR → SetMotion(RESOLUTION); D, H, H+,
  H- → assignments to the hidden distance register `%D<device>`; G → a placeholder Move that
  modes.py resolves by data flow into Move(ABSOLUTE|RELATIVE) + WaitMotion, or Slew in MC (the
  mode commands disappear into the moves); T → Delay (s); TRE/TRN → WaitInput(InputMatch) /
  WaitInput(Not(...)); TRIP → WaitMotion; PZ → SetPosition(0); GH n → Home(speed) + WaitMotion;
  O → SetOutput; HALT → End; the configuration commands of neutral.SETTINGS → Setting;
  the quote command and the reports PR (neutral.position_report: `*`, the signed position), 1FOL, 1INL,
  1OUTL → Print (of a Status reading); PS →
  Pause (motion runs on), C → Resume, #n → Step; VARn= → Assign (left to right; POS/ABS are Status readings); SV → Save.
  Everything else is Native("x150", mnemonic, args as written, form="B" when B-prefixed, axis).
- Device addresses are axes "1".."32", "*" for none. Operations without an axis field (Assign,
  Delay, WaitInput, Save, Call, ...) take the routine's device; where a command's address differs
  from its routine's (a stream mixing devices), it stays Native so the address is kept.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field
from fractions import Fraction

from mcc.compiler import ir, ir_names
from mcc.compiler.diagnostics import Diagnostics
from mcc.compiler import homing
from mcc.compiler.profiles import Profile
from mcc.compiler.x150 import catalog as cat
from mcc.compiler import units
from mcc.compiler.x150 import modes, naming, neutral
from mcc.compiler.x150 import syntax as st
from mcc.compiler.x150.structure import Unit, sequence_number, split_units

DIALECT = "x150"
UNITS = {"user steps": ir.Unit.STEPS, "steps": ir.Unit.STEPS, "s": ir.Unit.S, "%": ir.Unit.PERCENT}
RATES = {"rev/s^2": ir.Unit.STEPS_PER_S2, "rev/s": ir.Unit.STEPS_PER_S}  # converted with the resolution
MOTION = {"accel": ir.MotionParam.ACCEL, "max_speed": ir.MotionParam.MAX_SPEED}
READINGS = {"POS": "position", "ABS": "encoder"}  # chain sources with a neutral meaning (L4591-L4592)
DIRECTION = {"H": "-", "H+": "abs", "H-": "-abs"}  # what H, H+ and H- do to the distance register
HANDLERS = {"powerup": "power", "fault_handler": "fault", "event_handler": "when"}
ROLE_KINDS = {"call": ir.RoutineKind.SUBROUTINE, "powerup": ir.RoutineKind.POWERUP,
              "fault_handler": ir.RoutineKind.HANDLER, "event_handler": ir.RoutineKind.HANDLER}
KIND_RANK = {ir.RoutineKind.POWERUP: 3, ir.RoutineKind.HANDLER: 2, ir.RoutineKind.SUBROUTINE: 1,
             ir.RoutineKind.MAIN: 0}
# The roles and the mnemonics `Lowering.simple` lowers to a neutral operation (each of its cases asks
# for one of them); any other command is a Native at once, without asking every case.
NEUTRAL_ROLES = frozenset((*MOTION, "distance", "go", "home", "delay", "wait_input", "assign", "save", "return",
                           "when"))
NEUTRAL_NAMES = frozenset((*DIRECTION, "CUR", "O", "TRIP", "PZ", '"', "PR", "SB", "ST", *neutral.SETTINGS,
                           "IN", "OUT", "INL", "OUTL", "HALT", "PS", "C", "#", "TX", "QS"))
# Queries that report a setting in force (`1FOL` -> FOLLOWING PERCENT = n%, L1569; `1INL` ->
# *0000000_0000000000, L2134): a print of the setting's reading
SETTING_REPORTS = {"FOL": "following_ratio", "INL": "input_levels", "OUTL": "output_levels"}
OPENERS = {"loop": "L", "if": "IF", "while": "WHILE", "repeat": "REPEAT"}
CLOSERS = {"loop_end": "L", "endif": "IF", "endwhile": "WHILE", "until": "REPEAT", "else": "IF"}
CLOSER_NAMES = {"L": "N", "IF": "NIF", "WHILE": "NWHILE", "REPEAT": "UNTIL(...)"}
LOOP_VAR = "%L"
# A quoted command string that starts a sequence on another device (`1"2XR3"`, L5593: the quote
# command is used "to command other devices to move"; the example L5614 starts sequence 1 on unit 2)
REMOTE_RUN = re.compile(r"(\d+)(XR|GOSUB)(\d+)", re.IGNORECASE)


@dataclass
class Frame:
    """An open construct while lowering: its kind, opener, and the blocks it must wire up."""

    kind: str  # L IF WHILE REPEAT
    opener: st.Command
    head: str = ""  # L/WHILE/REPEAT: the block to go back to
    exit: str = ""  # WHILE: the block after the loop
    counter: str = ""  # L: the hidden counter variable
    count: object = None  # L: the count it starts from (an IR expression)
    branch: ir.Branch | None = None  # IF: the conditional branch, its `otherwise` patched by ELSE/NIF
    ends: list[ir.Jump] = field(default_factory=list)  # IF: jumps to the join, patched at NIF
    else_seen: bool = False


@dataclass
class Site:
    """Where a sequence is named (a call, goto or handler selection), for the whole-program checks."""

    command: st.Command
    kind: str  # call | goto | handler
    number: int | None  # None: through a variable
    targets: tuple[str, ...]  # routines the command may run (defined in this file)
    routine: str  # the routine it is written in
    depth: dict[str, int]  # open constructs at the site, by kind
    unit: Unit


class Lowering:
    def __init__(self, tree: st.SyntaxTree, profile: Profile, diags: Diagnostics):
        self.tree = tree
        self.profile = profile
        self.diags = diags
        self.cat = cat.load()
        self.module = ir.Module(DIALECT, profile.name, path=tree.path)
        self.units: list[Unit] = []
        self.sites: list[Site] = []
        self.leading_nifs: dict[str, int] = {}  # routine -> NIFs before its first other command
        self.max_depth: dict[str, dict[str, int]] = {}  # routine -> deepest nesting of each construct
        self.nesting = int(profile.get("limits.nesting", self.cat.limit("nesting", default=16)))
        self.defined: set[str] = set()
        self.device_list: list[int] = []  # devices that have sequences defined for them
        self.generated = 0
        self.counters = 0
        self.unit: Unit | None = None
        self.routine: ir.Routine | None = None
        self.block: ir.Block | None = None
        self.device: int | None = None
        self.device_axis = ir.ALL_AXES
        self.frames: list[Frame] = []
        self.leading = True
        self.after_skip: st.Command | None = None  # the SKE/SKN whose next command may be skipped

    # -- driver ----------------------------------------------------------------------------------
    def run(self) -> ir.Module:
        self.cur: dict[str, int] = {}  # user steps per revolution of each device (CUR)
        self.factors: dict[int, Fraction] = {}  # CUR -> IR steps per user step (see `distance`)
        # One pass over the commands for what the lowering needs to know of the whole file first:
        # the addresses written, the CUR commands (`resolution`), and whether the trace is on.
        addresses: set[int] = set()
        resolutions: list[st.Command] = []
        tracing = False
        for command in self.tree.commands():
            if command.address is not None:
                addresses.add(command.address)
            mnemonic = command.mnemonic
            if mnemonic == "CUR":
                resolutions.append(command)
            elif mnemonic == "XTR" or mnemonic == "XST":
                tracing = True
        self.addresses = addresses
        self.own_device: dict[int, bool] = {}  # address -> `fits` for a command outside a sequence
        self.module.steps_per_rev = self.resolution(resolutions)
        self.units = split_units(self.tree, self.diags)
        self.on_receipt: dict[int, ir.Native] = {}  # an immediate setting's op -> the command as written
        # trace reports (XTR, L5384-L5433): only a program that turns the trace on sends them; they
        # also mark where each command starts, which single step (XST, L5330-L5345) counts
        self.tracing = tracing
        self.name_units()
        self.device_list = sorted({u.address for u in self.units if u.is_sequence and u.address is not None})
        kinds = self.routine_kinds()
        for unit in self.units:
            self.lower_unit(unit, kinds)
        self.module.externals = external_routines(self.module)
        devices = {str(a) for a in self.profile.axes} | {str(a) for a in self.addresses}
        modes.resolve(self.module, self.diags, tuple(sorted(devices, key=lambda d: (len(d), d))))
        neutral.stops_in_turn(self.module, self.on_receipt)  # after the modes: only then is it known which G waits
        neutral.loops_ended_on_receipt(self.module, LOOP_VAR)
        return self.module

    def resolution(self, commands: list[st.Command]) -> int:
        """User steps per revolution: the CUR the program sets with a number (the IR's step), else
        the profile's. A second, different CUR or a CUR(VARn) is reported (X141): positions written
        after it are in other steps than mcc converts with. `commands`: the file's CUR commands."""
        found: int | None = None
        for command in commands:
            if command.info is None or not command.ok or command.arg is None:
                continue
            arg = command.arg
            device = str(command.address) if command.address is not None else ir.ALL_AXES
            earlier = self.cur.get(device)
            if isinstance(arg, st.Number) and isinstance(arg.value, int) and arg.value > 0 \
                    and (earlier is None or earlier == arg.value):
                self.cur[device] = arg.value
                found = found or arg.value
                continue
            self.diags.add("X143", command.span,
                           f"the user resolution changes here ({command.text}) after CUR{earlier} (or is not known "
                           "statically): mcc converts every distance of this device with its first CUR, so "
                           "positions after this line are not what it reports; set CUR once per device, with a "
                           "number, before the first move")
        return found or self.profile.steps_per_rev

    def distance(self, arg, axis: str):
        """A distance in user steps of its device (CUR) as IR steps (the module's first CUR)."""
        cur = self.cur.get(axis, self.cur.get(ir.ALL_AXES))
        if cur is None and axis == ir.ALL_AXES:
            # an unaddressed distance on a one-device chain is that device's: `1CUR2000` then `D4000`
            # is 2 revolutions (parker-x150.md L742-L745), not 4000 steps at the profile's CUR
            devices = {str(a) for a in self.profile.axes} | {str(a) for a in self.addresses}
            if len(devices) == 1:
                cur = self.cur.get(next(iter(devices)))
        if cur is None:
            cur = self.profile.steps_per_rev or self.module.steps_per_rev
        factor = self.factors.get(cur)
        if factor is None:  # a Fraction is slow to make and to compare: once per resolution
            factor = self.factors[cur] = Fraction(self.module.steps_per_rev, cur) if cur else Fraction(1)
        if factor == 1:
            return self.value(arg, None, ir.Unit.STEPS)
        if isinstance(arg, st.Number):
            scaled = Fraction(arg.value) * factor if isinstance(arg.value, int) else arg.value * float(factor)
            value = int(scaled) if isinstance(scaled, Fraction) and scaled.denominator == 1 else float(scaled)
            return ir.Const(value, ir.Unit.STEPS, arg.span)
        return ir.BinOp("*", self.value(arg, None), ir.Const(float(factor), ir.Unit.NONE), getattr(arg, "span", None))
    def name_units(self) -> None:
        copies: dict[tuple[int, int | None], int] = {}
        streams = 0
        for unit in self.units:
            if unit.is_sequence:
                key = (unit.number if unit.number is not None else 0, unit.address)
                copies[key] = copies.get(key, 0) + 1
                if copies[key] == 2:
                    first = next(u for u in self.units if u.is_sequence and (u.number or 0, u.address) == key)
                    self.diags.add("X132", unit.start.span,
                                   f"sequence {unit.number} is defined again (first at line {first.start.span.line}); "
                                   "the controller keeps one sequence per number: renumber one of them")
                unit.name = naming.sequence_name(key[0], unit.address, copies[key])
                self.defined.add(unit.name)
            else:
                streams += 1
                unit.name = naming.immediate_name(streams, unit.device())

    def routine_kinds(self) -> dict[str, ir.RoutineKind]:
        """Sequences selected by XP are POWERUP, by XFK/XWHEN HANDLERs, run by XR/GOSUB (or reached
        by GOTO/XG from another sequence or the stream) SUBROUTINEs."""
        kinds: dict[str, ir.RoutineKind] = {}
        for unit in self.units:
            device = unit.address if unit.is_sequence else None
            for command in unit.commands:
                info = command.info
                if info is None:
                    continue
                remote = self.remote_run(command, device) if command.mnemonic == '"' else None
                if remote is not None:  # a sequence another device is told to run: a subroutine
                    for name in self.resolve(remote[1], remote[0]):
                        if KIND_RANK[ir.RoutineKind.SUBROUTINE] > KIND_RANK[kinds.get(name, ir.RoutineKind.MAIN)]:
                            kinds[name] = ir.RoutineKind.SUBROUTINE
                    continue
                kind = ROLE_KINDS.get(info.ir)
                if info.ir == "goto":
                    # a sequence that another one or the stream jumps to runs when that one gets
                    # there (GOTO/XG, L1788), never on its own: not the program's main routine,
                    # which the simulator would run once more after the stream (docs/SIMULATOR.md)
                    kind = ir.RoutineKind.SUBROUTINE
                if kind is None or not command.ok:
                    continue
                number = sequence_number(command)
                if not number:
                    continue
                for name in self.resolve(number, command.address if command.address is not None else device):
                    if info.ir == "goto" and name == unit.name:
                        continue  # a sequence that starts itself again is still run by something else or main
                    if KIND_RANK[kind] > KIND_RANK[kinds.get(name, ir.RoutineKind.MAIN)]:
                        kinds[name] = kind
        return kinds

    def remote_run(self, command: st.Command, device: int | None) -> tuple[int, int] | None:
        """(device, sequence) when `command` is a quote whose text starts a sequence on another
        device (`1"2XR3"`): the sender transmits the text over the daisy chain, where device 2
        receives it as a command (L5593, example L5614). The sender is the command's address, else
        the sequence's device, else the profile's one device; None for any other quote."""
        arg = command.arg
        if command.mnemonic != '"' or not isinstance(arg, st.Text) or command.buffered or not command.ok:
            return None
        match = REMOTE_RUN.fullmatch(arg.text)
        if match is None:
            return None
        sender = command.address if command.address is not None else device
        axes = [str(a) for a in self.profile.axes]
        if sender is None and len(axes) == 1 and axes[0].isdigit():
            sender = int(axes[0])
        target, number = int(match.group(1)), int(match.group(3))
        if sender is None or target == sender or not 1 <= target <= 32 or not 1 <= number <= 64:
            return None
        return target, number

    def resolve(self, number: int, address: int | None) -> tuple[str, ...]:
        """The routines of this file a command naming sequence `number` may run."""
        if address is None:
            exact = naming.sequence_name(number, None)
            if exact in self.defined:
                return (exact,)
            return tuple(n for n in (naming.sequence_name(number, d) for d in self.device_list) if n in self.defined)
        return tuple(n for n in naming.candidates(number, address) if n in self.defined)[:1]

    # -- units, routines, blocks -----------------------------------------------------------------
    def lower_unit(self, unit: Unit, kinds: dict[str, ir.RoutineKind]) -> None:
        span = unit.start.span if unit.start is not None else (unit.commands[0].span if unit.commands else None)
        if unit.erase is not None and span is not None:
            span = unit.erase.span.to(span)  # XEn XDn: the backend maps each of the two lines back
        if unit.is_sequence:
            kind = kinds.get(unit.name, ir.RoutineKind.MAIN)
            number = unit.number
        else:
            kind, number = ir.RoutineKind.IMMEDIATE, None
        self.unit = unit
        self.routine = ir.Routine(unit.name, kind, span=span, number=number)
        self.module.routines.append(self.routine)
        self.device = naming.device_of(unit.name)
        self.device_axis = str(self.device) if self.device is not None else ir.ALL_AXES  # `axis` without an address
        self.frames = []
        self.after_skip = None
        self.leading = unit.is_sequence
        self.leading_nifs[unit.name] = 0
        self.block = None
        self.new_block(span)
        for command in unit.commands:
            self.lower_command(command)
        end = unit.end or unit.start
        if self.tracing and unit.is_sequence and unit.end is not None:
            self.trace(unit.end)
        self.close_all(end, "XT" if unit.is_sequence else "the end of the stream")
        end_span = unit.end.span if unit.end is not None else self.block.span
        if self.block.terminator is not None and unit.end is not None:
            self.new_block(end_span)  # the XT after an XG/XRT: kept for the source map
        if self.block.terminator is None:
            self.block.terminator = ir.FallOff(end_span)

    def label(self) -> str:
        self.generated += 1
        return f"%{self.generated}"

    def new_block(self, span, label: str | None = None) -> ir.Block:
        block = ir.Block(label or self.label(), span=span)
        self.routine.blocks.append(block)
        self.block = block
        return block

    def live_block(self, span) -> ir.Block:
        """The block to add to; after a terminator (XG, XRT) the code that follows is kept in a new,
        unreachable block so the backend writes it back."""
        if self.block.terminator is not None:
            self.new_block(span)
        return self.block

    def emit(self, op) -> None:
        block = self.block  # `live_block`, without a call for each of the program's operations
        if block.terminator is not None:
            block = self.new_block(op.span)
        block.ops.append(op)

    def terminate(self, term) -> None:
        self.live_block(term.span).terminator = term

    # -- commands ----------------------------------------------------------------------------------
    def axis(self, command: st.Command) -> str:
        address = command.address
        return str(address) if address is not None else self.device_axis

    def fits(self, command: st.Command) -> bool:
        """True when the routine's device says the command's address (so an address-less IR
        operation loses nothing), or the address is the one device the profile drives (a command
        addressed to the device itself)."""
        if self.device is not None or command.address is None:
            return True
        found = self.own_device.get(command.address)
        if found is None:  # once per address: the file's addresses and the profile do not change
            found = self.own_device[command.address] = self.addresses == {command.address} \
                and [str(command.address)] == [str(a) for a in self.profile.axes]
        return found

    def sender(self, command: st.Command) -> str:
        """The device a report comes from (`Print.axis`): empty when the routine's device says it."""
        return "" if self.fits(command) else str(command.address)

    def lower_command(self, command: st.Command) -> None:
        info = command.info
        if info is None and not command.host:
            return
        if info is None:
            role = ""
        elif info.name == command.mnemonic:  # the catalog entry the token was read as: `lookup` would find it
            role = info.ir
        else:  # VARn=FUN and the like: the entry of the statement, the role of the token (VAR)
            token = self.cat.lookup(command.mnemonic)
            role = token.ir if token is not None else ""
        structural = role in OPENERS or role in CLOSERS
        if command.problems and not structural:
            return
        if self.leading and not (role == "endif" and not self.frames):
            self.leading = False
        skip, self.after_skip = self.after_skip, (command if role == "skip" else None)
        if skip is not None and structural:
            self.diags.add("X133", skip.span,
                           f"{skip.mnemonic} skips the next command, here {command.text}: skipping one end of a "
                           f"construct unbalances the {'sequence' if self.unit.is_sequence else 'stream'} "
                           "(L3772, L3814); put a command such as T0.001 in between, or use IF(IN...)")
        if self.tracing and self.unit.is_sequence:
            self.trace(command)
        if role in OPENERS:
            self.open(command, OPENERS[role])
        elif role in CLOSERS:
            self.close(command, role)
        elif role in ("call", "goto") or role in HANDLERS:
            self.transfer(command, role)
        else:
            self.simple(command, role, skip)

    def simple(self, command: st.Command, role: str, skip: st.Command | None = None) -> None:
        info = command.info
        arg = command.arg
        span = command.span
        axis = self.axis(command)
        if command.host:
            self.emit(ir.Native(DIALECT, "!", (self.expr(arg),), axis=axis, span=span))
            return
        name = command.mnemonic
        if role not in NEUTRAL_ROLES and name not in NEUTRAL_NAMES:
            self.emit(self.native(command))
            return
        fits = self.fits(command) and not command.buffered
        axis_ok = not command.buffered  # operations that carry the axis keep the address themselves
        if role in MOTION and arg is not None and axis_ok:
            value = self.value(arg, info)
            self.emit(ir.SetMotion(MOTION[role], axis, value, span))
            if MOTION[role] is ir.MotionParam.ACCEL:  # X150 decelerates at A too (one ramp rate)
                self.emit(ir.SetMotion(ir.MotionParam.DECEL, axis, value, span))
        elif role == "distance" and arg is not None and axis_ok and not isinstance(arg, st.Pattern):
            self.emit(ir.Assign(ir.Var(modes.distance_var(axis), span), self.distance(arg, axis), span))
        elif name in DIRECTION and arg is None and axis_ok:
            var = ir.Var(modes.distance_var(axis), span)
            how = DIRECTION[name]
            value = ir.UnOp("-", var, span) if how == "-" else ir.Func("abs", (var,), span)
            if how == "-abs":
                value = ir.UnOp("-", value, span)
            self.emit(ir.Assign(var, value, span))
        elif role == "go" and arg is None and axis_ok:
            self.emit(ir.Move(ir.MoveMode.MODAL, ((axis, ir.Var(modes.distance_var(axis), span)),), span=span))
        elif name == "CUR" and isinstance(arg, st.Number):  # BCUR in a sequence is the same setting
            self.emit(ir.SetMotion(ir.MotionParam.RESOLUTION, axis, ir.Const(arg.value, ir.Unit.NONE, arg.span), span))
        elif name == "O" and isinstance(arg, st.Pattern) and fits:
            self.emit(self.outputs(arg, span))
        elif name == "TRIP" and arg is None and axis_ok:
            self.emit(ir.WaitMotion(axis, span))
        elif role == "home" and isinstance(arg, st.Number) and arg.value != 0 and axis_ok:
            # GH n: seek the home input at |n| rev/s in the sign's direction (L1711-L1713); the next
            # command runs once homing has ended ("use the SP command after the GH is complete", L1715)
            speed = ir.Const(units.revs_to_steps(abs(arg.value), self.module.steps_per_rev), ir.Unit.STEPS_PER_S,
                             arg.span)
            self.emit(homing.home_op(self.profile, self.module.steps_per_rev, axis, "switch",
                                     1 if arg.value > 0 else -1, span, speed=speed))
            self.emit(ir.WaitMotion(axis, span))
        elif name == "PZ" and arg is None and axis_ok:
            self.emit(ir.SetPosition(axis, ir.Const(0, ir.Unit.STEPS, span), span))
        elif role == "delay" and arg is not None and fits:
            self.emit(ir.Delay(self.value(arg, info), span))
        elif role == "wait_input" and isinstance(arg, st.Pattern) and fits:
            cond: ir.Cond = neutral.to_cond(arg.bits, axis, arg.span)
            if info.entry.get("negated", False):
                cond = ir.Not(cond, arg.span)
            self.emit(ir.WaitInput(cond, span))
        elif role == "assign" and isinstance(arg, st.VarStatement) and arg.value is not None and fits \
                and self.neutral_chain(arg.value):
            self.declare(arg.var)
            self.emit(ir.Assign(ir.Var(arg.var.name, arg.var.span), self.chain(arg.value, axis), span))
        elif role == "save" and fits:
            self.emit(ir.Save(span))
        elif (remote := self.remote_run(command, self.device)) is not None:  # 1"2XR3": device 2 runs sequence 3
            device, number = remote
            targets = self.resolve(number, device)
            self.sites.append(Site(command, "call", number, targets, self.routine.name, self.depths(), self.unit))
            self.emit(ir.Call(targets[0] if targets else naming.sequence_name(number, device), None, span))
        elif name == '"' and isinstance(arg, st.Text) and not command.buffered:  # '_' is sent as a space (L5589)
            self.emit(ir.Print((ir.Text(arg.text.replace("_", " "), arg.span),), False, span, self.sender(command)))
        elif name == "PR" and arg is None and not command.buffered:  # the position counter, e.g. *-25600 (L3141)
            self.emit(neutral.position_report(axis, span, self.sender(command)))
        elif name == "SB" and arg is None and axis_ok:  # a stop in its turn in the buffer (L3694)
            self.emit(ir.Stop(axis, True, span))
        elif name == "ST" and isinstance(arg, st.Number) and arg.value in (0, 1) and axis_ok:  # ST1 shuts down
            self.emit(ir.DriveEnable(axis, ir.Const(1 - int(arg.value), ir.Unit.NONE, arg.span), span))
        elif name in neutral.SETTINGS and isinstance(arg, (st.Number, st.VarRef)) and self.settable(command):
            setting = neutral.SETTINGS[name]
            unit = ir_names.SETTINGS[setting].unit  # rev/s and rev/s^2 become steps/s and steps/s^2
            if name in neutral.SCALES:  # ms -> s
                value = units.to_ir(self.expr(arg), neutral.SCALES[name], unit)
            else:
                value = self.value(arg, info, unit) if unit is not ir.Unit.NONE else self.expr(arg)
            op = ir.Setting(setting, axis, value, span)
            self.emit(op)
            if name in neutral.ON_RECEIPT and not self.unit.is_sequence:  # IV: exact only in its turn
                self.on_receipt[id(op)] = self.native(command)
        elif name in ("IN", "OUT") and isinstance(arg, st.IoFunction) and self.settable(command) \
                and arg.function.upper() in (neutral.INPUT_FUNCTIONS if name == "IN" else neutral.OUTPUT_FUNCTIONS):
            table = neutral.INPUT_FUNCTIONS if name == "IN" else neutral.OUTPUT_FUNCTIONS
            setting = "input_function" if name == "IN" else "output_function"
            self.emit(ir.Setting(setting, axis, ir.Text(table[arg.function.upper()], arg.span), span, arg.index))
        elif name in ("INL", "OUTL") and isinstance(arg, st.Pattern) and self.settable(command):
            # X leaves a level as it is: one setting per level set; INL's dedicated group (LMT+ ...
            # INDEX, L2136) sets the switch inputs' levels (ir_names.SWITCH_INPUTS, the same order)
            groups = [("output_active_high", arg.bits)] if name == "OUTL" else \
                list(zip(("switch_active_high", "input_active_high"), neutral.split(arg.bits)))
            for setting, bits in groups:
                for index, bit in enumerate(bits.upper(), 1):
                    if bit in "01":
                        self.emit(ir.Setting(setting, axis, ir.Const(int(bit), ir.Unit.NONE, arg.span), span, index))
        elif name in ("INL", "OUTL") and arg is None and not command.buffered:  # *0000100_1001000000 (L2141)
            self.emit(neutral.levels_report(name, axis, span, self.sender(command)))
        elif name == "TX" and isinstance(arg, st.Fields) and len(arg.values) == 3 and arg.tail \
                and 1 <= arg.values[0] <= 50 and arg.values[1] in (0, 1) and 0 <= arg.values[2] <= 5 \
                and not command.buffered:  # TXn,m,p,x: x then VARn (L4463-L4483)
            var = st.VarRef(arg.values[0], arg.spans[0] if arg.spans else arg.span)
            self.declare(var)
            self.emit(neutral.transmit(ir.Var(var.name, var.span), arg.values[1] == 1, arg.values[2], arg.tail, span,
                                       self.sender(command)))
        elif name == "QS" and arg is None and not command.buffered:  # ;*01! (L3209-L3217)
            self.emit(neutral.identity_report(axis, span, self.sender(command)))
        elif name in SETTING_REPORTS and arg is None and not command.buffered:
            self.emit(ir.Print((ir.Status(SETTING_REPORTS[name], axis, None, span),), True, span, self.sender(command)))
        elif name == "PS" and arg is None and axis_ok:  # pauses command execution, not motion (L3151)
            self.emit(ir.Pause(axis, False, span))
        elif name == "C" and arg is None and axis_ok:
            self.emit(ir.Resume(axis, span))
        elif name == "#" and (arg is None or isinstance(arg, st.Fields) and len(arg.values) == 1
                              and arg.tail is None) and axis_ok:  # '#' alone runs one command (L5557)
            count = ir.Const(arg.values[0], ir.Unit.NONE, arg.span) if arg is not None \
                else ir.Const(1, ir.Unit.NONE, span)
            self.emit(ir.Step(axis, count, span))
        elif name == "HALT" and arg is None and fits:
            self.terminate(ir.End(span))  # stops execution and clears the buffer (L1883)
        elif role == "return" and fits:
            self.terminate(ir.Return(span))
        elif role == "when" and isinstance(arg, st.Condition) and fits:
            self.emit(ir.SetHandler("when", None, (self.cond(arg, axis),), span))
        else:
            op = self.native(command)
            self.emit(op)

    def trace(self, command: st.Command) -> None:
        """The device's trace report of `command`, sent while the trace is on (XTR1):
        `;SEQUENCE: 1 COMMAND: G      LOOP COUNT: 2` in an L loop, the iteration of the innermost
        one (L5408-L5433). The loop count is the counter's: n + 1 - %Lk (it counts down from n)."""
        span = command.span
        # the command as stored; the end is `XT` whatever address its download gave it (L5431)
        text = "XT" if command is self.unit.end else command.text.strip()
        items: tuple = (ir.Text(f";SEQUENCE: {self.unit.number} COMMAND: {text}", span),)
        loop = next((f for f in reversed(self.frames) if f.kind == "L"), None)
        if loop is not None:
            iteration = ir.BinOp("-", ir.BinOp("+", loop.count, ir.Const(1, ir.Unit.NONE, span), span),
                                 ir.Var(loop.counter, span), span)
            items += (ir.Text("      LOOP COUNT: ", span), iteration)
        axis = "" if self.device is None else str(self.device)
        self.emit(ir.Print(items, True, span, axis, traced=True))

    def settable(self, command: st.Command) -> bool:
        """A setting command whose B prefix the backend writes back by itself: none, or the one every
        B-prefixable command takes inside a sequence."""
        return not command.buffered or (self.unit.is_sequence and command.info.b_prefixable)

    def outputs(self, pattern: st.Pattern, span) -> ir.SetOutput:
        """`O` with one output set (the others X) is that output; any other pattern stays a pattern."""
        bits = pattern.bits
        set_bits = [(i, b) for i, b in enumerate(bits) if b != "X"]
        if len(set_bits) == 1:
            index, bit = set_bits[0]
            return ir.SetOutput(index + 1, ir.Const(int(bit), ir.Unit.NONE, pattern.span), span)
        return ir.SetOutput(None, ir.Pattern(bits, pattern.span), span)

    def neutral_chain(self, chain: st.Chain) -> bool:
        """A chain reads only variables, numbers and readings with a neutral meaning (POS, ABS)."""
        operands = [chain.first] + [operand for _, operand in chain.rest]
        return all(not isinstance(o, st.Source) or o.name in READINGS for o in operands)

    def transfer(self, command: st.Command, role: str) -> None:
        """XR/GOSUB (call), XG/GOTO (goto), XP/XFK/XWHEN (handler selection)."""
        number = sequence_number(command)
        address = command.address if command.address is not None else self.device
        targets = self.resolve(number, address) if number else ()
        kind = "call" if role == "call" else "goto" if role == "goto" else "handler"
        self.sites.append(Site(command, kind, number, targets, self.routine.name, self.depths(), self.unit))
        span = command.span
        if number is None:  # through a variable, or a report (XP alone)
            self.emit(self.native(command))
        elif number == 0:  # XP0 / XFK0 / XWHEN0: no sequence selected
            if role in HANDLERS and self.fits(command):
                self.emit(ir.SetHandler(HANDLERS[role], None, (), span, takes_over=HANDLERS[role] == "fault"))
            else:
                self.emit(self.native(command))
        else:
            name = self.target_name(command, number, targets)
            if name is None:
                self.emit(self.native(command))
            elif role == "call":
                self.emit(ir.Call(name, None, span))
            elif role == "goto":
                self.terminate(ir.GotoRoutine(name, span))
            else:
                self.emit(ir.SetHandler(HANDLERS[role], name, (), span, takes_over=HANDLERS[role] == "fault"))

    def target_name(self, command: st.Command, number: int, targets: tuple[str, ...]) -> str | None:
        """The routine name for a transfer, or None when the IR cannot keep the command's address."""
        if self.device is not None:
            return targets[0] if targets else naming.sequence_name(number, self.device)
        written = command.address
        if not targets:
            return naming.sequence_name(number, written)
        if len(targets) == 1 and naming.device_of(targets[0]) == written:
            return targets[0]
        return None

    # -- constructs --------------------------------------------------------------------------------
    def depths(self) -> dict[str, int]:
        out = {kind: 0 for kind in OPENERS.values()}
        for frame in self.frames:
            out[frame.kind] += 1
        return out

    def open(self, command: st.Command, kind: str) -> None:
        depth = sum(1 for f in self.frames if f.kind == kind) + 1
        deepest = self.max_depth.setdefault(self.routine.name, {})
        deepest[kind] = max(deepest.get(kind, 0), depth)
        if depth == self.nesting + 1:
            self.diags.add("X110", command.span,
                           f"{kind} is nested {depth} deep; the controller allows {self.nesting} "
                           f"(L2011, L2332): move the inner part to its own sequence")
        span = command.span
        frame = Frame(kind, command)
        if kind == "L":
            self.counters += 1
            counter = f"{LOOP_VAR}{self.counters}"
            self.module.variables[counter] = ir.Variable(counter, ir.VarType.INT32, ir.Const(0), "local", span)
            count = self.value(command.arg, command.info) if command.arg is not None else ir.Const(0, ir.Unit.NONE, span)
            self.emit(ir.Assign(ir.Var(counter, span), count, span))
            frame.counter, frame.count = counter, count
            head = self.label()
            self.terminate(ir.Jump(head, span))
            self.new_block(span, head)
            frame.head = head
        elif kind == "IF":
            then = self.label()
            frame.branch = ir.Branch(self.cond(command.arg, self.axis(command)), then, "", span)
            self.terminate(frame.branch)
            self.new_block(span, then)
        elif kind == "WHILE":
            head, body, frame.exit = self.label(), self.label(), self.label()
            self.terminate(ir.Jump(head, span))
            self.new_block(span, head).terminator = ir.Branch(self.cond(command.arg, self.axis(command)),
                                                              body, frame.exit, span)
            self.new_block(span, body)
            frame.head = head
        else:  # REPEAT
            head = self.label()
            self.terminate(ir.Jump(head, span))
            self.new_block(span, head)
            frame.head = head
        self.frames.append(frame)

    def close(self, command: st.Command, role: str) -> None:
        kind = CLOSERS[role]
        name = command.mnemonic
        index = next((i for i in range(len(self.frames) - 1, -1, -1) if self.frames[i].kind == kind), None)
        if index is None:
            if role == "endif" and self.unit.is_sequence and self.leading_nif(command):
                return
            opener = {"L": "L", "IF": "IF(...)", "WHILE": "WHILE(...)", "REPEAT": "REPEAT"}[kind]
            self.diags.add("X109", command.span,
                           f"{name} closes {opener}, but none is open here"
                           + (" in this sequence (a construct must open and close in one sequence, L2332)"
                              if self.unit.is_sequence else "") + f": remove {name} or add the {opener}")
            return
        while len(self.frames) - 1 > index:
            inner = self.frames[-1]
            self.unclosed(inner, f"{name} at line {command.span.line}")
            self.finish(self.frames.pop(), None)
        frame = self.frames[-1]
        if role == "else":
            if frame.else_seen:
                self.diags.add("X109", command.span, f"a second ELSE for the IF at line {frame.opener.span.line}: "
                                                     "an IF has at most one ELSE")
                return
            frame.ends.append(self.jump_pending(command.span))
            block = self.new_block(command.span)
            frame.branch.otherwise = block.label
            frame.else_seen = True
            return
        self.finish(self.frames.pop(), command)

    def leading_nif(self, command: st.Command) -> bool:
        """NIFs opening a sequence close an IF left open by a GOTO into it (L1794): kept as written."""
        if not self.leading:
            return False
        self.leading_nifs[self.routine.name] += 1
        self.emit(self.native(command))
        return True

    def jump_pending(self, span) -> ir.Jump:
        jump = ir.Jump("", span)
        self.terminate(jump)
        return jump

    def finish(self, frame: Frame, command: st.Command | None) -> None:
        span = command.span if command is not None else frame.opener.span
        if frame.kind == "L":
            var = ir.Var(frame.counter, span)
            self.emit(ir.Assign(var, ir.BinOp("-", var, ir.Const(1)), span))
            after = self.label()
            self.terminate(ir.Branch(ir.Compare("!=", var, ir.Const(0)), frame.head, after, span))
            self.new_block(span, after)
        elif frame.kind == "IF":
            frame.ends.append(self.jump_pending(span))
            join = self.new_block(span)
            for jump in frame.ends:
                jump.target = join.label
            if not frame.else_seen:
                frame.branch.otherwise = join.label
        elif frame.kind == "WHILE":
            self.terminate(ir.Jump(frame.head, span))
            self.new_block(span, frame.exit)
        else:  # REPEAT
            cond = self.cond(command.arg, self.axis(command)) if command is not None and command.arg is not None \
                else ir.Truth(ir.Const(1))
            after = self.label()
            self.terminate(ir.Branch(cond, after, frame.head, span))
            self.new_block(span, after)

    def unclosed(self, frame: Frame, where: str) -> None:
        self.diags.add("X108", frame.opener.span,
                       f"{frame.opener.mnemonic} at line {frame.opener.span.line} is not closed before {where}: add "
                       f"{CLOSER_NAMES[frame.kind]}"
                       + (" inside this sequence (L2332)" if self.unit.is_sequence else ""))

    def close_all(self, end: st.Command | None, what: str) -> None:
        while self.frames:
            self.unclosed(self.frames[-1], what if end is None or what != "XT" else f"XT at line {end.span.line}")
            self.finish(self.frames.pop(), None)

    # -- values ------------------------------------------------------------------------------------
    def declare(self, var: st.VarRef) -> None:
        name = var.name
        if name not in self.module.variables:
            # VAR1-VAR50 hold 0 until the program sets them (the default, L4569)
            self.module.variables[name] = ir.Variable(name, ir.VarType.DECIMAL, ir.Const(0, ir.Unit.NONE, var.span),
                                                      "global", var.span)

    def value(self, arg, info: cat.Command | None, unit: ir.Unit | None = None):
        """A command's value in the IR's units: rev/s and rev/s^2 times the resolution (steps/s,
        steps/s^2); a (VARn) holding rev/s becomes VARn * steps per rev."""
        written = info.entry.unit if info is not None else ""
        spr = self.module.steps_per_rev
        if written in RATES:
            if isinstance(arg, st.Number):
                return ir.Const(units.revs_to_steps(arg.value, spr), RATES[written], arg.span)
            if isinstance(arg, st.VarRef):
                self.declare(arg)
                return ir.BinOp("*", ir.Var(arg.name, arg.span), ir.Const(spr, ir.Unit.NONE, arg.span), arg.span)
        unit = unit or UNITS.get(written, ir.Unit.NONE)
        if isinstance(arg, st.Number):
            return ir.Const(arg.value, unit, arg.span)
        if isinstance(arg, st.VarRef):
            self.declare(arg)
            return ir.Var(arg.name, arg.span)
        return self.expr(arg)

    def operand(self, node: st.Operand, axis: str):
        if isinstance(node, st.Number):
            return ir.Const(node.value, ir.Unit.NONE, node.span)
        if isinstance(node, st.VarRef):
            self.declare(node)
            return ir.Var(node.name, node.span)
        if node.name in READINGS:
            return ir.Status(READINGS[node.name], axis, None, node.span)
        meaning = self.cat.sources.get(node.name, {}).get("ir", "")
        return ir.DeviceRef(DIALECT, node.name, meaning, axis, None, node.span)

    def chain(self, chain: st.Chain, axis: str):
        expr = self.operand(chain.first, axis)
        for op, operand in chain.rest:
            right = self.operand(operand, axis)
            expr = ir.BinOp(op, expr, right, chain.first.span.to(operand.span))
        return expr

    def cond(self, arg, axis: str):
        if not isinstance(arg, st.Condition):
            return ir.Truth(ir.Const(1))
        result = None
        for join, term in zip([""] + arg.joins, arg.terms):
            if isinstance(term, st.InputTerm):
                lowered = neutral.to_cond(term.pattern.bits, axis, term.pattern.span)
            else:
                lowered = ir.Compare(term.op, self.operand(term.left, axis), self.operand(term.right, axis), term.span)
            result = lowered if result is None else ir.Logic(join.lower(), result, lowered, arg.span)
        return result

    def expr(self, arg):
        """Native arguments: each syntax argument as IR expressions."""
        if isinstance(arg, st.Number):
            return ir.Const(arg.value, ir.Unit.NONE, arg.span)
        if isinstance(arg, st.VarRef):
            self.declare(arg)
            return ir.Var(arg.name, arg.span)
        if isinstance(arg, st.Pattern):
            return ir.Pattern(arg.bits, arg.span)
        if isinstance(arg, st.Text):
            return ir.Text(arg.text, arg.span)
        raise TypeError(f"unexpected argument {type(arg).__name__}")

    def native_args(self, command: st.Command) -> tuple:
        arg = command.arg
        axis = self.axis(command)
        if arg is None:
            return ()
        if isinstance(arg, st.IoFunction):
            return (ir.Const(arg.index, ir.Unit.NONE, arg.span), ir.Text(arg.function, arg.span))
        if isinstance(arg, st.Fields):
            values = tuple(ir.Const(v, ir.Unit.NONE, s) for v, s in zip(arg.values, arg.spans))
            return values + ((ir.Text(arg.tail, arg.span),) if arg.tail is not None else ())
        if isinstance(arg, st.VarStatement):
            self.declare(arg.var)
            var = ir.Var(arg.var.name, arg.var.span)
            return (var,) + ((self.chain(arg.value, axis),) if arg.value is not None else ())
        if isinstance(arg, st.Condition):
            return (self.cond(arg, axis),)
        return (self.expr(arg),)  # as written: a Native keeps the dialect's own units

    def native(self, command: st.Command) -> ir.Native:
        mnemonic = command.mnemonic if command.info is not None else "!"
        if isinstance(command.arg, st.VarStatement) and command.info is not None and command.info.name not in \
                self.cat.commands:  # VARn=FUN etc.: the token's mnemonic is VAR
            mnemonic = "VAR"
        return ir.Native(DIALECT, mnemonic, self.native_args(command), form="B" if command.buffered else "",
                         axis=self.axis(command), span=command.span)


def external_routines(module: ir.Module) -> list[str]:
    """Sequences a program calls or jumps to without defining them (stored on the controller)."""
    known = {r.name for r in module.routines}  # defined, or already in `used`
    used: list[str] = []
    naming_routines = (ir.Call, ir.SetHandler)  # the IR's operation classes have no subclasses
    for routine in module.routines:
        for block in routine.blocks:
            for op in block.ops:
                if type(op) in naming_routines:
                    name = op.routine
                    if name and name not in known:
                        known.add(name)
                        used.append(name)
            term = block.terminator
            if type(term) is ir.GotoRoutine and term.routine not in known:
                known.add(term.routine)
                used.append(term.routine)
    return used
