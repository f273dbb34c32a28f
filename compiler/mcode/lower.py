"""Lowering an MCode syntax tree to the shared IR.

MCode programs are flat: `PG <address>` opens program memory, `LB` names places, `BR` jumps,
`CL`/`RT` call and return, `E` ends, `PG` closes. Lines outside PG … PG run immediately while the
file is downloaded. The lowering turns this into:

- one IMMEDIATE routine per stretch of lines outside a program (setup before, `S` after);
- for each program region, routines split at the labels that something calls: `CL` targets become
  SUBROUTINE routines, trip and `OE` targets HANDLER routines, `LB SU` the POWERUP routine and
  the region's first routine MAIN;
- inside a routine, a new basic block at every label and after every `BR`, `RT` and `E`.

Labels are module-unique block names (upper case, as MCode compares them case-insensitively);
blocks the source did not name get internal names starting with `%`, which no MCode name can
collide with. A `BR` to a label in another routine stays a cross-routine jump (the linter reports
it when it leaves a handler).
"""

from __future__ import annotations

from mcc.compiler import cancel, ir, ir_names, units
from mcc.compiler.diagnostics import Diagnostics
from mcc.compiler.mcode import catalog as cat
from mcc.compiler.mcode import syntax as st
from mcc.compiler.mcode.resolve import Resolved, Resolver
from mcc.compiler.mcode.tables import STAND_IN_VERSION, TABLES
from mcc.compiler import homing
from mcc.compiler.profiles import Profile

DIALECT = "mcode"
TRIP_EVENTS = {"TI": "input", "TP": "position", "TC": "capture", "TT": "time", "TR": "relative",
               "TA": "hmt", "TM": "power_loss"}
# A trip fires once and must be re-enabled ("only the activated trip function needs to be
# re-enabled", TE, L5667), and fires only while its TE bit is set (TE default 0, disabled, L5670).
HANDLER_FACTS = {"once": True, "gated": True}
HOME_METHODS = {"HM": "switch", "HI": "index", "HF": "offset"}
HOME_TYPES = {1: (-1, +1), 2: (-1, -1), 3: (+1, -1), 4: (+1, +1)}  # type -> (seek, creep) (L3206-L3210)
MOTION_PARAMS = {"accel": ir.MotionParam.ACCEL, "decel": ir.MotionParam.DECEL,
                 "initial_speed": ir.MotionParam.INITIAL_SPEED, "max_speed": ir.MotionParam.MAX_SPEED,
                 "resolution": ir.MotionParam.RESOLUTION}
# What a register read means in the IR (the catalog's `ir` kind -> an ir_names.STATUS meaning).
READINGS = {"set_position": "position", "counter": "position", "encoder": "encoder", "velocity": "velocity",
            "moving": "moving", "input": "input", "inputs": "inputs", "output": "output", "outputs": "outputs",
            "error_code": "error", "stalled": "stalled", "accel": "accel", "decel": "decel",
            "max_speed": "max_speed", "initial_speed": "initial_speed", "analog_input": "analog",
            "input_pending": "input_pending", "hmt_status": "hmt_status",
            "moving_to_position": "moving_to_position", "locked_rotor": "locked_rotor"}
# Settings with a neutral name (ir_names.SETTINGS): catalog `ir` kind -> (setting, factor to IR units).
SETTINGS = {"error_code": ("error_code", 1, ir.Unit.NONE), "run_current": ("run_current", 1, ir.Unit.PERCENT),
            "hold_current": ("hold_current", 1, ir.Unit.PERCENT),
            "settle_time": ("settle_time", 0.001, ir.Unit.S), "hold_delay": ("hold_delay", 0.001, ir.Unit.S),
            "input_debounce": ("input_debounce", 0.001, ir.Unit.S), "encoder_enable": ("encoder_enable", 1, ir.Unit.NONE),
            "trip_enable": ("handler_enable", 1, ir.Unit.NONE)}
# IS/OS type numbers (spec §6.6, L770-L831) -> ir_names.INPUT_FUNCTIONS / OUTPUT_FUNCTIONS.
INPUT_TYPES = {0: "general", 1: "home", 2: "limit_plus", 3: "limit_minus", 4: "run_program", 5: "soft_stop",
               6: "pause", 7: "jog_plus", 8: "jog_minus", 11: "reset", 12: "capture", 13: "step_direction",
               14: "encoder_ab", 15: "step_up_down"}
OUTPUT_TYPES = {16: "general", 17: "moving", 18: "error", 19: "stall", 20: "velocity_changing", 21: "locked_rotor",
                23: "moving_to_position", 24: "hmt_active", 25: "make_up_active", 26: "encoder_a", 27: "encoder_b",
                28: "trip", 29: "attention"}
FULL_STEPS_PER_REV = 200  # a 1.8° motor (L645); profiles may say otherwise (`full_steps_per_rev`)
MS_TO_S = 0.001
COMPARE_OPS = {"=": "=", "<>": "!=", "<": "<", "<=": "<=", "=<": "<=", ">": ">", ">=": ">="}
BINARY_OPS = {"+": "+", "-": "-", "*": "*", "/": "/", "&": "&", "|": "|", "^": "^"}
# LO: the section calls it "Logarithm Base 2" (L6618, L6627) and its example's comment "log (base
# 10)", but the value it prints for 51200 is 10.843495 = ln 51200 (L6636): mcc follows the printed
# value, the natural logarithm, unless the profile's `[mcode] lo_function` says "log2" or "log10"
# (docs/dialects/mcode.md).
LO_FUNCTIONS = ("log", "log2", "log10")
FUNCTIONS = {"AB": "abs", "CS": "cos", "C_": "acos", "LO": "log", "L_": "log10", "SI": "sin",
             "S_": "asin", "SQ": "sqrt", "TG": "tan", "T_": "atan"}
TRIG = frozenset({"sin", "cos", "tan", "asin", "acos", "atan"})
# PI "holds the value of PI" as the section's title writes it, 3.141592654 (L6658-L6676): 51200*PI
# prints 160849.543885, where math.pi would give 160849.543864.
PI = 3.141592654
# The line tables PR reports (tables.TABLES): the neutral settings of a line's two parameters, and
# how the first prints (an IS/OS type number from the function's name; the number itself for LS).
TABLE_SETTINGS = {"OS": ("output_function", "output_active_high"), "LS": ("soft_limit_position", "soft_limit_enable")}
# How PR MD prints the last move's kind (L4145-L4153).
LAST_MOVE_TEXTS = {"absolute": "MA", "relative": "MR", "slew": "SL"}


def first_arg_name(res: Resolved) -> str:
    """The label/variable a statement names first (LB K1, CL K1, VA Q1=0)."""
    if not res.args:
        return ""
    arg = res.args[0]
    if isinstance(arg, st.Comparison):
        arg = arg.left
    if isinstance(arg, st.Name):
        return arg.key
    if isinstance(arg, st.Number) and isinstance(arg.value, int):
        return str(arg.value)
    return ""


def handler_label(res: Resolved) -> st.Node | None:
    """The label argument of a trip or OE definition (TP=51200,Kb / TA=4,k6 / OE K1)."""
    name = res.command.name
    args = res.args
    if name in ("OE", "TC", "TM"):
        return args[0] if args else None
    if name in ("TI", "TP", "TT", "TR"):
        return args[1] if len(args) > 1 else None
    if name == "TA":  # the manual's syntax and example disagree on the order (spec §8 #14)
        for arg in args[:2]:
            if isinstance(arg, st.Name):
                return arg
        return args[0] if args else None
    return None


class Lowering:
    def __init__(self, tree: st.SyntaxTree, profile: Profile, diags: Diagnostics):
        self.tree = tree
        self.profile = profile
        self.diags = diags
        self.resolver = Resolver(profile, diags)
        self.cat = self.resolver.cat
        self.module = ir.Module(DIALECT, profile.name, path=tree.path, steps_per_rev=profile.steps_per_rev)
        self.full_steps = int(profile.get("full_steps_per_rev", FULL_STEPS_PER_REV))
        self.resolution_set = False
        self.resolved: list[tuple[st.Line, Resolved, bool]] = []  # (line, meaning, in_program)
        self.callees: set[str] = set()
        self.handlers: set[str] = set()
        self.label_refs: list[tuple[str, st.Node, str]] = []  # (label, node, command)
        self.routine: ir.Routine | None = None
        self.block: ir.Block | None = None
        self.generated = 0
        self.region_origin: int | None = None
        self.region_routines: list[ir.Routine] = []
        self.region_span = None

    # pass 1: meanings, names, label references -----------------------------------------------
    def collect(self) -> None:
        in_program = False
        names = self.resolver.names
        for index, line in enumerate(self.tree.lines):
            cancel.every(index)  # the editor server abandons a stale analysis here
            stmt = line.statement
            if stmt is None:
                continue
            res = self.resolver.resolve(stmt)
            self.resolved.append((line, res, in_program))
            command = res.command
            if command is None:
                continue
            name = command.name
            if name == "PG":
                in_program = bool(res.args)
            elif name == "LB":
                label = first_arg_name(res)
                if label and isinstance(res.args[0], st.Name):
                    if label in names.labels:
                        first = names.labels[label]
                        self.diags.add("M105", res.args[0].span,
                                       f"label {res.args[0].text} is already defined at line {first.span.line}; "
                                       "each label names one place (rename one of them)")
                    else:
                        names.labels[label] = res.args[0]
            elif name == "VA":
                var = first_arg_name(res)
                arg = res.args[0] if res.args else None
                target = arg.left if isinstance(arg, st.Comparison) else arg
                if var and isinstance(target, st.Name) and var not in names.variables:
                    names.variables[var] = target
                elif var and isinstance(target, st.Name) and names.variables.get(var) is not target:
                    first = names.variables[var]
                    self.diags.add("M141", target.span,
                                   f"VA {target.text} again: {first.text} is already declared at line "
                                   f"{first.span.line}, and the device refuses to redefine a user variable "
                                   f"(Error 28, L8472): set it with `{target.text}=value` instead")
            ir_kind = command.ir
            if ir_kind in ("call", "branch", "execute") or name in ("BP", "L", "CP"):
                target = res.args[0] if res.args else None
                if name == "CP" and len(res.args) > 1:
                    target = res.args[1]
                if isinstance(target, st.Name) or isinstance(target, st.Number) and isinstance(target.value, int):
                    self.label_refs.append((first_node_key(target), target, name))
                    if ir_kind == "call" and isinstance(target, st.Name):
                        self.callees.add(target.key)
            elif ir_kind in ("trip", "on_error") or name in TRIP_EVENTS or name == "OE":
                target = handler_label(res)
                if isinstance(target, (st.Name, st.Number)):
                    self.label_refs.append((first_node_key(target), target, name))
                    if isinstance(target, st.Name):
                        self.handlers.add(target.key)

    # pass 2: the IR ------------------------------------------------------------------------------
    def run(self) -> ir.Module:
        self.collect()
        for index, (line, res, in_program) in enumerate(self.resolved):
            cancel.every(index)
            ok = self.resolver.check(res, in_program)
            try_lower = ok or res.command is not None and res.command.name in ("PG", "LB")
            if not try_lower:
                continue
            self.lower_statement(res, in_program)
        if self.region_origin is not None or self.region_routines:
            span = self.routine.span if self.routine and self.routine.span else None
            if span is not None:
                self.diags.add("M128", span, "the program is not closed: add `PG` after its last line to leave "
                                             "program mode")
            self.close_region()
        self.finish()
        return self.module

    def lower_statement(self, res: Resolved, in_program: bool) -> None:
        command = res.command
        name = command.name if command else ""
        if name == "PG":
            if res.args:
                if self.region_origin is not None or self.region_routines:
                    self.close_region()
                origin = first_arg_name(res)
                self.region_origin = int(origin) if origin.isdigit() else 0
                self.region_span = res.stmt.span
                self.region_routines = []
                self.routine = None
                self.block = None  # the immediate lines before PG do not flow into the program
            elif self.region_origin is None and not self.region_routines:
                self.diags.add("M128", res.stmt.span, "`PG` without an address closes program mode, but no program "
                                                      "is open here")
            else:
                self.close_region()
            return
        if not in_program:
            self.immediate_op(res)
            return
        if name == "LB":
            label = first_arg_name(res)
            if label:
                self.start_label(label, res.stmt.span)
            return
        self.ensure_block(res.stmt.span)
        if name == "BR":
            self.branch(res)
        elif name == "RT":
            self.terminate(ir.Return(res.stmt.span))
        elif name == "E":
            self.terminate(ir.End(res.stmt.span))
        else:
            self.append(self.op(res, in_program))

    # regions, routines, blocks -------------------------------------------------------------------
    def close_region(self) -> None:
        if self.block is not None and self.block.terminator is None:
            self.block.terminator = ir.FallOff(self.block.span)
        self.region_origin = None
        self.region_routines = []
        self.routine = None
        self.block = None

    def routine_kind(self, label: str) -> ir.RoutineKind:
        if label == "SU":
            return ir.RoutineKind.POWERUP
        if label in self.handlers:
            return ir.RoutineKind.HANDLER
        if label in self.callees:
            return ir.RoutineKind.SUBROUTINE
        return ir.RoutineKind.MAIN

    def new_routine(self, name: str, kind: ir.RoutineKind, span) -> ir.Routine:
        routine = ir.Routine(name, kind, span=span)
        if not self.region_routines:
            routine.origin = self.region_origin if self.region_origin is not None else 0
            routine.span = self.region_span or span  # the PG line opens the region
        self.region_routines.append(routine)
        self.module.routines.append(routine)
        self.routine = routine
        return routine

    def start_label(self, label: str, span) -> None:
        starts_routine = self.routine is None or (
            label in self.callees or label in self.handlers or label == "SU") and self.routine_has_code()
        block = ir.Block(label, span=span, named=True)
        if self.block is not None and self.block.terminator is None:
            if not self.block.ops and not self.block.named and self.routine and self.routine.blocks \
                    and self.routine.blocks[-1] is self.block and self.block is not self.routine.entry:
                self.routine.blocks.pop()  # an empty unnamed block: nothing to keep
                self.retarget(self.block.label, label)
            else:
                self.block.terminator = ir.Jump(label, span)
        if starts_routine:
            if self.routine is not None and self.routine.entry is self.block and not self.block.ops \
                    and not self.block.named:
                # The region started with an unnamed empty block: the label is the real start.
                self.routine.blocks.clear()
                self.routine.name = label
                self.routine.kind = self.routine_kind(label)
            else:
                self.new_routine(label, self.routine_kind(label), span)
        self.routine.blocks.append(block)
        self.block = block

    def routine_has_code(self) -> bool:
        return any(b.ops or b.terminator is not None or b.named for b in self.routine.blocks)

    def retarget(self, old: str, new: str) -> None:
        """Point the jumps to the dropped block `old` at `new`. Only generated blocks are dropped, and
        only `branch` targets one: the block just before it (scanning the module made each label
        cost the whole program, so long programs checked in quadratic time)."""
        if old.startswith("%") and self.routine is not None and self.routine.blocks:
            ir.retarget(self.routine.blocks[-1].terminator, old, new)
            return
        for _, block in self.module.blocks():
            ir.retarget(block.terminator, old, new)

    def fresh_label(self) -> str:
        self.generated += 1
        return f"%{self.generated}"

    def ensure_block(self, span) -> None:
        if self.routine is None:
            origin = self.region_origin if self.region_origin is not None else 0
            self.new_routine(f"@{origin}", ir.RoutineKind.MAIN, span)
        current = self.routine.blocks[-1] if self.routine.blocks else None
        if self.block is None or self.block.terminator is not None or self.block is not current:
            block = ir.Block(self.fresh_label(), span=span)
            self.routine.blocks.append(block)
            self.block = block

    def terminate(self, term) -> None:
        self.block.terminator = term

    def branch(self, res: Resolved) -> None:
        target = self.target_label(res.args[0]) if res.args else "%?"
        span = res.stmt.span
        if len(res.args) > 1:
            after = self.fresh_label()
            self.terminate(ir.Branch(self.cond(res.args[1]), target, after, span))
            block = ir.Block(after, span=span)
            self.routine.blocks.append(block)
            self.block = block
        else:
            self.terminate(ir.Jump(target, span))

    def target_label(self, node: st.Node) -> str:
        if isinstance(node, st.Name):
            return node.key
        if isinstance(node, st.Number):
            for origin, routines in [(r.origin, r) for r in self.module.routines if r.origin is not None]:
                if origin == node.value and routines.entry is not None:
                    return routines.entry.label
            return f"@{node.text}"
        return "%?"

    def finish(self) -> None:
        """Drop empty unnamed blocks nothing reaches and give dangling blocks an explicit end."""
        referenced = set()
        for _, block in self.module.blocks():
            referenced.update(ir.successors(block.terminator))
        for routine in self.module.routines:
            kept = []
            for i, block in enumerate(routine.blocks):
                empty = not block.ops and not block.named and block.label not in referenced
                if empty and i > 0 and isinstance(block.terminator, (ir.FallOff, type(None))):
                    continue
                if block.terminator is None:
                    block.terminator = ir.FallOff(block.span)
                kept.append(block)
            routine.blocks[:] = kept

    # immediate lines -----------------------------------------------------------------------------
    def immediate_op(self, res: Resolved) -> None:
        if self.routine is None or self.routine.kind is not ir.RoutineKind.IMMEDIATE:
            count = sum(1 for r in self.module.routines if r.kind is ir.RoutineKind.IMMEDIATE)
            name = "immediate" if count == 0 else f"immediate.{count + 1}"
            routine = ir.Routine(name, ir.RoutineKind.IMMEDIATE, [ir.Block(f"%imm{count + 1}", span=res.stmt.span)],
                                 span=res.stmt.span)
            self.module.routines.append(routine)
            self.routine = routine
            self.block = routine.blocks[0]
        self.append(self.op(res, in_program=False))

    # operations ----------------------------------------------------------------------------------
    def append(self, op) -> None:
        """Add the operation(s) of one statement (a few statements lower to two operations)."""
        if isinstance(op, list):
            self.block.ops.extend(op)
        elif op is not None:
            self.block.ops.append(op)

    def axis(self, res: Resolved) -> str:
        """The statement's axis: its party prefix, or the drive itself (the profile's axis)."""
        if res.party:
            return res.party
        return self.profile.axes[0] if self.profile.axes else "1"

    def op(self, res: Resolved, in_program: bool):
        op = self.neutral_op(res, in_program)
        native_read = op is not None and not isinstance(op, (list, ir.Native)) and reads_register(op)
        if (native_read or res.party and op is not None and not isinstance(op, (list, ir.Move))
                and not hasattr(op, "axis")) and res.command is not None:
            # A party prefix addresses the statement to one device; an operation without an axis
            # would lose it, so the statement stays native with the prefix as its axis.
            return ir.Native(DIALECT, res.command.name, tuple(self.native_arg(res.command, a) for a in res.args),
                             form="=" if res.stmt.form == "assign" else (" " if res.args else ""),
                             axis=res.party, span=res.stmt.span)
        return op

    def neutral_op(self, res: Resolved, in_program: bool):
        stmt = res.stmt
        span = stmt.span
        if stmt.form == "number":
            return ir.Native(DIALECT, "", (self.expr(res.args[0]),), form="number", span=span)
        if res.command is None:  # a user variable assignment
            return ir.Assign(ir.Var(res.user, stmt.head.span), self.expr(res.args[0]), span)
        command = res.command
        name, kind = command.name, command.ir
        args = res.args
        axis = self.axis(res)
        if kind == "resolution" and args:
            return self.resolution(axis, args[0], span)
        if kind in MOTION_PARAMS and args:
            param = MOTION_PARAMS[kind]
            return ir.SetMotion(param, axis, self.expr(args[0], ir.PARAM_UNITS[param]), span)
        if command.entry.get("setting") and args:
            return self.register_setting(command, args, axis, span)
        if kind in SETTINGS and args:
            setting, factor, unit = SETTINGS[kind]
            return ir.Setting(setting, axis, units.to_ir(self.expr(args[0]), factor, unit), span, command.index)
        if kind == "io_setup" and len(args) in (2, 3):  # MDrivePlus S1-S4 (mcode-families.toml)
            point_setup = self.point_setup(command.index, axis, args, span)
            if point_setup is not None:
                return point_setup
        if name in ("IS", "OS", "LS") and len(args) == 3 or name == "OS" and len(args) == 2:
            line_setup = self.line_setup(name, axis, args, span)
            if line_setup is not None:
                return line_setup
        if kind in ("move_absolute", "move_relative") and args:
            mode = ir.MoveMode.ABSOLUTE if kind == "move_absolute" else ir.MoveMode.RELATIVE
            options = tuple((key, self.expr(arg)) for key, arg in zip(("notify", "continuous"), args[1:]))
            return ir.Move(mode, ((axis, self.expr(args[0], ir.Unit.STEPS)),), options, span)
        if kind == "slew" and args:
            velocity = self.expr(args[0], ir.Unit.STEPS_PER_S)
            if isinstance(velocity, ir.Const) and velocity.value == 0:
                return ir.Stop(axis, True, span)  # SL 0: decelerate to a stop, as every dialect's ramped stop
            return ir.Slew(axis, velocity, span=span)
        if name in HOME_METHODS and args:
            kind_of = self.expr(args[0])
            if isinstance(kind_of, ir.Const) and kind_of.value in HOME_TYPES:
                seek, creep = HOME_TYPES[kind_of.value]
                return homing.home_op(self.profile, self.module.steps_per_rev, axis, HOME_METHODS[name], seek, span,
                                      written_creep=creep)
        if kind == "hold" or name == "H":
            if args:
                return ir.Delay(units.to_ir(self.expr(args[0]), MS_TO_S, ir.Unit.S), span)
            return ir.WaitMotion(axis, span)
        if name == "PS" and not args:  # pauses with the normal decel ramp; RS resumes the move (L4931-L4959)
            return ir.Pause(axis, True, span)
        if name == "RS" and not args:
            return ir.Resume(axis, span)
        if kind == "set_position" and args:
            return ir.SetPosition(axis, self.expr(args[0], ir.Unit.STEPS), span)
        if kind == "output" and args and command.index is not None:
            return ir.SetOutput(command.index, self.expr(args[0]), span)
        if kind == "outputs" and args:
            return ir.SetOutput(None, self.expr(args[0]), span)
        if kind == "drive_enable" and args:
            return ir.DriveEnable(axis, self.expr(args[0]), span)
        if kind == "print" and len(args) == 1 and isinstance(args[0], st.Name) and stmt.suffix != ";":
            listing = self.listing(args[0].key, axis, span)
            if listing is not None:
                return listing
        if kind == "print":
            items = []
            for arg in args:  # a text and the item glued to it (comma missing) are two items
                items += [self.item(arg.first), self.item(arg.second)] if isinstance(arg, st.Juxtaposed) \
                    else [self.item(arg)]
            return ir.Print(tuple(items), newline=stmt.suffix != ";", span=span, axis=res.party)
        if kind == "call" and args:
            cond = self.cond(args[1]) if len(args) > 1 else None
            return ir.Call(self.target_label(args[0]), cond, span)
        if kind == "register" and args:
            self.declare_register(command)
            return ir.Assign(ir.Var(name, stmt.head.span), self.expr(args[0]), span)
        if kind in ("increment", "decrement") and args:
            var = self.expr(args[0])
            if isinstance(var, ir.Var):
                op = "+" if kind == "increment" else "-"
                return ir.Assign(var, ir.BinOp(op, var, ir.Const(1)), span)
        if kind == "declare":
            return self.declare(res, in_program)
        if kind == "save" or name == "S":
            return ir.Save(span)
        if kind == "on_error" or name == "OE":
            # OE runs "when an error code ER is asserted" (L4538): every time, with no TE bit (not `once`)
            return ir.SetHandler("error", self.target_label(args[0]) if args else None, (), span)
        if name in TRIP_EVENTS:
            label_node = handler_label(res)
            others = tuple(self.trip_arg(name, i, a) for i, a in enumerate(a for a in args if a is not label_node))
            label = self.target_label(label_node) if label_node is not None else None
            return ir.SetHandler(TRIP_EVENTS[name], label, others, span, **HANDLER_FACTS)
        return ir.Native(DIALECT, name, tuple(self.native_arg(command, a) for a in args),
                         form="=" if stmt.form == "assign" else (" " if args else ""), axis=axis, span=span)

    def register_setting(self, command: cat.Command, args, axis: str, span):
        """`CW=100`, `SA=0.9`, `PF=8,4,1,1`: a drive register the catalog names a neutral setting
        (its `setting` key); the simulator keeps the value and reads it back (docs/SIMULATOR.md,
        "Drive registers"). A text setting (PF's four numbers) needs literal numbers."""
        name = command.entry.get("setting")
        info = ir_names.SETTINGS[name]
        self.declare_device_value(command)
        if info.value_type == "text":
            values = [self.expr(a) for a in args]
            if not all(isinstance(v, ir.Const) for v in values):
                return self.native(command, args, span, axis)
            text = ",".join(format(v.value) for v in values)
            return ir.Setting(name, axis, ir.Text(text, span), span)
        factor = MS_TO_S if info.unit is ir.Unit.S else 1
        return ir.Setting(name, axis, units.to_ir(self.expr(args[0]), factor, info.unit), span)

    def declare_device_value(self, command: cat.Command) -> None:
        """The value the register reads before the program sets it: the catalog's factory default
        (each entry's manual lines), in the IR's units; the identity from the profile's [device]."""
        name = command.entry.get("setting") or command.entry.get("reading") or SETTINGS.get(command.ir, ("",))[0]
        if not name or name in self.module.device_values:
            return
        if name == "part_number":  # none known: the device prints 0 (docs/PROFILES.md)
            value = self.profile.get("device.part_number") or 0
        elif name == "firmware_version":
            value = self.profile.get("device.version") or STAND_IN_VERSION
        else:
            value = command.entry.default
            info = ir_names.SETTINGS.get(name)
            if info is not None and info.unit is ir.Unit.S and isinstance(value, (int, float)):
                value = value * MS_TO_S
            if name == "last_move":
                self.module.print_texts[name] = dict(LAST_MOVE_TEXTS)
        if value is not None:
            self.module.device_values[name] = value

    def native(self, command: cat.Command, args, span, axis: str):
        return ir.Native(DIALECT, command.name, tuple(self.native_arg(command, a) for a in args), form="=",
                         axis=axis, span=span)

    def listing(self, name: str, axis: str, span) -> list[ir.Print] | None:
        """`PR OS`, `PR LS`, `PR UV`: one print per line of the table, as the drive answers it
        (L4647-L4650, L4044, L5972): each line reads the line's settings in force (their factory
        values declared on the module); UV lists the user variables declared before it, `name = G|L
        value` (G global, declared outside a program; L local)."""
        if name == "UV":
            return [ir.Print((ir.Text(f"{v.name} = {'G' if v.scope == 'global' else 'L'} ", span), ir.Var(v.name, span)),
                             span=span) for v in self.module.variables.values()]
        if name not in TABLE_SETTINGS:
            return None
        lines, form = TABLES[name]
        first, second = TABLE_SETTINGS[name]
        factory = next(iter(lines.values()))
        if name == "OS":
            self.module.print_texts[first] = {function: str(number) for number, function in OUTPUT_TYPES.items()}
            self.module.device_values.setdefault(first, OUTPUT_TYPES[factory[0]])
        else:
            self.module.device_values.setdefault(first, factory[0])
        self.module.device_values.setdefault(second, factory[1])
        prints = []
        for n in lines:
            head, _, rest = form.replace("{n}", str(n)).partition("{0}")
            middle, _, tail = rest.partition("{1}")
            items = (ir.Text(head, span), ir.Status(first, axis, n, span), ir.Text(middle, span),
                     ir.Status(second, axis, n, span)) + ((ir.Text(tail, span),) if tail else ())
            prints.append(ir.Print(items, span=span))
        return prints

    def line_setup(self, name: str, axis: str, args, span):
        """`IS=1,1,0` / `OS=1,17,1` with literal numbers: an input's or output's function and its
        active level, as two neutral settings (returned as one list the caller flattens)."""
        values = [self.expr(a) for a in args]
        if not all(isinstance(v, ir.Const) for v in values):
            return None
        if name == "LS":  # LS=<0/1>,<position>,<0/1>: a software limit (L4023-L4044)
            if len(values) != 3 or values[0].value not in (0, 1) or values[2].value not in (0, 1):
                return None
            limit = values[0].value
            return [ir.Setting("soft_limit_position", axis, self.expr(args[1], ir.Unit.STEPS), span, limit),
                    ir.Setting("soft_limit_enable", axis, values[2], span, limit)]
        line, kind_of = values[0].value, values[1].value
        active = values[2].value if len(values) == 3 else None  # OS=3,29 keeps the active level (L4646)
        table = INPUT_TYPES if name == "IS" else OUTPUT_TYPES
        if kind_of not in table or not isinstance(line, int) or line not in range(1, 5) or active not in (0, 1, None):
            return None
        what = "input" if name == "IS" else "output"
        function = ir.Setting(f"{what}_function", axis, ir.Text(table[kind_of], args[1].span), span, line)
        if active is None:
            return [function]
        return [function, ir.Setting(f"{what}_active_high", axis, ir.Const(active), span, line)]

    def point_setup(self, point: int | None, axis: str, args, span):
        """`S1=1,0,0` (MDrivePlus) with literal numbers: I/O point 1 becomes an input or an output by
        its function (inputs 0-11, outputs 16-20), with its active level, and sinking (0) or
        sourcing (1): the same neutral settings as Lexium's IS/OS, plus `io_sourcing`."""
        values = [self.expr(a) for a in args]
        if point is None or not all(isinstance(v, ir.Const) for v in values):
            return None
        function, active = values[0].value, values[1].value
        what, table = ("input", INPUT_TYPES) if function in INPUT_TYPES else ("output", OUTPUT_TYPES)
        if function not in table or active not in (0, 1):
            return None
        out = [ir.Setting(f"{what}_function", axis, ir.Text(table[function], args[0].span), span, point),
               ir.Setting(f"{what}_active_high", axis, ir.Const(active), span, point)]
        if len(values) == 3:
            out.append(ir.Setting("io_sourcing", axis, values[2], span, point))
        return out

    def resolution(self, axis: str, node: st.Node, span):
        """`MS=256`: microsteps per full step. The IR counts steps per revolution, and a literal
        resolution set before any program decides the size of the module's step."""
        value = self.expr(node)
        if isinstance(value, ir.Const):
            steps = value.value * self.full_steps
            if not self.resolution_set and not any(r.kind is not ir.RoutineKind.IMMEDIATE
                                                   for r in self.module.routines):
                self.module.steps_per_rev = steps
                self.resolution_set = True
            return ir.SetMotion(ir.MotionParam.RESOLUTION, axis, ir.Const(steps, ir.Unit.NONE, value.span), span)
        return ir.SetMotion(ir.MotionParam.RESOLUTION, axis,
                            ir.BinOp("*", value, ir.Const(self.full_steps)), span)

    def trip_arg(self, name: str, index: int, node: st.Node):
        """A trip's parameters in IR units: TP/TR positions in steps, TT a time in seconds."""
        value = self.expr(node)
        if index == 0 and name in ("TP", "TR"):
            return self.expr(node, ir.Unit.STEPS)
        if index == 0 and name == "TT":
            return units.to_ir(value, MS_TO_S, ir.Unit.S)
        return value

    def declare(self, res: Resolved, in_program: bool):
        arg = res.args[0] if res.args else None
        target = arg.left if isinstance(arg, st.Comparison) else arg
        if not isinstance(target, st.Name):
            return None
        init = self.expr(arg.right) if isinstance(arg, st.Comparison) else None
        name = target.key
        scope = "local" if in_program else "global"
        if name not in self.module.variables:
            self.module.variables[name] = ir.Variable(name, ir.VarType.INT32, init, scope, res.stmt.span)
        if in_program:
            args = (ir.Var(name, target.span),) + ((init,) if init is not None else ())
            return ir.Native(DIALECT, "VA", args, form=" ", span=res.stmt.span)
        return None

    def declare_register(self, command: cat.Command) -> None:
        """Record a device register's type in the module: the catalog's default value says it, a
        float for the floating-point registers F1-F8 (double precision, L2802-L2811), an integer for
        R1-R4. Expressions assigned to a float64 register compute in floating point (L1249)."""
        if command.name not in self.module.registers:
            floating = isinstance(command.entry.default, float)
            self.module.registers[command.name] = ir.VarType.FLOAT64 if floating else ir.VarType.INT32

    # expressions ---------------------------------------------------------------------------------
    def native_arg(self, command: cat.Command, node: st.Node):
        if isinstance(node, st.Name) and node.key in self.resolver.names.labels \
                and node.key not in self.resolver.names.variables:
            return ir.LabelRef(node.key, node.span)
        if isinstance(node, st.Comparison):
            return self.cond(node)
        return self.item(node)

    def item(self, node: st.Node):
        if isinstance(node, st.String):
            return ir.Text(node.text, node.span)
        if isinstance(node, st.Juxtaposed):
            return self.item(node.first)  # the lost comma was reported; PR keeps both items below
        return self.expr(node)

    def expr(self, node: st.Node, unit: ir.Unit = ir.Unit.NONE):
        if isinstance(node, st.Number):
            return ir.Const(node.value, unit, node.span)
        if isinstance(node, st.Name):
            upper = node.key
            if upper in self.resolver.names.variables:
                return ir.Var(upper, node.span)
            command = self.cat.commands.get(upper)
            if command is not None and command.ir == "register":
                self.declare_register(command)
                return ir.Var(upper, node.span)
            if upper == "PI":
                return ir.Const(PI, unit, node.span)
            if upper in self.resolver.names.labels:
                return ir.LabelRef(upper, node.span)
            meaning = command.ir if command is not None else ""
            index = command.index if command is not None else None
            read_back = self.read_back(command, node) if command is not None else None
            if read_back is not None:
                return read_back
            if meaning in READINGS:
                reading = READINGS[meaning]
                indexed = reading in ("input", "output", "analog")
                if reading == "analog":
                    index = 1  # I5, the one analog input
                return ir.Status(reading, "" if indexed else self.drive_axis(), index if indexed else None,
                                 node.span)
            return ir.DeviceRef(DIALECT, upper, meaning, "", index, node.span)
        if isinstance(node, st.Unary):
            operand = self.expr(node.operand)
            if node.op == "-" and isinstance(operand, ir.Const):
                return ir.Const(-operand.value, unit, node.span)
            return ir.UnOp("-" if node.op == "-" else "~", operand, node.span)
        if isinstance(node, st.Binary):
            return ir.BinOp(BINARY_OPS.get(node.op, node.op), self.expr(node.left), self.expr(node.right), node.span)
        if isinstance(node, st.FuncCall):
            name = FUNCTIONS.get(node.name, node.name.lower())
            if node.name == "LO":
                chosen = self.profile.get("mcode.lo_function", "log")
                name = chosen if chosen in LO_FUNCTIONS else "log"
            if name in TRIG and "RA" in self.cat.commands:  # angles in the unit RA gives (default radians, L5107)
                self.declare_device_value(self.cat.commands["RA"])
            return ir.Func(name, (self.expr(node.operand),), node.span)
        if isinstance(node, st.String):
            return ir.Text(node.text, node.span)
        if isinstance(node, st.Juxtaposed):
            return self.item(node.first)
        if isinstance(node, st.Comparison):
            return self.cond(node)
        raise TypeError(f"unexpected node {type(node).__name__}")

    def read_back(self, command: cat.Command, node: st.Name):
        """A read of a drive register that is a neutral setting or reading (the catalog's `setting`,
        `reading` or a setting `ir` kind): the value in force, in the register's own units."""
        setting = command.entry.get("setting")
        reading = command.entry.get("reading")
        if command.ir == "resolution":  # MS: microsteps per full step, the steps per revolution in force / 200
            return ir.BinOp("/", ir.Status("resolution", self.drive_axis(), None, node.span),
                            ir.Const(self.full_steps), node.span)
        if not setting and not reading and command.ir in SETTINGS and command.ir not in READINGS:
            setting, factor, _unit = SETTINGS[command.ir]
        elif setting:
            factor = MS_TO_S if ir_names.SETTINGS[setting].unit is ir.Unit.S else 1
        elif reading:
            factor = 1
        else:
            return None
        self.declare_device_value(command)
        indexed = command.index is not None and setting == "input_debounce"
        status = ir.Status(setting or reading, self.drive_axis(), command.index if indexed else None, node.span)
        return units.from_ir(status, factor) if factor != 1 else status

    def drive_axis(self) -> str:
        return self.profile.axes[0] if self.profile.axes else "1"

    def cond(self, node: st.Node):
        if isinstance(node, st.Comparison):
            return units.typed_compare(ir.Compare(COMPARE_OPS.get(node.op, node.op), self.expr(node.left),
                                                  self.expr(node.right), node.span))
        return ir.Truth(self.expr(node), node.span)


def reads_register(op) -> bool:
    """Whether an operation reads a register with no neutral meaning (kept in MCode's spelling):
    then the whole statement stays Native, so the dialect's spelling never leaks into the IR."""
    return any(isinstance(node, ir.DeviceRef) for expr in ir.op_exprs(op) for node in ir.walk_expr(expr))


def first_node_key(node: st.Node) -> str:
    if isinstance(node, st.Name):
        return node.key
    return str(node.value) if isinstance(node, st.Number) else ""
