"""The MCode backend: IR → a device-ready Lexium MCode listing.

Layout (the convention of every sample in the manual, L7617-L7658):

    VA declarations, then the immediate setup lines
    PG <address>
      the main routine: labels, body, E
      subroutines and handlers, each ending in RT
    PG
    S                (when the source saved)
    ' comment        (after a final S: the manual asks for it so the S line's end is sent, L5269)

Every line fits the 64-character device buffer (a longer one is an error, M201). Blocks the source
did not name get generated labels that follow the naming rules (two characters, a letter first,
never an MCode name) and never collide with the program's own names. Output is canonical (upper
case, `NAME=value` for settings, `MA 100` for instructions, no comments but the one after a final
`S`), so compiling the output again gives the same text.
"""

from __future__ import annotations

import dataclasses
from functools import lru_cache

import string
from fractions import Fraction

from mcc.backends import enable_outputs, int32, resolution
from mcc.backends.step_values import IN_STEPS, MIXED, PLAIN, STEPS, StepValues, step_readings
from mcc.backends.listing import Listing, axis_sets_written
from mcc.compiler import homing
from mcc.compiler import ir, ir_names, units
from mcc.compiler.diagnostics import Diagnostics
from mcc.compiler import in_force
from mcc.compiler.in_force import FIXED, InForce, lookup, with_fixed_initial_speed, with_source_power_up
from mcc.compiler.mcode import catalog as cat
from mcc.compiler import profiles
from mcc.compiler.profiles import Profile
from mcc.compiler.span import Span

DIALECT = "mcode"
PARAM_NAMES = {ir.MotionParam.ACCEL: "A", ir.MotionParam.DECEL: "D", ir.MotionParam.INITIAL_SPEED: "VI",
               ir.MotionParam.MAX_SPEED: "VM", ir.MotionParam.RESOLUTION: "MS"}
COMPARE = {"=": "=", "!=": "<>", "<": "<", "<=": "<=", ">": ">", ">=": ">="}
NEGATE = {"=": "!=", "!=": "=", "<": ">=", "<=": ">", ">": "<=", ">=": "<"}  # in the IR's neutral names
FUNCTIONS = {"abs": "AB", "cos": "CS", "acos": "C_", "log": "LO", "log10": "L_", "sin": "SI", "asin": "S_",
             "sqrt": "SQ", "tan": "TG", "atan": "T_"}
TRIPS = {"input": "TI", "position": "TP", "capture": "TC", "time": "TT", "relative": "TR", "hmt": "TA",
         "power_loss": "TM"}
PI = 3.141592654  # what the drive's PI holds (lexium-mcode.txt L6658); the frontend lowers PI to it
UNIT_FACTORS = {ir.Unit.S: 1000}  # delays are written in ms
MS_TO_S = 0.001
FULL_STEPS_PER_REV = 200
# IR readings -> MCode registers (the inverse of the frontend's READINGS); indexed ones take the number.
READINGS = {"position": "P", "encoder": "C2", "velocity": "V", "moving": "MV", "inputs": "IN", "outputs": "OT",
            "error": "ER", "stalled": "ST", "accel": "A", "decel": "D", "max_speed": "VM", "initial_speed": "VI",
            "input_pending": "IF", "hmt_status": "AF", "moving_to_position": "MP",
            "locked_rotor": "LR"}
INDEXED_READINGS = {"input": ("I", range(1, 5)), "output": ("O", range(1, 4)), "analog": ("I", range(5, 6))}
# Neutral settings -> (MCode variable, factor from IR units to MCode units).
SETTINGS = {"error_code": ("ER", 1), "run_current": ("RC", 1), "hold_current": ("HC", 1),
            "settle_time": ("MT", 1000), "hold_delay": ("HT", 1000), "encoder_enable": ("EE", 1),
            "input_debounce": ("D", 1000), "handler_enable": ("TE", 1)}
INPUT_TYPES = {"general": 0, "home": 1, "limit_plus": 2, "limit_minus": 3, "run_program": 4, "soft_stop": 5,
               "pause": 6, "jog_plus": 7, "jog_minus": 8, "reset": 11, "capture": 12, "step_direction": 13,
               "encoder_ab": 14, "step_up_down": 15}
OUTPUT_TYPES = {"general": 16, "moving": 17, "error": 18, "stall": 19, "velocity_changing": 20, "locked_rotor": 21,
                "moving_to_position": 23, "hmt_active": 24, "make_up_active": 25, "encoder_a": 26, "encoder_b": 27,
                "trip": 28, "attention": 29}
HOME_TYPES = {(-1, +1): 1, (-1, -1): 2, (+1, -1): 3, (+1, +1): 4, (-1, 0): 1, (+1, 0): 3}
# operations MCode writes with a program-only statement (CL, BR loops, H): an immediate stream of
# another dialect holding one runs as a program
PROGRAM_ONLY = (ir.Call, ir.WaitInput, ir.WaitMotion, ir.Delay)
REPORT_VAR = "%report"  # the key of the signed report's variable in Writer.names (never a source name)
OUTPUTS = 3  # O1-O3; OT sets them as a 3-bit value (L4669)
SAVE_TRAILER = "' end of program: this line ends the S above (L5269)"


@lru_cache(maxsize=1)
def registers() -> dict[str, str]:
    """Neutral setting or reading -> the drive register that holds it: the catalog's `setting` and
    `reading` keys (compiler/catalogs/mcode.toml), the inverse of the frontend's lowering."""
    table: dict[str, str] = {}
    for command in cat.load().commands.values():
        name = command.entry.get("setting") or command.entry.get("reading")
        if name and name not in READINGS and name not in SETTINGS:
            table.setdefault(name, command.name)
    return table


def read_back(node: ir.BinOp) -> str | None:
    """`MT`, `D2`, `LT` read back: the frontend reads a setting held in seconds as
    `Status(setting) / 0.001` (ms); the register is written as it was."""
    if node.op != "/" or not isinstance(node.left, ir.Status) or not isinstance(node.right, ir.Const):
        return None
    meaning, index = node.left.meaning, node.left.index
    if meaning == "resolution" and node.right.value == FULL_STEPS_PER_REV:  # MS: steps per rev / 200
        return "MS"
    if node.right.value != MS_TO_S:
        return None
    if meaning in registers():
        return registers()[meaning]
    found = SETTINGS.get(meaning)
    if found is None or found[1] != 1000:
        return None
    return f"{found[0]}{index}" if found[0] == "D" and index in range(1, 5) else (found[0] if found[0] != "D" else None)


# The line tables `PR OS` and `PR LS` answer (the frontend writes one print per line reading that
# line's settings): the reading of a line's first parameter -> (the table, its first line).
TABLE_READINGS = {"output_function": ("OS", 1), "soft_limit_position": ("LS", 0)}


def table_listing(op: ir.Print) -> tuple[str, bool] | None:
    """(table, first line?) when `op` prints one line of an MCode setup table, else None."""
    for item in op.items:
        if isinstance(item, ir.Status) and item.meaning in TABLE_READINGS:
            table, first = TABLE_READINGS[item.meaning]
            return table, item.index == first
    return None


class Unsupported(Exception):
    """An IR construct this backend cannot write; reported as G003 at the operation's span."""


def format_number(value: int | float) -> str:
    if isinstance(value, float):
        if value.is_integer() and abs(value) < 1e15:
            return f"{value:.1f}"
        return repr(value)
    return str(value)


class Writer:
    def __init__(self, module: ir.Module, profile: Profile, microsteps: int | None = None):
        self.module = module
        self.microsteps = microsteps  # the MS the output sets first (chosen_microsteps), or None
        self.profile = profile
        self.cat = cat.for_profile(profile)  # Lexium MCode, or the profile's older family (S1-S4 I/O set-up)
        self.listing = Listing(DIALECT)
        self.diags: Diagnostics = self.listing.diagnostics
        self.limit = int(profile.get("limits.line_length", 64))
        self.settled = ir.settled_ops(module)  # where no move can run: a pause means the same in both dialects
        self.foreign = module.dialect != DIALECT
        self.index = module.block_index()  # the writer never changes the module
        self.factor = units.ratio(module.steps_per_rev, profile.steps_per_rev) if self.foreign else Fraction(1)
        self.drive = profile.axes[0] if profile.axes else "1"
        self.reserved = self.cat.commands.keys() | self.cat.functions.keys() | self.cat.legacy.keys()
        self.taken = self.used_names()
        self.names = self.allocate_variables()
        self.labels = self.allocate_labels()
        self.axis_map = self.map_axes()
        self.ramps = self.uses_ramp_times()
        self.states = self.settings_in_force() if self.foreign else {}
        self.written_ramp: dict[str, float] = {}
        self.contexts = self.run_contexts() if self.foreign else {}
        self.block_start = 0
        self.immediate = False  # writing lines outside any program (H cannot be written there, M112)
        self.moving = moving_before(module, foreign=self.foreign)
        self.masked_banks = masked_bank_reads(module, profile) if self.foreign else set()
        # which values count steps, where the output's steps differ from the source's (step_values.py)
        self.step_values = StepValues(module) if self.foreign and self.factor != 1 else None
        self.source_units = False  # writing an expression in the source's steps (in_source_steps)
        self.report_var = self.allocate_report_var()

    # names ---------------------------------------------------------------------------------------
    def fresh_name(self) -> str:
        """A two-character user name (Z0, Z1, ...) no program name or mnemonic uses."""
        for first in "ZYXWQJ":
            for second in string.digits + string.ascii_uppercase:
                name = first + second
                if name not in self.taken and name not in self.reserved:
                    self.taken.add(name)
                    return name
        raise Unsupported("more generated names than the two-character name space holds")

    def allocate_variables(self) -> dict[str, str]:
        """MCode names for the program's variables: a valid user name is kept, any other
        (Arcus `V10`, X150 `VAR1`, a hidden loop counter) gets a fresh two-character name."""
        names: dict[str, str] = {}
        for name in self.variable_names():
            ok = len(name) == 2 and name[0].isalpha() and name.isalnum() and name.isascii()
            if ok and (not self.foreign or name.upper() not in self.reserved):
                names[name] = name
            elif self.cat.commands.get(name.upper()) is not None and not self.foreign:
                names[name] = name  # a register (R1, F1) of an MCode source
        for name in self.variable_names():
            if name not in names:
                names[name] = self.fresh_name()
        return names

    def allocate_report_var(self) -> str | None:
        """The variable a signed report reads its value into (`signed_print`), declared with the
        program's own: one for the whole program, allocated only when a report needs it."""
        if not self.foreign or not any(isinstance(op, ir.Print) and op.signed
                                       for _, block in self.module.blocks() for op in block.ops):
            return None
        name = self.fresh_name()
        self.names[REPORT_VAR] = name
        return name

    def variable_names(self) -> list[str]:
        seen = dict.fromkeys(self.module.variables)
        for _, block in self.module.blocks():
            exprs = [e for op in block.ops for e in ir.op_exprs(op)] + list(ir.term_exprs(block.terminator))
            exprs += [op.target for op in block.ops if isinstance(op, ir.Assign)]
            for expr in exprs:
                for node in ir.walk_expr(expr):
                    if isinstance(node, ir.Var):
                        seen.setdefault(node.name)
        return list(seen)

    def var(self, name: str) -> str:
        return self.names.get(name, name)

    def map_axes(self) -> dict[str, str]:
        """Source axis -> party prefix. An MCode source keeps its party names; another dialect's
        program must use one axis, which becomes this drive (no prefix)."""
        if not self.foreign:
            return {}
        used: list[str] = []
        enables: list[str] = []  # an axis only enabled (Arcus EO2) is this drive only when nothing moves
        for _, block in self.module.blocks():
            for op in block.ops:
                for axis in op_axes(op):
                    found = enables if isinstance(op, ir.DriveEnable) else used
                    if axis != ir.ALL_AXES and axis not in found:
                        found.append(axis)
        if not used and not enables:  # only universal commands move (X150 `G`): a reading addressed to one
            # device (`1PR`) names the device the program runs on, which universal commands reach too
            read = [node.axis for _, block in self.module.blocks() for op in block.ops for e in ir.op_exprs(op)
                    for node in ir.walk_expr(e) if isinstance(node, ir.Status) and node.axis not in ("", ir.ALL_AXES)]
            used = list(dict.fromkeys(read))
        used = used or enables
        return {used[0]: ""} if used else {}

    # values in force (ramp times) ----------------------------------------------------------------
    def uses_ramp_times(self) -> bool:
        return any(isinstance(op, ir.SetMotion) and op.param in (ir.MotionParam.ACCEL_TIME, ir.MotionParam.DECEL_TIME)
                   for _, block in self.module.blocks() for op in block.ops)

    def settings_in_force(self) -> dict[int, dict]:
        analysis = InForce(self.module)
        states: dict[int, dict] = {}
        for routine in self.module.routines:
            for _, _, op, state in analysis.walk(routine):
                states[id(op)] = state
        return states

    # how each routine runs (another dialect's program) ----------------------------------------------
    def run_contexts(self) -> dict[str, set[str]]:
        """How each routine of another dialect's program can run: "called" (CL: its end returns to
        the caller) and/or "top" (a program run by EX or at power-up: its end stops the program).

        An X150 sequence ends at XT, which returns when it was run by XR/GOSUB and stops the program
        otherwise (parker-x150.md L1750, L5138). MCode spells the two ends differently: RT returns
        from a CL (lexium-mcode.txt L2121, L5232), E ends the program (L2527). XG/GOTO to another
        sequence hands over without a new return address (L5077, L1790): it is written as `CL` of
        that sequence followed by this routine's own end (Writer.goto), so the sequence it reaches
        is a called one; a BR into another routine would leave MCode code that enters a routine
        without CL and leaves it with RT (M302), which the MCode reading of the output cannot follow."""
        contexts: dict[str, set[str]] = {r.name: set() for r in self.module.routines}
        reached: set[str] = set()
        for routine in self.module.routines:
            for block in routine.blocks:
                # a handler runs like a CL and ends with RT (L5232)
                targets = [op.routine for op in block.ops if isinstance(op, (ir.Call, ir.SetHandler)) and op.routine]
                if isinstance(block.terminator, ir.GotoRoutine) and block.terminator.routine != routine.name:
                    targets.append(block.terminator.routine)
                for target in targets:
                    if target in contexts:
                        contexts[target].add("called")
                        reached.add(target)
        for routine in self.module.routines:
            # a program: run at power-up, as the converted stream, or (a sequence nothing in the file
            # runs) by the host
            if routine.kind is ir.RoutineKind.POWERUP or self.as_program(routine) \
                    or routine.kind is ir.RoutineKind.MAIN and routine.name not in reached:
                contexts[routine.name].add("top")
            if routine.kind is ir.RoutineKind.HANDLER:  # run like a CL, ends with RT (L5232)
                contexts[routine.name].add("called")
        return contexts

    def goto_cycle(self, source: str, target: str) -> bool:
        """Whether XG/GOTO from `source` to `target` can come back to `source` by XG/GOTO alone: written
        as CL, each round would nest one call deeper until the device's stack overflows (Error 43)."""
        edges: dict[str, set[str]] = {}
        for routine in self.module.routines:
            for block in routine.blocks:
                if isinstance(block.terminator, ir.GotoRoutine) and block.terminator.routine != routine.name:
                    edges.setdefault(routine.name, set()).add(block.terminator.routine)
        seen, todo = set(), [target]
        while todo:
            name = todo.pop()
            if name == source:
                return True
            if name not in seen:
                seen.add(name)
                todo.extend(edges.get(name, ()))
        return False

    def goto(self, term: ir.GotoRoutine, routine: ir.Routine | None, span) -> None:
        """XG/GOTO to another routine of another dialect's program: CL it, then end as this routine
        ends (its XT would return to the same caller, or stop the program, as the sequence reached)."""
        target = self.module.routine(term.routine)
        if target is None or target.entry is None:
            raise Unsupported(self.not_in_file("a jump to", term.routine))
        if routine is None or target is routine:
            self.line(f"BR {self.label(target.entry.label)}", span)
            return
        if self.goto_cycle(routine.name, target.name):
            raise Unsupported(f"a jump (XG/GOTO) to {target.name} that leads back to {routine.name} by jumps alone "
                              "(MCode has no jump into another routine that returns right, M302, and written as a "
                              "call each round would nest deeper until the stack overflows, Error 43: make the "
                              "loop inside one sequence)")
        end = self.end_of(routine, f"a jump (XG/GOTO) to {target.name} at the end")
        self.line(f"CL {self.label(target.entry.label)}", span)
        self.line(end, span)

    def end_of(self, routine: ir.Routine | None, what: str, default: str = "E") -> str:
        """RT or E for a routine's end (an X150 XT or XRT) in another dialect's program; refused when
        the routine runs both called and as a program, since one line cannot both return and stop.
        A routine nothing runs keeps `default` (RT for a written return, E otherwise)."""
        contexts = self.contexts.get(routine.name, set()) if routine is not None else set()
        if contexts == {"called", "top"}:
            raise Unsupported(f"{what} of {routine.name} (it runs both as a subroutine, XR/GOSUB, where its end "
                              "returns, and as a program, where its end stops; MCode's RT and E cannot do both: "
                              "give each use its own sequence)")
        if not contexts:
            return default
        return "RT" if contexts == {"called"} else "E"

    # labels --------------------------------------------------------------------------------------
    def used_names(self) -> set[str]:
        names = {name for name in self.module.variables if is_user_name(name, self.reserved)}
        for _, block in self.module.blocks():
            if not block.label.startswith(("%", "@")):
                names.add(block.label)
        return names

    def through(self, label: str) -> str:
        """Where a jump to `label` really goes: past empty blocks that only jump on (an empty IF
        arm, a loop's bare back edge), so the same branch is written however the CFG was built."""
        seen = {label}
        found = self.index.get(label) if self.foreign else None
        while found is not None:
            block = found[1]
            if block.ops or block.named and not self.foreign or not isinstance(block.terminator, ir.Jump):
                break
            label = block.terminator.target
            if label in seen:
                break
            seen.add(label)
            found = self.index.get(label)
        return label

    def needed_blocks(self) -> set[str]:
        """Unnamed blocks that something jumps to, calls, or names as a handler need a label."""
        needed: set[str] = set()
        order = [b.label for _, b in self.module.blocks()]
        following = {label: self.through(order[i + 1]) if i + 1 < len(order) else None
                     for i, label in enumerate(order)}
        for _, block in self.module.blocks():
            term = threaded(block.terminator, self.through)
            after = following.get(block.label)
            if isinstance(term, ir.Jump) and term.target != after:
                needed.add(term.target)
            elif isinstance(term, ir.Branch):  # mirrors Writer.branch
                if term.then == term.otherwise:
                    if term.then != after:
                        needed.add(term.then)
                elif term.then == after:
                    needed.add(term.otherwise)
                else:
                    needed.add(term.then)
                    if term.otherwise != after:
                        needed.add(term.otherwise)
            elif isinstance(term, ir.GotoRoutine):
                target = self.module.routine(term.routine)
                if target is not None and target.entry is not None:
                    needed.add(target.entry.label)
            for op in block.ops:
                if isinstance(op, ir.Call):
                    needed.add(op.routine)
        for routine in self.module.routines:
            if routine.kind in (ir.RoutineKind.SUBROUTINE, ir.RoutineKind.HANDLER) and routine.entry:
                needed.add(routine.entry.label)
            if routine.kind is ir.RoutineKind.POWERUP and routine.entry:
                needed.add(routine.entry.label)
        if self.foreign:  # another dialect's programs (X150 sequences) run by name: EX <label>
            programs = [r for r in self.program_order() if (r.kind is ir.RoutineKind.MAIN or self.as_program(r))
                        and r.entry]
            needed.update(r.entry.label for r in programs[1:])
        return needed

    def allocate_labels(self) -> dict[str, str]:
        """Deterministic two-character names for the blocks that need one (Z0, Z1, ... skipping taken
        names); in another dialect's program every block label is generated (theirs are not MCode names)."""
        mapping: dict[str, str] = {}
        for _, block in self.module.blocks():
            label = block.label
            valid = not label.startswith(("%", "@")) and (not self.foreign or is_user_name(label, self.reserved))
            if valid or label not in self.needed_blocks_cache():
                continue
            mapping[label] = self.fresh_name()
        return mapping

    _needed: set[str] | None = None

    def needed_blocks_cache(self) -> set[str]:
        if self._needed is None:
            self._needed = self.needed_blocks()
        return self._needed

    def label(self, block_label: str) -> str:
        if block_label.startswith("@"):
            return block_label[1:]
        if block_label not in self.labels and self.foreign and not is_user_name(block_label, self.reserved):
            self.labels[block_label] = self.fresh_name()
        return self.labels.get(block_label, block_label)

    # output --------------------------------------------------------------------------------------
    def line(self, text: str, *spans) -> None:
        if len(text) > self.limit:
            span = next((s for s in spans if s is not None), None)
            if span is not None:
                self.diags.add("M201", span, f"the generated line is {len(text)} characters, over the device's "
                                             f"{self.limit}: `{text[:40]}…`; split the expression in the source")
        self.listing.emit(text, *spans)

    def header(self) -> None:
        """The assumptions of a conversion from another dialect, as comment lines."""
        source = self.module
        lines = [f"' mcc: converted from {source.dialect} ({source.profile})",
                 f"' steps/rev: source {source.steps_per_rev or '?'}, target {self.profile.steps_per_rev}"
                 f" ({self.profile.name})"]
        if self.axis_map:
            axis = next(iter(self.axis_map))
            lines.append(f"' source axis {axis} is this drive")
        if self.ramps:
            lines.append("' ramp times become A/D from the speeds in force")
        if (ir.MotionParam.INITIAL_SPEED, ir.ALL_AXES) in FIXED.get(source.dialect, {}):
            lines.append(f"' {source.dialect} starts moves from standstill: VI at its lowest")
        for text in lines:
            self.line(text[:self.limit])

    def run(self) -> Listing:
        if self.foreign:
            self.header()
        for name, var in self.module.variables.items():
            if var.scope == "global" or self.foreign:
                init = f"={self.expr(var.init)}" if var.init is not None else ""
                self.line(f"VA {self.var(name)}{init}", var.span)
        if self.foreign:
            for name in self.names:
                if name not in self.module.variables:
                    self.line(f"VA {self.var(name)}")
        if self.microsteps is not None:
            span = next((op.span for _, b in self.module.blocks() for op in b.ops if op.span is not None), None)
            self.line(f"MS={self.microsteps}", span)  # after the variables, as an MCode source's own MS is written
        region_open = False
        order = [(r, b) for r in self.program_order() for b in r.blocks]
        origin_given = any(r.origin is not None for r in self.module.routines)
        for index, (routine, block) in enumerate(order):
            self.immediate = routine.kind is ir.RoutineKind.IMMEDIATE and not self.as_program(routine)
            if self.immediate:
                if region_open:
                    self.line("PG")
                    region_open = False
                index = 0
                while index < len(block.ops):
                    index += self.op_at(block.ops, index)
                continue
            if block is routine.entry and (routine.origin is not None or not origin_given and not region_open):
                if region_open:
                    self.line("PG")
                self.line(f"PG {routine.origin if routine.origin is not None else 1}", routine.span)
                region_open = True
            if block is routine.entry and not region_open:
                # after a closing PG a line runs at once (immediate mode, L510-L512) and its label
                # is never stored: a routine there would run on download and CL could not find it
                self.unsupported(routine.span or next((op.span for op in block.ops if op.span), None),
                                 f"the routine {routine.name} outside any program region (PG <address> ... PG); "
                                 "a program's subroutines belong inside it (L4794)")
            next_label = self.through(order[index + 1][1].label) if index + 1 < len(order) else None
            self.block(block, next_label, routine)
        if region_open:
            self.line("PG")
        if self.foreign and any(self.as_program(r) for r in self.module.routines):
            self.line("EX 1")  # the converted stream ran as it was sent: run the program now
        self.end_save()
        self.stats()
        return self.listing

    def end_save(self) -> None:
        """A listing that ends with `S` gets a comment line after it: the manual asks for one so the
        `S` line's <CR/LF> is sent (L5269); without it a downloader may leave the save unsent."""
        if self.listing.lines and self.listing.lines[-1].text == "S":
            self.line(SAVE_TRAILER, *self.listing.lines[-1].sources)

    def as_program(self, routine: ir.Routine) -> bool:
        """Another dialect's immediate stream that branches, loops, calls or waits cannot run outside
        a program in MCode (BR, CL and H are program statements, M112): it becomes the program at
        address 1."""
        if not self.foreign or routine.kind is not ir.RoutineKind.IMMEDIATE:
            return False
        return len(routine.blocks) > 1 or any(isinstance(op, PROGRAM_ONLY) or isinstance(op, ir.Print) and op.signed
                                              for b in routine.blocks for op in b.ops)

    def program_order(self) -> list[ir.Routine]:
        """Routines in source order; in a converted program the one that runs first leads the
        region and subroutines follow (MCode runs a program from its PG address)."""
        routines = list(self.module.routines)
        if not self.foreign:
            return routines
        # the converted stream runs first (EX 1, its commands ran as they were sent); sequences are
        # only stored until something runs them
        first = [r for r in routines if self.as_program(r)] + [r for r in routines if r.kind is ir.RoutineKind.MAIN]
        rest = [r for r in routines if r not in first]
        immediate = [r for r in rest if r.kind is ir.RoutineKind.IMMEDIATE]
        program = first + [r for r in rest if r not in immediate]
        # immediate commands keep their place around the program region: a save (S) sent after the
        # definitions must follow them, or it saves the program before it is loaded
        start = min((line_of(r) for r in program), default=0)
        before = [r for r in immediate if line_of(r) <= start]
        return before + program + [r for r in immediate if r not in before]

    def stats(self) -> None:
        text_lines = [line.text for line in self.listing.lines]
        self.listing.stats = {
            "lines": len(text_lines),
            "bytes": sum(len(t) + 1 for t in text_lines),
            "longest_line": max((len(t) for t in text_lines), default=0),
            "line_limit": self.limit,
            "labels": sum(1 for t in text_lines if t.startswith("LB ")),
            "routines": sum(1 for r in self.module.routines if r.kind is not ir.RoutineKind.IMMEDIATE),
        }

    def block(self, block: ir.Block, next_label: str | None, routine: ir.Routine | None = None) -> None:
        self.block_start = len(self.listing.lines)
        if block.named and not self.foreign or block.label in self.labels:
            self.line(f"LB {self.label(block.label)}", block.span)
        self.written_ramp.clear()  # a label can be reached from anywhere: nothing known written
        ops = block.ops
        index = 0
        while index < len(ops):
            index += self.op_at(ops, index)
        term = threaded(block.terminator, self.through)
        span = getattr(term, "span", None)
        try:
            self.terminator(term, next_label, span, routine)
        except Unsupported as exc:
            self.unsupported(span, str(exc))

    def terminator(self, term, next_label: str | None, span, routine: ir.Routine | None = None) -> None:
        if self.foreign and routine is not None and isinstance(term, (ir.Jump, ir.Branch)):
            own = {b.label for b in routine.blocks}
            away = [t for t in successors(term) if t not in own]
            if away:  # a BR out of a routine leaves its return address on the stack (M302)
                raise Unsupported(f"a jump from {routine.name} into another routine (MCode leaves a routine with RT "
                                  "or E, not BR)")
        if isinstance(term, ir.Jump):
            if term.target != next_label:
                self.line(f"BR {self.label(term.target)}", span)
        elif isinstance(term, ir.Branch):
            self.branch(term, next_label)
        elif isinstance(term, ir.Return):
            end = self.end_of(routine, "a return (XRT)", "RT") if self.foreign else "RT"
            if not self.repeats_end(end):
                self.line(end, span)
        elif isinstance(term, ir.End):
            self.line("E", span)
        elif isinstance(term, ir.GotoRoutine) and self.foreign:
            self.goto(term, routine, span)
        elif isinstance(term, ir.GotoRoutine):
            target = self.module.routine(term.routine)
            if target is None or target.entry is None:
                raise Unsupported(f"a jump to {term.routine}, which is not in this program")
            self.line(f"BR {self.label(target.entry.label)}", span)
        elif isinstance(term, ir.FallOff) and self.foreign:
            # another dialect's routine returns or stops at its end; MCode would run on into the next
            # line (or off the end of the region: a called routine must still return)
            end = self.end_of(routine, "the end (XT)")
            if (end == "RT" or next_label is not None) and not self.repeats_end(end):
                self.line(end, span)

    def repeats_end(self, end: str) -> bool:
        """Whether this block wrote nothing (no label, no operation) and the line before it is
        already the same end: the XT kept after an XG (written as CL then the end) adds no line."""
        lines = self.listing.lines
        return self.foreign and len(lines) == self.block_start and bool(lines) and lines[-1].text == end

    def branch(self, term: ir.Branch, next_label: str | None) -> None:
        if term.then == term.otherwise:  # both ways lead to one place: a jump
            if term.then != next_label:
                self.line(f"BR {self.label(term.then)}", term.span)
            return
        if term.then == next_label:
            self.jump_if(ir.Not(term.cond), self.label(term.otherwise), term.span)
            return
        self.jump_if(term.cond, self.label(term.then), term.span)
        if term.otherwise != next_label:
            self.line(f"BR {self.label(term.otherwise)}", term.span)

    def jump_if(self, cond, target: str, span) -> None:
        """BR lines that go to `target` when `cond` holds and fall through otherwise. MCode tests
        one comparison per BR, so AND, OR, NOT and input patterns become several."""
        cond = simplify(cond)
        if isinstance(cond, ir.Logic) and cond.op == "or":
            self.jump_if(cond.left, target, span)
            self.jump_if(cond.right, target, span)
        elif isinstance(cond, ir.Logic) and cond.op == "and":
            skip = self.fresh_name()
            self.jump_if(ir.Not(cond.left), skip, span)
            self.jump_if(cond.right, target, span)
            self.line(f"LB {skip}", span)
        elif isinstance(cond, ir.InputMatch):
            self.jump_if(pattern_cond(cond.pattern), target, span)
        else:
            self.line(f"BR {target},{self.cond(cond)}", span)

    def unsupported(self, span, what: str) -> None:
        # never dropped: an IR built without spans (a program generated in memory) is reported on
        # the file, since a silently missing line changes what the program does
        span = span or self.fallback_span() or Span(self.module.path or "<ir>", 1, 1, 1, 1, 0, 0)
        self.diags.add("G003", span, f"{what} cannot be written in MCode")

    def fallback_span(self):
        for _, block in self.module.blocks():
            for op in block.ops:
                if op.span is not None:
                    return op.span
        return None

    # operations ----------------------------------------------------------------------------------
    def op_at(self, ops: list, index: int) -> int:
        """Write the operation at `index`; returns how many operations it used (IS/OS take two)."""
        op = ops[index]
        pair = ops[index + 1] if index + 1 < len(ops) else None
        if isinstance(op, ir.Setting) and op.name in ("input_function", "output_function", "soft_limit_position"):
            third = ops[index + 2] if index + 2 < len(ops) else None
            sourcing = third if isinstance(third, ir.Setting) and third.name == "io_sourcing" \
                and third.index == op.index and isinstance(pair, ir.Setting) and pair.index == op.index else None
            try:
                self.line(self.line_setup(op, pair, sourcing), op.span)
            except Unsupported as exc:
                self.unsupported(op.span, str(exc))
            return (3 if sourcing is not None else 2) if isinstance(pair, ir.Setting) and pair.index == op.index else 1
        if isinstance(op, ir.Setting) and op.name == "io_sourcing" and self.cat.io_setup != "point":
            # sinking/sourcing is wiring on a Lexium drive (the Reference input's bias): the
            # migration reported it (compiler/mcode/migrate.py); nothing to write
            return 1
        self.op(op)
        return 1

    def op(self, op) -> None:
        try:
            for text in self.op_lines(op):
                self.line(text, op.span)
        except Unsupported as exc:
            self.unsupported(op.span, str(exc))

    def op_lines(self, op) -> list[str]:
        """The lines of one operation: usually one; a converted ramp or a compound wait adds some."""
        before: list[str] = []
        if isinstance(op, (ir.Move, ir.Slew, ir.Home)) and self.ramps:
            before = self.ramp_lines(op)
        if isinstance(op, ir.WaitInput):
            return self.wait_input(op)
        if isinstance(op, ir.Call) and op.cond is not None and not isinstance(simplify(op.cond), (ir.Compare, ir.Truth)):
            return self.guarded_call(op)
        if isinstance(op, ir.SetOutput) and op.index is None:
            return self.all_outputs(op)
        if isinstance(op, ir.Print) and op.signed and self.report_var is not None:
            return self.signed_print(op)
        text = self.op_text(op)
        if isinstance(op, (ir.Move, ir.Home)) and text is not None:
            before = self.hold_first(op) + before
        return before + ([text] if text is not None else [])

    def hold_first(self, op) -> list[str]:
        """`H` before a move or homing whose axis may still be moving. The manual never says what a
        motion command does to a move in progress; it asks for `H` after every move (L3048) and for
        motion to have stopped before the next motion command (L5404). The IR's move waits for its
        axis to stop (docs/SIMULATOR.md, `move_while_busy = block`): the H makes the drive do the same."""
        axis = op.targets[0][0] if isinstance(op, ir.Move) else op.axis
        moving = self.moving.get(id(op))
        if moving is not None and (not moving or axis not in moving and axis != ir.ALL_AXES):
            return []
        if self.immediate:  # H is a program statement (M112): an immediate line cannot hold
            if self.foreign:
                raise Unsupported("a move sent while the previous one may still run, among immediate commands "
                                  "(MCode holds for a move only in a program, with H: L3048, M112); wait for the "
                                  "move in the source")
            return []  # an MCode source's own immediate lines: sent as the source sends them
        return [f"{self.prefix(axis)}H"]

    def prefix(self, axis: str) -> str:
        if self.foreign:
            if axis == ir.ALL_AXES:
                return ""
            if axis not in self.axis_map:
                raise Unsupported(f"an operation on axis {axis} (an MCode drive moves one axis: this program's "
                                  f"axis is {next(iter(self.axis_map), '?')}; compile the part of each axis on its "
                                  "own, one drive per axis)")
            return self.axis_map[axis]
        if axis in ("", self.drive):
            return ""
        return axis if axis != ir.ALL_AXES else "*"

    def op_text(self, op) -> str | None:
        """The statement of one operation (None: nothing to write), by its handler in `TEXT_METHODS`,
        one per operation of the table (compiler/ir_ops.py); one without a handler is refused."""
        method = TEXT_METHODS.get(type(op))
        if method is None:
            raise Unsupported(f"the operation {type(op).__name__}")
        return method(self, op)

    def _setting_text(self, op: ir.Setting) -> str | None:
        if op.name == "enable_outputs" and self.foreign:
            return self.enable_outputs(op)
        return self.setting(op)

    def _move_text(self, op: ir.Move) -> str:
        axes = {self.prefix(axis) for axis, _ in op.targets}
        if len(op.targets) != 1 or len(axes) != 1:
            raise Unsupported(f"a linear interpolation of {len(op.targets)} axes "
                              f"({', '.join(a for a, _ in op.targets)}): an MCode drive moves one axis")
        if op.mode is ir.MoveMode.MODAL:
            raise Unsupported("a move whose absolute or relative mode is not known")
        axis, target = op.targets[0]
        name = "MA" if op.mode is ir.MoveMode.ABSOLUTE else "MR"
        args = [self.position(target)] + [self.expr(value) for _, value in op.options]
        return f"{self.prefix(axis)}{name} {','.join(args)}"

    def _slew_text(self, op: ir.Slew) -> str:
        if op.velocity is None:
            return f"{self.prefix(op.axis)}SL {'-' if op.direction < 0 else ''}VM"
        return f"{self.prefix(op.axis)}SL {self.rate(op.velocity)}"

    def _wait_motion_text(self, op: ir.WaitMotion) -> str:
        return f"{self.prefix(op.axis)}H"

    def _delay_text(self, op: ir.Delay) -> str:
        return f"H {self.delay(op.duration)}"

    def _set_position_text(self, op: ir.SetPosition) -> str:
        return f"{self.prefix(op.axis)}P={self.position(op.value)}"

    def _output_text(self, op: ir.SetOutput) -> str:
        if op.index not in range(1, 4):
            raise Unsupported(f"output {op.index} (the drive has outputs 1 to 3)")
        return f"O{op.index}={self.expr(op.value)}"

    def _print_text(self, op: ir.Print) -> str | None:
        if op.signed:
            raise Unsupported("a report with the sign of every number, + included (X150 PR: *+4000, L3141; "
                              "MCode prints positive numbers unsigned),")
        if op.traced:
            raise Unsupported("a trace report of the command the device runs (a trace mode, X150 XTR, "
                              "parker-x150.md L5384),")
        op = self.with_known_address(op)
        formatted = [spec for spec in op.formats if spec]
        if formatted:
            raise Unsupported(f"a value printed in the format '{formatted[0]}' (docs/IR.md, \"Print formats\"; "
                              "MCode's PR prints a number as it is, floats in the PF format),")
        table = table_listing(op)
        if table is not None:  # one line of PR OS / PR LS: the statement is written at its first line
            return f"PR {table[0]}" if table[1] else None
        items = ",".join(self.item(item) for item in op.items)
        prefix = self.prefix(op.axis) if op.axis else ""
        return f"{prefix}PR {items}{'' if op.newline else ';'}"

    def _enable_text(self, op: ir.DriveEnable) -> str | None:
        if self.foreign and enable_outputs.undriven(self.module, op, set(self.axis_map)):
            self.undriven_enable(op)
            return None
        return f"{self.prefix(op.axis)}DE={self.expr(op.on)}"

    def _call_text(self, op: ir.Call) -> str:
        target = self.call_label(op.routine)
        return f"CL {target}" + (f",{self.cond(simplify(op.cond))}" if op.cond is not None else "")

    def _save_text(self, op: ir.Save) -> str:
        return "S"

    def _stop_text(self, op: ir.Stop) -> str | None:
        if op.ramp:
            return f"{self.prefix(op.axis)}SL 0"
        if self.foreign and id(op) in self.settled:
            return None  # no move can run here: the source's abort stops nothing (docs/CROSS.md, "Abort")
        raise Unsupported("an abort without deceleration while a move may run (MCode stops at once only with "
                          "ESC from the host, not a statement; stop with a ramp, SL 0, or wait for the move)")

    def _pause_text(self, op: ir.Pause) -> str:
        if not op.stop_motion and id(op) not in self.settled:
            raise Unsupported("a pause that lets a move in progress run on (MCode's PS ramps the move down, "
                              "L4931; wait for the move to end before the pause)")
        return f"{self.prefix(op.axis)}PS"

    def _resume_text(self, op: ir.Resume) -> str:
        return f"{self.prefix(op.axis)}RS"

    def _step_text(self, op: ir.Step) -> str:
        raise Unsupported("a single step sent by the host (MCode steps with a space typed in EX mode 2, which "
                          "a program cannot hold)")

    def enable_outputs(self, op: ir.Setting) -> str:
        """Another product's enable outputs as one mask (Arcus `EO=3`, arcus-pmx-4ex-sa.txt L748):
        the bit of this drive's axis as `DE` (0 or 1, lexium-mcode.txt L2362-L2378); the bits of axes
        the program never uses are drives the target does not have (backends/enable_outputs.py)."""
        axis = next(iter(self.axis_map), None) or enable_outputs.source_axes(self.module)[0]
        bit = enable_outputs.bit_of(self.module, axis)
        value = enable_outputs.enable_value(op.value, bit) if bit is not None else None
        if value is None:
            raise Unsupported(f"the enable outputs set to {self.expr(op.value)} (a mask of 0-15, axis {axis} in "
                              f"bit {bit}),")
        return f"DE={self.expr(value)}"

    def undriven_enable(self, op: ir.DriveEnable) -> None:
        span = op.span or self.fallback_span() or Span(self.module.path or "<ir>", 1, 1, 1, 1, 0, 0)
        self.diags.add("G060", span, f"the enable of axis {op.axis} is left out: this program never moves axis "
                                     f"{op.axis}, and the MCode drive is axis {next(iter(self.axis_map), '?')} "
                                     "only (DE enables its own bridge, lexium-mcode.txt L2362)")

    def motion_setting(self, op: ir.SetMotion) -> str | None:
        if op.param in (ir.MotionParam.ACCEL_TIME, ir.MotionParam.DECEL_TIME):
            self.prefix(op.axis)
            return None  # written as A=/D= before each move, from the speeds in force (ramp_lines)
        if op.param not in PARAM_NAMES:
            raise Unsupported(f"the motion setting {op.param.value}")
        if op.param is ir.MotionParam.RESOLUTION and self.foreign:
            self.prefix(op.axis)
            if in_own_steps(op, self.module):
                return None  # the unit of the source's positions, converted to this drive's
            raise Unsupported(f"a resolution of {self.expr(op.value)} steps/rev where the program's positions count "
                              f"{self.module.steps_per_rev} (the positions after it would change unit; set the "
                              "resolution once, before the first move)")
        if op.param is ir.MotionParam.RESOLUTION:
            return f"{self.prefix(op.axis)}MS={self.resolution(op.value)}"
        if op.param is ir.MotionParam.MAX_SPEED and self.foreign:
            self.check_initial_speed(op)
        name = PARAM_NAMES[op.param]
        return f"{self.prefix(op.axis)}{name}={self.ranged(name, self.rate(op.value), op)}"

    def ranged(self, name: str, text: str, op: ir.SetMotion) -> str:
        """A constant setting inside the catalog's range for `name`: a speed just under the minimum
        (an initial speed of 0 where VI starts at 1 step/s) is written as the minimum with warning
        G005 (it changes a move's time by about 1/acceleration); anything else outside is refused."""
        command = self.cat.lookup(name)
        bounds = command.entry.range if command is not None else None
        try:
            value = float(text)
        except ValueError:
            return text  # computed at run time: the drive checks it
        if bounds is None or bounds[0] <= value <= bounds[1]:
            return text
        low, high = bounds
        if op.param in (ir.MotionParam.INITIAL_SPEED, ir.MotionParam.MAX_SPEED) and 0 <= value < low:
            self.diags.add("G005", op.span or self.fallback_span() or Span(self.module.path or "<ir>", 1, 1, 1, 1, 0, 0),
                           f"the speed {text} is below MCode's minimum {name} of {low:g} steps/s: written as {low:g}")
            return format_number(low)
        raise Unsupported(f"{name}={text}, outside what MCode accepts ({low:g} to {high:g})")

    def check_initial_speed(self, op: ir.SetMotion) -> None:
        """MCode refuses VM not above VI (Error 22/23). A converted program that never set the initial
        speed would run with MCode's default VI, which the source did not choose: refused."""
        state = self.states.get(id(op), {})
        if lookup(state, ir.MotionParam.INITIAL_SPEED, op.axis) is None and isinstance(op.value, ir.Const):
            default = float(self.profile.get("mcode.default_initial_speed", 1000))
            if float(units.scale_rate(op.value.value, self.factor)) <= default:
                raise Unsupported(f"a maximum speed of {op.value.value} steps/s before any initial speed is set "
                                  f"(MCode's default initial speed {default:g} is not below it; set the initial "
                                  "speed in the source first)")

    def resolution(self, value) -> str:
        full = int(self.profile.get("full_steps_per_rev", FULL_STEPS_PER_REV))
        if isinstance(value, ir.Const):
            microsteps = Fraction(value.value) / full
            if microsteps.denominator != 1:
                raise Unsupported(f"a resolution of {value.value} steps/rev ({full} full steps per rev)")
            return str(int(microsteps))
        if isinstance(value, ir.BinOp) and value.op == "*" and value.right == ir.Const(full):
            return self.expr(value.left)
        raise Unsupported("a resolution computed at run time")

    def ramp_lines(self, op) -> list[str]:
        """A/D for a move when the source gave ramp times: (max - initial speed) / ramp time,
        from the settings in force (compiler/in_force.py); refused when they are not known."""
        state = self.states.get(id(op), {})
        axis = op.targets[0][0] if isinstance(op, ir.Move) else op.axis
        lines = []
        for time_param, name in ((ir.MotionParam.ACCEL_TIME, "A"), (ir.MotionParam.DECEL_TIME, "D")):
            ramp = lookup(state, time_param, axis)
            if ramp is None:
                if any(k[0] is time_param for k in state) or self.ramp_set_anywhere(time_param):
                    raise Unsupported(f"a move whose ramp time is only known at run time ({name}= needs it)")
                continue
            top = lookup(state, ir.MotionParam.MAX_SPEED, axis)
            low = lookup(state, ir.MotionParam.INITIAL_SPEED, axis)
            if top is None or low is None:
                raise Unsupported("a move whose ramp time cannot become an acceleration: the initial and maximum "
                                  "speeds in force are not known here")
            accel = units.accel_from_ramp(float(ramp.value), float(low.value), float(top.value))
            if accel is None:
                raise Unsupported(f"a ramp time of {ramp.value} s")
            value = round(float(units.scale_rate(accel, self.factor)))
            if self.written_ramp.get(name) != value:
                lines.append(f"{name}={max(value, 1)}")
                self.written_ramp[name] = value
        return lines

    def ramp_set_anywhere(self, param) -> bool:
        return any(isinstance(op, ir.SetMotion) and op.param is param
                   for _, block in self.module.blocks() for op in block.ops)

    def home(self, op: ir.Home) -> str:
        name = {"switch": "HM", "index": "HI", "offset": "HF"}.get(op.method)
        if name is None:
            raise Unsupported(f"homing by {op.method}")
        if op.speed is not None:  # X150 GH n
            raise Unsupported("homing at a speed of its own (MCode homes at the max speed VM; set VM to that speed "
                              "around the homing move in the source)")
        refused = homing.refusal(op, self.profile, self.module.steps_per_rev)
        if refused:  # HM creeps off at VI and leaves P alone (L3198): another homing moves the zero
            raise Unsupported(refused)
        if op.mode is not None:
            return f"{self.prefix(op.axis)}{name} {self.expr(op.mode)}"
        kind = HOME_TYPES.get((op.direction, op.creep))
        if kind is None:
            raise Unsupported("homing without a seek direction")
        return f"{self.prefix(op.axis)}{name} {kind}"

    def setting(self, op: ir.Setting) -> str:
        register = registers().get(op.name)
        if op.name not in SETTINGS and register is not None:  # a drive register (the catalog's `setting`)
            info = ir_names.SETTINGS[op.name]
            if info.value_type == "text":
                if not isinstance(op.value, ir.Text):
                    raise Unsupported(f"the setting {op.name} from a computed value")
                return f"{self.prefix(op.axis)}{register}={op.value.value}"
            value = units.from_ir(op.value, MS_TO_S) if info.unit is ir.Unit.S else op.value
            return f"{self.prefix(op.axis)}{register}={self.expr(value)}"
        if op.name not in SETTINGS:
            info = ir_names.SETTINGS.get(op.name)
            raise Unsupported(f"the setting {op.name}" + (f" ({info.meaning})" if info else ""))
        name, factor = SETTINGS[op.name]
        if name == "D":  # D1-D4: one per input
            if op.index not in range(1, 5):
                raise Unsupported(f"a debounce time for input {op.index}")
            name = f"D{op.index}"
        value = op.value
        if factor != 1:
            value = units.from_ir(value, 1 / factor)
        return f"{self.prefix(op.axis)}{name}={self.expr(value)}"

    def line_setup(self, op: ir.Setting, pair, sourcing=None) -> str:
        if op.name == "soft_limit_position":  # LS=<0/1>,<position>,<0/1> (L4023-L4044)
            if not (isinstance(pair, ir.Setting) and pair.name == "soft_limit_enable" and pair.index == op.index):
                raise Unsupported("a software limit's position without its enable (MCode's LS sets both)")
            return f"{self.prefix(op.axis)}LS={op.index},{self.position(op.value)},{self.expr(pair.value)}"
        table, name = (INPUT_TYPES, "IS") if op.name == "input_function" else (OUTPUT_TYPES, "OS")
        function = op.value.value if isinstance(op.value, ir.Text) else None
        if function not in table:
            raise Unsupported(f"an {op.name} of {function}")
        paired = isinstance(pair, ir.Setting) and pair.index == op.index \
            and pair.name == op.name.replace("function", "active_high")
        if not paired and name == "OS":  # `OS=3,29`: the type only, the line keeps its active level (L4646)
            return f"{self.prefix(op.axis)}{name}={op.index},{table[function]}"
        if not paired:  # IS sets the active level too (the manual shows no IS without it, L3500-L3533)
            raise Unsupported(f"an {op.name} without its active level (MCode's IS sets both; the source sets "
                              "only the function)")
        active = pair.value
        if self.cat.io_setup == "point":  # MDrivePlus: S<point>=<function>,<active>[,<sink/source>]
            extra = f",{self.expr(sourcing.value)}" if sourcing is not None else ""
            if f"S{op.index}" not in self.cat.commands:
                raise Unsupported(f"setting up I/O point {op.index} (the drive has S1-S4)")
            return f"{self.prefix(op.axis)}S{op.index}={table[function]},{self.expr(active)}{extra}"
        return f"{self.prefix(op.axis)}{name}={op.index},{table[function]},{self.expr(active)}"

    def all_outputs(self, op: ir.SetOutput) -> list[str]:
        """Every output at once. OT sets outputs 1-3 from a 3-bit value, 0-7 (L4669; the range line
        L4671 says 1-7, the catalog takes 0-7): a value with a higher bit would set outputs the drive
        lacks, so it is refused; a pattern (X150 `O1X0`) becomes one `On=` per output it sets (an OT
        would also set the outputs it leaves as they are), and is refused when it sets one above 3."""
        value = op.value
        if isinstance(value, ir.Pattern):
            beyond = [n + 1 for n, bit in enumerate(value.bits) if n >= OUTPUTS and bit in "01"]
            if beyond:
                raise Unsupported(f"setting output {beyond[0]} in the pattern {value.bits} (the drive has outputs 1 "
                                  f"to {OUTPUTS})")
            return [f"O{n + 1}={bit}" for n, bit in enumerate(value.bits[:OUTPUTS]) if bit in "01"]
        if isinstance(value, ir.Const):
            number = value.value
            if isinstance(number, float) and number.is_integer():
                number = int(number)
            if not isinstance(number, int) or not 0 <= number < 2 ** OUTPUTS:
                raise Unsupported(f"all outputs set to {format_number(value.value)} (OT takes 0-7, outputs 1-3 as "
                                  f"bits, L4669: a higher bit is an output the drive lacks)")
            return [f"OT={number}"]
        if self.foreign:
            raise Unsupported("all outputs set from a value computed at run time (OT takes 0-7, outputs 1-3 as bits, "
                              "L4669, and the source's value may set outputs the drive lacks: set outputs 1-3 "
                              "one by one)")
        return [f"OT={self.expr(value)}"]  # an MCode source's own OT: the drive checks it as the source's would

    def wait_input(self, op: ir.WaitInput) -> list[str]:
        """MCode has no wait-for-input statement: a loop that tests until the condition holds."""
        here = self.fresh_name()
        self.line(f"LB {here}", op.span)
        self.jump_if(ir.Not(op.cond), here, op.span)
        return []

    def with_known_address(self, op: ir.Print) -> ir.Print:
        """`op` with the address of the device that runs it written out as text where the print
        formats it (X150 `QS` answers `;*01!`, "an asterisk, a two digit device address, an
        exclamation mark", parker-x150.md L3209-L3217). The converted program runs on the one drive
        that stands for the source's device (`axis_map`; a universal command's device is the source
        profile's first, as in the simulator): its address is a number known here, and the
        drive sends the same characters. MCode has no such reading (its party name DN is a letter)."""
        if not self.foreign or not any(isinstance(item, ir.Status) and item.meaning == "device_address"
                                       for item in op.items):
            return op
        items, formats = list(op.items), list(op.formats) + [""] * (len(op.items) - len(op.formats))
        for at, item in enumerate(items):
            if not (isinstance(item, ir.Status) and item.meaning == "device_address"):
                continue
            device = item.axis if item.axis not in ("", ir.ALL_AXES) else next(iter(self.axis_map), "")
            if device in ("", ir.ALL_AXES):
                source = self.source_profile()
                device = source.axes[0] if source is not None and source.axes else ""
            if device not in self.axis_map and self.axis_map or not str(device).isdigit():
                raise Unsupported(f"the address of device {device or '?'} (the drive stands for one device: "
                                  f"{next(iter(self.axis_map), '?')})")
            words = formats[at].split()
            if words and (words[0] != "pad" or len(words) != 2):
                continue  # another format: refused below as any formatted value
            text = str(int(device)).rjust(int(words[1]) if words else 0, "0")  # `pad n`: leading zeros
            items[at], formats[at] = ir.Text(text, item.span), ""
        merged: list = []  # neighbouring texts as one string: `PR ";*01!"`
        merged_formats: list[str] = []
        for item, spec in zip(items, formats):
            if isinstance(item, ir.Text) and merged and isinstance(merged[-1], ir.Text) and not spec:
                merged[-1] = ir.Text(merged[-1].value + item.value, merged[-1].span)
                continue
            merged.append(item)
            merged_formats.append(spec)
        return dataclasses.replace(op, items=tuple(merged), formats=tuple(merged_formats))

    def source_profile(self) -> Profile | None:
        try:
            return profiles.load(self.module.profile)
        except Exception:  # a profile built in memory or a user's file: no device to name
            return None

    def signed_print(self, op: ir.Print) -> list[str]:
        """A report that sends every number with its sign, `+` included (X150 `1PR` answers
        `*+4000` and `*-25600`: "a number preceded by a sign", parker-x150.md L3141-L3143).
        MCode's PR sends a negative number with its `-` and a positive one bare (L4880-L4906), so
        the `+` is printed by a branch on the value, read once into a variable of its own (the
        position read twice could change between the test and the print):

            Z9=P                the value (in the source's steps: P/5 where the output counts 5
            BR Z8,Z9<0          of its steps per source step, `step_values`)
            PR "*+",Z9
            BR Z7
            LB Z8
            PR "*",Z9
            LB Z7

        Each way is one whole PR, so the host receives the report in one piece as from the X150.

        A program statement (BR, M112): an immediate stream that reports becomes the program
        (`as_program`). Only a report of a position reading: X150 sends no other signed value
        but TX, whose fixed-point format MCode has not."""
        values = [i for i, item in enumerate(op.items) if not isinstance(item, ir.Text)]
        if len(values) != 1 or any(op.formats) or op.traced or not isinstance(op.items[values[0]], ir.Status) \
                or op.items[values[0]].meaning not in ("position", "encoder"):
            raise Unsupported("a report with the sign of every number, + included (X150 PR: *+4000, L3141; "
                              "MCode prints positive numbers unsigned),")
        if self.immediate:
            raise Unsupported("a signed report among immediate commands (MCode prints the + by a branch, which "
                              "runs only in a program, M112)")
        at = values[0]
        value, var = op.items[at], self.report_var
        source = self.expr(value)
        if self.factor != 1:
            if self.stops_anywhere():
                raise Unsupported(f"a position report where the output counts {self.profile.steps_per_rev} steps/rev "
                                  f"and the source {self.module.steps_per_rev}, in a program that homes or runs at a "
                                  "velocity (a switch or a stop may leave the drive between two source steps; give "
                                  "a target profile with the source's steps_per_rev, --profile)")
            if self.factor.denominator == 1:
                source = f"{source}/{self.factor.numerator}"  # whole: every move lands on a multiple
            elif self.factor.numerator == 1:
                source = f"{source}*{self.factor.denominator}"
            else:
                raise Unsupported(f"a position report where the output counts {self.profile.steps_per_rev} "
                                  f"steps/rev and the source {self.module.steps_per_rev} (not a whole ratio)")
        prefix = self.prefix(op.axis) if op.axis else ""
        end = "" if op.newline else ";"

        def report(sign: str) -> str:
            texts = [self.item(item) for item in op.items[:at]]
            if sign and texts and texts[-1].endswith('"'):
                texts[-1] = texts[-1][:-1] + sign + '"'
            elif sign:
                texts.append(f'"{sign}"')
            return f"{prefix}PR {','.join(texts + [var] + [self.item(item) for item in op.items[at + 1:]])}{end}"

        negative, done = self.fresh_name(), self.fresh_name()
        return [f"{var}={source}", f"BR {negative},{var}<0", report("+"), f"BR {done}", f"LB {negative}",
                report(""), f"LB {done}"]

    def guarded_call(self, op: ir.Call) -> list[str]:
        skip = self.fresh_name()
        self.jump_if(ir.Not(op.cond), skip, op.span)
        self.line(f"CL {self.call_label(op.routine)}", op.span)
        self.line(f"LB {skip}", op.span)
        return []

    def call_label(self, name: str) -> str:
        routine = self.module.routine(name)
        if routine is not None and routine.entry is not None:
            return self.label(routine.entry.label)
        if self.foreign:
            raise Unsupported(self.not_in_file("a call of", name))
        return self.label(name)

    def in_source_steps(self, value) -> str:
        """`value`, a sum of a position reading and plain numbers (X150 `VAR8=POS+50000`), in the
        source's steps: the reading divided by the steps this drive counts per source step (`P/5`),
        exact where every position the output moves to is a multiple of them (a homing may stop
        between two: refused). MCode evaluates left to right (docs/dialects/mcode.md), so the
        reading must come first: `P/5+50000`."""
        readings = step_readings(value)
        self.source_units = True  # constants in steps as the source wrote them
        try:
            text = self.expr(value)
        finally:
            self.source_units = False
        if not readings:
            return text
        leftmost = value
        while isinstance(leftmost, ir.BinOp):
            leftmost = leftmost.left
        if len(readings) != 1 or leftmost is not readings[0] or self.stops_anywhere():
            raise Unsupported(self.mixed_steps())
        head = self.expr(leftmost)
        if self.factor.denominator == 1:
            scaled = f"{head}/{self.factor.numerator}"
        elif self.factor.numerator == 1:
            scaled = f"{head}*{self.factor.denominator}"
        else:
            raise Unsupported(self.mixed_steps())
        return scaled + text[len(head):]

    def stops_anywhere(self) -> bool:
        """Whether the drive may stop between two of the source's steps: after a homing (where the
        switch is found) or a run at a velocity (where the stop comes). Every move of the output
        lands on a whole source step, so elsewhere P divides exactly."""
        return any(isinstance(o, (ir.Home, ir.Slew)) for _, b in self.module.blocks() for o in b.ops)

    def mixed_steps(self) -> str:
        return (f"a value that adds a position in steps to a plain number (the output counts "
                f"{self.profile.steps_per_rev} steps/rev where the source counts {self.module.steps_per_rev}: "
                "the steps are scaled, the number is not; docs/CROSS.md, \"Steps in variables\")")

    def not_in_file(self, what: str, name: str) -> str:
        """A routine the source calls that this file does not define (an X150 sequence stored on the
        controller, `Module.externals`): the output cannot call what was never converted."""
        if name in self.module.externals:
            return (f"{what} {name}, which is stored on the source's controller and not defined in this file "
                    "(a converted program has only what the file defines: add the definition of "
                    f"{name} to the file, or compile a file that has it),")
        return f"{what} {name}, which is not in this program"

    def assign(self, op: ir.Assign) -> str:
        target = self.var(op.target.name)
        value = op.value
        too_big = int32.overflow(self.module, op) if self.foreign else None
        if too_big:
            raise Unsupported(too_big + ",")
        if self.step_values is not None:
            kind = self.step_values.kind(value)
            if kind == MIXED or self.step_values.vars.get(op.target.name) == MIXED:
                raise Unsupported(self.mixed_steps())
            if self.step_values.holds_plain(op.target.name):  # the variable holds the source's units
                if kind == STEPS:
                    raise Unsupported(self.mixed_steps())
                return f"{target}={self.in_source_steps(value)}"
        if isinstance(value, ir.BinOp) and value.op in "+-" and value.left == op.target \
                and isinstance(value.right, ir.Const) and value.right.value == 1:
            return f"{'IC' if value.op == '+' else 'DC'} {target}"
        return f"{target}={self.expr(value)}"

    def handler(self, op: ir.SetHandler) -> str:
        label = self.call_label(op.routine) if op.routine else ""
        if op.takes_over:
            raise Unsupported(f"a '{op.event}' handler that takes over the program (MCode's handlers interrupt it "
                              "and return)")
        if op.event == "error":
            if op.once or op.gated:
                raise Unsupported("an error handler that fires once or only when enabled (MCode's OE runs on every "
                                  "error, L4538)")
            return f"OE {label}"
        name = TRIPS.get(op.event)
        if name is None:
            raise Unsupported(f"a '{op.event}' event handler")
        if op.routine and not (op.once and op.gated):
            raise Unsupported(f"a '{op.event}' handler that stays armed (an MCode trip {name} fires once, while its TE "
                              "bit is set, L5667)")
        args = [self.trip_arg(name, i, a) for i, a in enumerate(op.args)]
        if name == "TI":
            return f"TI {','.join(args[:1] + [label])}"
        if name in ("TC", "TM"):
            return f"{name}={label}"
        if name == "TR":
            return f"TR={','.join(args[:1] + [label] + args[1:])}"
        if name == "TA":
            return f"TA={','.join([label] + args)}"
        return f"{name}={','.join(args + [label])}"

    def trip_arg(self, name: str, index: int, value) -> str:
        if index == 0 and name in ("TP", "TR"):
            return self.position(value)
        if index == 0 and name == "TT":
            return self.expr(units.from_ir(value, MS_TO_S))
        return self.expr(value)

    def native(self, op: ir.Native) -> str:
        if op.dialect != DIALECT:
            raise Unsupported(f"the {op.dialect} command {op.mnemonic}")
        args = ",".join(self.item(a) for a in op.args)
        if op.form == "number":
            return args
        command = self.cat.lookup(op.mnemonic)
        prefix = self.prefix(op.axis)
        if not op.args:
            return f"{prefix}{op.mnemonic}"
        setting = command is not None and command.kind in (cat.VARIABLE, cat.FLAG)
        return f"{prefix}{op.mnemonic}{'=' if setting else ' '}{args}"

    # quantities ----------------------------------------------------------------------------------
    def position(self, value) -> str:
        """A position or distance in this drive's steps, scaled from the source's."""
        if self.factor == 1:
            return self.expr(value)
        if isinstance(value, ir.Const):
            scaled = units.scale_steps(value.value, self.factor)
            if not scaled.exact:
                raise Unsupported(f"the position {value.value} steps (source {self.module.steps_per_rev} steps/rev) "
                                  f"falls between two steps of the target ({self.profile.steps_per_rev} steps/rev): "
                                  "give a profile whose steps_per_rev makes it exact (--profile)")
            return format_number(scaled.value)
        kind = self.step_values.kind(value) if self.step_values is not None else None
        if kind in IN_STEPS:  # already in this drive's steps: its constants are scaled, P counts them
            return self.expr(value)
        if kind == MIXED:
            raise Unsupported(self.mixed_steps())
        if self.factor.denominator == 1:
            return f"{self.expr(value)}*{self.factor.numerator}"
        raise Unsupported("a position computed at run time, which cannot be scaled exactly to this drive's steps")

    def rate(self, value) -> str:
        """A speed or acceleration in this drive's steps per second (per second)."""
        if isinstance(value, ir.Const):
            scaled = units.scale_rate(value.value, self.factor)
            return format_number(round(scaled) if self.foreign else scaled)
        if self.factor == 1:
            return self.expr(value)
        raise Unsupported("a speed computed at run time, which cannot be scaled to this drive's steps")

    def delay(self, duration) -> str:
        value = units.from_ir(duration, MS_TO_S)
        if isinstance(value, ir.Const):
            ms = value.value
            return format_number(int(round(ms)) if not isinstance(ms, int) else ms)
        return self.expr(value)

    # expressions ---------------------------------------------------------------------------------
    def item(self, node) -> str:
        if isinstance(node, ir.Text):
            return f'"{node.value}"'
        if isinstance(node, (ir.Compare, ir.Truth, ir.Logic, ir.Not, ir.InputMatch)):
            return self.cond(node)
        return self.expr(node)

    def expr(self, node) -> str:
        if isinstance(node, ir.Const):
            if node.value == PI and node.unit is ir.Unit.NONE:
                return "PI"  # the drive's PI, 3.141592654 (L6658)
            if node.unit is ir.Unit.STEPS and self.factor != 1 and not self.source_units:
                return self.position(node)
            if node.unit in (ir.Unit.STEPS_PER_S, ir.Unit.STEPS_PER_S2) and self.factor != 1:
                return self.rate(node)
            return format_number(node.value)
        if isinstance(node, ir.Var):
            return self.var(node.name)
        if isinstance(node, ir.Status):
            return self.status(node)
        if isinstance(node, ir.DeviceRef):
            if node.dialect != DIALECT:
                raise Unsupported(f"the {node.dialect} value {node.name}")
            return node.name
        if isinstance(node, ir.LabelRef):
            return self.label(node.name)
        if isinstance(node, ir.Text):
            return f'"{node.value}"'
        if isinstance(node, ir.UnOp):
            operand = self.expr(node.operand)
            if isinstance(node.operand, ir.BinOp):
                raise Unsupported("an operator applied to a whole expression")
            if node.op == "!":
                raise Unsupported("a logical NOT inside an expression")
            return ("-" if node.op == "-" else "!") + operand
        if isinstance(node, ir.BinOp) and read_back(node) is not None:
            return read_back(node)
        if isinstance(node, ir.BinOp):
            if isinstance(node.right, ir.BinOp):
                raise Unsupported("an expression that needs parentheses (MCode evaluates left to right)")
            op = node.op
            if op not in ("+", "-", "*", "/", "&", "|", "^"):
                raise Unsupported(f"the operator {op}")
            return f"{self.expr(node.left)}{op}{self.expr(node.right)}"
        if isinstance(node, ir.Func):
            if node.name == "pi":
                return "PI"
            name = FUNCTIONS.get(node.name)
            if node.name in ("log", "log2", "log10"):  # LO is the logarithm the profile says (docs/dialects/mcode.md)
                lo = self.profile.get("mcode.lo_function", "log")
                name = "LO" if node.name == lo else ("L_" if node.name == "log10" else None)
            if name is None or len(node.args) != 1:
                raise Unsupported(f"the function {node.name}")
            return f"{name} {self.expr(node.args[0])}"
        raise Unsupported(f"the value {type(node).__name__}")

    def status(self, node: ir.Status) -> str:
        if node.meaning in registers():  # a drive register read back (PR CW)
            return registers()[node.meaning]
        if node.meaning in SETTINGS and SETTINGS[node.meaning][1] == 1 and node.meaning not in READINGS:
            return SETTINGS[node.meaning][0]  # a setting read back in its own units (PR TE)
        if node.meaning in INDEXED_READINGS:
            prefix, numbers = INDEXED_READINGS[node.meaning]
            index = node.index if node.meaning != "analog" else (node.index or 1) + 4
            if index not in numbers:
                raise Unsupported(f"{node.meaning} {node.index} (the drive has no such line)")
            return f"{prefix}{index}"
        name = READINGS.get(node.meaning)
        if name is None:
            raise Unsupported(f"the reading {node.meaning}")
        if self.foreign and node.meaning in ("inputs", "outputs") and id(node) not in self.masked_banks:
            self.bank_width(node.meaning)
        if self.foreign and node.axis not in ("", ir.ALL_AXES):
            self.prefix(node.axis)  # refuses a reading of another axis
        return name

    def bank_width(self, meaning: str) -> None:
        """Refuses another product's reading of every input (or output) at once as one number when
        its bank is not as wide as the drive's: IN is inputs 1-4 (lexium-mcode.txt L3433), OT outputs
        1-3 (L851), Arcus DI and DO eight (arcus-pmx-4ex-sa.txt L752, L797): the number would differ.
        A bank compared with a number is an input pattern by then (in_force.with_bank_patterns)."""
        kind = "inputs" if meaning == "inputs" else "outputs"
        source = in_force.source_profile(self.module, self.profile)
        theirs = source.get(f"machine.{kind}.count", 0) if source is not None else 0
        ours = self.profile.get(f"machine.{kind}.count", 0)
        if theirs != ours or not theirs:  # (a bank whose every use is masked to the drive's bits: masked_bank_reads)
            raise Unsupported(f"every {kind[:-1]} read at once as one number (the source's bank has "
                              f"{theirs or 'an unknown number of'} {kind}, {READINGS[meaning]} has {ours or '?'}: the "
                              f"value would differ; read the {kind} one by one, or keep the drive's with `&`, as V2=V1&6)")

    def cond(self, node) -> str:
        node = simplify(node)
        if isinstance(node, ir.Compare) and self.step_values is not None:
            kind = self.step_values.kind(node)
            if kind == MIXED or step_readings(node) and kind == PLAIN:
                raise Unsupported(self.mixed_steps())
            if kind == PLAIN:  # a variable in the source's units against constants as written
                self.source_units = True
                try:
                    return f"{self.expr(node.left)}{COMPARE[node.op]}{self.expr(node.right)}"
                finally:
                    self.source_units = False
        if isinstance(node, ir.Compare):
            return f"{self.expr(node.left)}{COMPARE[node.op]}{self.expr(node.right)}"
        if isinstance(node, ir.Truth):
            return self.expr(node.expr)
        raise Unsupported("a condition with AND/OR or an input pattern here (MCode tests one condition)")



# One handler per operation of the table (compiler/ir_ops.py): the statement it is written as (None:
# nothing to write), or `Unsupported` at its line; an operation without one (an arc: an MCode drive
# moves one axis) is refused by `Writer.op_text` (tests/ir/test_handlers.py).
TEXT_METHODS = {
    ir.Native: Writer.native,
    ir.Assign: Writer.assign,
    ir.SetMotion: Writer.motion_setting,
    ir.Setting: Writer._setting_text,
    ir.Move: Writer._move_text,
    ir.Slew: Writer._slew_text,
    ir.Home: Writer.home,
    ir.WaitMotion: Writer._wait_motion_text,
    ir.Delay: Writer._delay_text,
    ir.SetPosition: Writer._set_position_text,
    ir.SetOutput: Writer._output_text,
    ir.Print: Writer._print_text,
    ir.DriveEnable: Writer._enable_text,
    ir.Call: Writer._call_text,
    ir.SetHandler: Writer.handler,
    ir.Save: Writer._save_text,
    ir.Stop: Writer._stop_text,
    ir.Pause: Writer._pause_text,
    ir.Resume: Writer._resume_text,
    ir.Step: Writer._step_text,
}

def line_of(routine: ir.Routine) -> int:
    """The source line a routine starts on (its first spanned operation when it has no span)."""
    if routine.span is not None:
        return routine.span.line
    spans = (op.span for block in routine.blocks for op in block.ops if op.span is not None)
    return next((span.line for span in spans), 0)


def masked_bank_reads(module: ir.Module, profile: Profile) -> set[int]:
    """The readings of every input (output) at once (by id) whose value only counts through an AND
    with a number within the drive's bits: `V1=DI` where every use of V1 is `V1&6` (arcus
    samples/sorting_station.prg), or `DI&6` itself. Such a value is the same on a bank of another
    width (IN: inputs 1-4, lexium-mcode.txt L3433, raw levels as Arcus DI, L797), so it is written."""
    widths = {"inputs": profile.get("machine.inputs.count", 0), "outputs": profile.get("machine.outputs.count", 0)}

    def within(node, meaning) -> bool:
        return isinstance(node, ir.BinOp) and node.op == "&" and isinstance(node.right, ir.Const) \
            and isinstance(widths[meaning], int) and 0 <= node.right.value < 2 ** widths[meaning]

    exprs = [e for _, b in module.blocks() for e in [*(x for op in b.ops for x in ir.op_exprs(op)),
                                                      *ir.term_exprs(b.terminator)]]
    found: set[int] = set()
    for expr in exprs:
        for node in ir.walk_expr(expr):
            if within(node, "inputs") or within(node, "outputs"):
                if isinstance(node.left, ir.Status) and node.left.meaning in widths and within(node, node.left.meaning):
                    found.add(id(node.left))
    for _, block in module.blocks():
        for op in block.ops:
            if isinstance(op, ir.Assign) and isinstance(op.value, ir.Status) and op.value.meaning in widths:
                name, meaning = op.target.name, op.value.meaning
                uses = [(n, parent) for e in exprs for parent in ir.walk_expr(e)
                        for n in _children(parent) if isinstance(n, ir.Var) and n.name == name]
                bare = [n for e in exprs if isinstance(e, ir.Var) and e.name == name for n in [e]]
                if uses and not bare and all(parent.left is n and within(parent, meaning) for n, parent in uses):
                    found.add(id(op.value))
    return found


def _children(node) -> tuple:
    if isinstance(node, ir.BinOp):
        return (node.left, node.right)
    if isinstance(node, ir.UnOp):
        return (node.operand,)
    if isinstance(node, ir.Func):
        return tuple(node.args)
    if isinstance(node, (ir.Compare, ir.Logic)):
        return (node.left, node.right)
    if isinstance(node, ir.Truth):
        return (node.expr,)
    if isinstance(node, ir.Not):
        return (node.cond,)
    return ()


def threaded(term, through):
    """A copy of a jump or branch with its targets followed through empty blocks."""
    if isinstance(term, ir.Jump):
        return ir.Jump(through(term.target), term.span)
    if isinstance(term, ir.Branch):
        return ir.Branch(term.cond, through(term.then), through(term.otherwise), term.span)
    return term


def is_user_name(name: str, reserved) -> bool:
    """A valid MCode user name: two characters, a letter then a letter or digit, not a mnemonic."""
    return len(name) == 2 and name.isascii() and name[0].isalpha() and name[1].isalnum() \
        and name.upper() == name and name not in reserved


def op_axes(op) -> list[str]:
    if isinstance(op, ir.Move):
        return [axis for axis, _ in op.targets]
    if isinstance(op, ir.Arc):
        return list(op.axes)
    axis = getattr(op, "axis", "")
    return [axis] if axis else []


def simplify(cond):
    """Push NOT inward: into comparisons (negated operator) and through AND/OR (De Morgan)."""
    if not isinstance(cond, ir.Not):
        return cond
    inner = cond.cond
    if isinstance(inner, ir.Not):
        return simplify(inner.cond)
    if isinstance(inner, ir.Compare):
        return ir.Compare(NEGATE[inner.op], inner.left, inner.right, inner.span)
    if isinstance(inner, ir.Truth):
        return ir.Compare("=", inner.expr, ir.Const(0), inner.span)
    if isinstance(inner, ir.Logic):
        flipped = "or" if inner.op == "and" else "and"
        return ir.Logic(flipped, simplify(ir.Not(inner.left)), simplify(ir.Not(inner.right)), inner.span)
    if isinstance(inner, ir.InputMatch):
        return simplify(ir.Not(pattern_cond(inner.pattern)))
    return cond


def pattern_cond(pattern: ir.Pattern):
    """An input pattern (bit n for input n+1; X: either) as a conjunction of input tests."""
    tests = [ir.Compare("=", ir.Status("input", "", n + 1), ir.Const(int(bit)), pattern.span)
             for n, bit in enumerate(pattern.bits) if bit in "01"]
    if not tests:
        return ir.Compare("=", ir.Const(0), ir.Const(0), pattern.span)
    cond = tests[0]
    for test in tests[1:]:
        cond = ir.Logic("and", cond, test, pattern.span)
    return cond


def moving_before(module: ir.Module, foreign: bool = False) -> dict[int, frozenset[str]]:
    """The axes that may still be moving before each operation (by id), for `Writer.hold_first`.

    A forward data flow over the blocks of every routine, and across calls: a move, homing or slew
    starts its axes, a wait for motion (`H`) ends them, an arc or native command may leave any axis
    running, and a call leaves what its routine may leave at its end. A program (main, power-up,
    immediate) starts with nothing moving; a subroutine with what its callers may leave running; a
    handler, which interrupts anywhere, with what may be running anywhere else or at the end of a
    handler; and what a handler may leave running at its end may be running before any operation.
    A block another routine jumps to, or that nothing reaches, may start with any axis moving.

    `foreign`: the module is another dialect's, written as one MCode program. Its second and later
    main routines (X150 sequences the host starts) become labels in that program, which MCode
    reads back as subroutines nothing calls: they start with any axis moving here too, so that
    compiling the output again writes the same H (issue 24)."""
    return Motion(module, foreign).run()


class Motion:
    """The data flow of `moving_before`; states are sets of the module's axis names."""

    STARTS = (ir.RoutineKind.MAIN, ir.RoutineKind.IMMEDIATE, ir.RoutineKind.POWERUP)

    def __init__(self, module: ir.Module, foreign: bool = False):
        self.module = module
        self.foreign = foreign
        axes = {axis for _, b in module.blocks() for op in b.ops for axis in op_axes(op)}
        axes |= {op.axis for _, b in module.blocks() for op in b.ops if isinstance(op, ir.WaitMotion)}
        axes.discard(ir.ALL_AXES)
        self.anything = frozenset(axes or {ir.ALL_AXES})
        self.seen: dict[str, frozenset[str]] = {}
        self.foreign_jumps: set[str] = set()
        for routine in module.routines:
            own = {b.label for b in routine.blocks}
            for block in routine.blocks:
                self.foreign_jumps.update(t for t in successors(block.terminator) if t not in own)

    def axes(self, axis: str) -> frozenset[str]:
        return self.anything if axis == ir.ALL_AXES else frozenset({axis})

    def after(self, op, moving: frozenset[str]) -> frozenset[str]:
        if isinstance(op, ir.WaitMotion):
            return moving - self.axes(op.axis)
        if isinstance(op, ir.Move):
            return moving.union(*(self.axes(axis) for axis, _ in op.targets))
        if isinstance(op, (ir.Slew, ir.Home)):
            return moving | self.axes(op.axis)
        if isinstance(op, (ir.Arc, ir.Native)):
            return self.anything
        return moving

    def run(self) -> dict[int, frozenset[str]]:
        module = self.module
        called = {op.routine for _, b in module.blocks() for op in b.ops if isinstance(op, ir.Call)}
        called |= {b.terminator.routine for _, b in module.blocks() if isinstance(b.terminator, ir.GotoRoutine)}
        handlers = [r for r in module.routines if r.kind is ir.RoutineKind.HANDLER]
        entry: dict[str, frozenset[str]] = {}
        mains = [r.name for r in module.routines if r.kind is ir.RoutineKind.MAIN]
        for routine in module.routines:
            known = routine.kind in self.STARTS or routine.kind is ir.RoutineKind.HANDLER \
                or routine.kind is ir.RoutineKind.SUBROUTINE and routine.name in called
            if self.foreign and routine.kind is ir.RoutineKind.MAIN and routine.name in mains[1:] \
                    and routine.name not in called:
                known = False
            entry[routine.name] = frozenset() if known else self.anything  # else: filled below
        exits: dict[str, frozenset[str]] = {r.name: frozenset() for r in module.routines}
        handler_names = {r.name for r in handlers}
        while True:
            result: dict[int, frozenset[str]] = {}
            self.seen = {}  # routine -> every state at any of its points
            found: list[tuple[str, frozenset[str]]] = []
            for routine in module.routines:
                found += [(name, state) for name, state in self.flow(routine, entry[routine.name], exits, result)]
            # what a handler starts and leaves running (from a standstill, in a scratch run); a
            # handler does not interrupt another (docs/SIMULATOR.md), so it interrupts the others' states
            scratch: dict[int, frozenset[str]] = {}
            ends = [(r, self.flow(r, frozenset(), exits, scratch)) for r in handlers]
            leftover = frozenset().union(*(state for r, found_here in ends for name, state in found_here
                                           if name == "exit:" + r.name))
            anywhere = frozenset().union(*(state for name, state in self.seen.items()
                                           if name not in handler_names)) | leftover
            changed = False
            for name, state in found:
                target = exits if name.startswith("exit:") else entry
                key = name.removeprefix("exit:")
                if key in target and not state <= target[key]:
                    target[key] |= state
                    changed = True
            for routine in handlers:  # a handler interrupts wherever the others are
                if not anywhere <= entry[routine.name]:
                    entry[routine.name] |= anywhere
                    changed = True
            if not changed:
                return {key: state | leftover for key, state in result.items()} if leftover else result

    def visit(self, routine: ir.Routine, by_label: dict[str, ir.Block], state_in: dict[str, frozenset[str]],
              reached: set[str], work: list[str], exits: dict[str, frozenset[str]], result: dict[int, frozenset[str]],
              found: list[tuple[str, frozenset[str]]]) -> None:
        """Run the work list to a fixed point, widening each block's entry state."""
        while work:
            label = work.pop()
            reached.add(label)
            block = by_label[label]
            moving = state_in[label]
            for op in block.ops:
                self.seen[routine.name] = self.seen.get(routine.name, frozenset()) | moving
                result[id(op)] = result.get(id(op), frozenset()) | moving
                if isinstance(op, ir.Call):
                    found.append((op.routine, moving))
                    moving = exits[op.routine] if op.routine in exits else self.anything
                else:
                    moving = self.after(op, moving)
            self.seen[routine.name] = self.seen.get(routine.name, frozenset()) | moving
            term = block.terminator
            if isinstance(term, ir.GotoRoutine):
                found.append((term.routine, moving))
            elif not isinstance(term, (ir.Jump, ir.Branch)):
                found.append(("exit:" + routine.name, moving))
            for target in successors(term):
                if target not in by_label:
                    continue
                merged = state_in[target] | moving
                if target not in reached or merged != state_in[target]:
                    state_in[target] = merged
                    work.append(target)

    def flow(self, routine: ir.Routine, start: frozenset[str], exits: dict[str, frozenset[str]],
             result: dict[int, frozenset[str]]) -> list[tuple[str, frozenset[str]]]:
        """One routine's data flow from `start`: records each operation's state in `result`; returns
        the entry states it gives the routines it calls or jumps to, and ("exit:" + its name) its end
        states."""
        if not routine.blocks:
            return []
        found: list[tuple[str, frozenset[str]]] = []
        by_label = {b.label: b for b in routine.blocks}
        first = routine.blocks[0].label
        state_in: dict[str, frozenset[str]] = {label: frozenset() for label in by_label}
        state_in[first] = start
        for label in by_label:
            if label in self.foreign_jumps:
                state_in[label] = self.anything
        reached: set[str] = set()
        work = [first] + [label for label in by_label if label in self.foreign_jumps]
        while work:
            self.visit(routine, by_label, state_in, reached, work, exits, result, found)
            # a block nothing here reaches (run by the host, EX <label>) may start with anything moving
            unreached = [b.label for b in routine.blocks if b.label not in reached]
            if unreached:
                state_in[unreached[0]] = self.anything
                work.append(unreached[0])
        return found


def successors(term) -> tuple[str, ...]:
    if isinstance(term, ir.Jump):
        return (term.target,)
    if isinstance(term, ir.Branch):
        return (term.then, term.otherwise)
    return ()


def in_own_steps(op: ir.SetMotion, module: ir.Module) -> bool:
    """A resolution that sets the steps per revolution the IR already counts in (an X150 `CUR4000`
    with the IR at 4000 steps/rev, parker-x150.md L731-L747): it names the unit of the source's
    positions, which the output converts to its own, so it is written as nothing."""
    return isinstance(op.value, ir.Const) and bool(module.steps_per_rev) and op.value.value == module.steps_per_rev


def chosen_microsteps(module: ir.Module, profile: Profile) -> int | None:
    """The MS code the output sets (lexium-mcode.txt L4282-L4340: microsteps per full step, one of
    the catalog's fixed codes, steps/rev = MS x full steps) when the profile's resolution would not
    convert a program of another dialect exactly and the program does not fix its own
    (backends/resolution.py). Codes below 10 are never chosen: with hMT on the drive takes none of
    them (L1480). None: the profile's resolution serves, or no code does better."""
    if module.dialect == DIALECT or not module.steps_per_rev or not profile.steps_per_rev \
            or not profile.get("cross.choose_resolution", True):
        return None
    if any(isinstance(op, ir.Setting) and op.name == "encoder_enable" for _, b in module.blocks() for op in b.ops):
        return None  # with the encoder on, MS is fixed at 256 (L7194, L7333): the profile's resolution
    full = int(profile.get("full_steps_per_rev", FULL_STEPS_PER_REV))
    entry = cat.for_profile(profile).lookup("MS")
    codes = [int(v) for v in (entry.values or ()) if int(v) >= 10] if entry is not None else []
    found = resolution.positions(module)
    if found.fixed and all(in_own_steps(op, module) for _, b in module.blocks() for op in b.ops
                           if isinstance(op, ir.SetMotion) and op.param is ir.MotionParam.RESOLUTION):
        found.fixed = False  # the source's resolution is the IR's step itself: it fixes nothing here
    chosen = resolution.choose(int(module.steps_per_rev), int(profile.steps_per_rev), [c * full for c in codes],
                               found)
    return chosen // full if chosen is not None else None


def emit(module: ir.Module, profile: Profile) -> Listing:
    microsteps = chosen_microsteps(module, profile)
    if microsteps is not None:  # the drive counts the steps the output sets with MS, before any program
        full = int(profile.get("full_steps_per_rev", FULL_STEPS_PER_REV))
        profile = dataclasses.replace(profile, steps_per_rev=microsteps * full)
    # an X150 program starts every move from standstill; VI has no 0: the output sets its lowest
    lowest = float(cat.load().lookup("VI").entry.range[0])
    lowest = lowest / float(units.ratio(module.steps_per_rev, profile.steps_per_rev))
    module = with_source_power_up(module, profile, lowest)  # the source's power-up speeds where ours differ
    module = with_fixed_initial_speed(module, lowest)
    module, refused = axis_sets_written(module, DIALECT, "MCode")  # an axis's own speeds as MCode applies them
    if refused is not None:
        return refused
    try:
        return Writer(module, profile, microsteps).run()
    except Unsupported as exc:  # a limit of the whole program (the name space), not of one line
        listing = Listing(DIALECT)
        span = next((op.span for _, b in module.blocks() for op in b.ops if op.span is not None),
                    Span(module.path or "-", 1, 1, 1, 1))
        listing.diagnostics.add("G003", span, f"this program cannot be written in MCode: {exc}")
        return listing
