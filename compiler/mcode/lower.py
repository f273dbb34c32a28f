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

from mcc.compiler import ir
from mcc.compiler.diagnostics import Diagnostics
from mcc.compiler.mcode import catalog as cat
from mcc.compiler.mcode import syntax as st
from mcc.compiler.mcode.resolve import Resolved, Resolver
from mcc.compiler.profiles import Profile

DIALECT = "mcode"
TRIP_EVENTS = {"TI": "input", "TP": "position", "TC": "capture", "TT": "time", "TR": "relative",
               "TA": "hmt", "TM": "power"}
HOME_METHODS = {"HM": "switch", "HI": "index", "HF": "offset"}
MOTION_PARAMS = {"accel": ir.MotionParam.ACCEL, "decel": ir.MotionParam.DECEL,
                 "initial_speed": ir.MotionParam.INITIAL_SPEED, "max_speed": ir.MotionParam.MAX_SPEED,
                 "resolution": ir.MotionParam.RESOLUTION}
COMPARE_OPS = {"=": "=", "<>": "!=", "<": "<", "<=": "<=", "=<": "<=", ">": ">", ">=": ">="}
BINARY_OPS = {"+": "+", "-": "-", "*": "*", "/": "/", "&": "&", "|": "|", "^": "^"}
FUNCTIONS = {"AB": "abs", "CS": "cos", "C_": "acos", "LO": "ln", "L_": "log10", "SI": "sin",
             "S_": "asin", "SQ": "sqrt", "TG": "tan", "T_": "atan"}


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
        self.module = ir.Module(DIALECT, profile.name, path=tree.path)
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
        for line in self.tree.lines:
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
        for line, res, in_program in self.resolved:
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
            op = self.op(res, in_program)
            if op is not None:
                self.block.ops.append(op)

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
        op = self.op(res, in_program=False)
        if op is not None:
            self.block.ops.append(op)

    # operations ----------------------------------------------------------------------------------
    def axis(self, res: Resolved) -> str:
        return res.party

    def op(self, res: Resolved, in_program: bool):
        op = self.neutral_op(res, in_program)
        if res.party and op is not None and not hasattr(op, "axis") and res.command is not None:
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
        if kind in MOTION_PARAMS and args:
            return ir.SetMotion(MOTION_PARAMS[kind], axis, self.expr(args[0]), span)
        if kind in ("move_absolute", "move_relative") and args:
            mode = ir.MoveMode.ABSOLUTE if kind == "move_absolute" else ir.MoveMode.RELATIVE
            options = tuple((key, self.expr(arg)) for key, arg in zip(("notify", "continuous"), args[1:]))
            return ir.Move(mode, ((axis, self.expr(args[0])),), options, span)
        if kind == "slew" and args:
            return ir.Slew(axis, self.expr(args[0]), span=span)
        if name in HOME_METHODS and args:
            return ir.Home(axis, HOME_METHODS[name], mode=self.expr(args[0]), span=span)
        if kind == "hold" or name == "H":
            if args:
                return ir.Delay(self.expr(args[0], ir.Unit.MS), span)
            return ir.WaitMotion(axis, span)
        if kind == "set_position" and args:
            return ir.SetPosition(axis, self.expr(args[0]), span)
        if kind == "output" and args and command.index is not None:
            return ir.SetOutput(command.index, self.expr(args[0]), span)
        if kind == "outputs" and args:
            return ir.SetOutput(None, self.expr(args[0]), span)
        if kind == "drive_enable" and args:
            return ir.DriveEnable(axis, self.expr(args[0]), span)
        if kind == "print":
            items = []
            for arg in args:  # a text and the item glued to it (comma missing) are two items
                items += [self.item(arg.first), self.item(arg.second)] if isinstance(arg, st.Juxtaposed) \
                    else [self.item(arg)]
            return ir.Print(tuple(items), newline=stmt.suffix != ";", span=span)
        if kind == "call" and args:
            cond = self.cond(args[1]) if len(args) > 1 else None
            return ir.Call(self.target_label(args[0]), cond, span)
        if kind == "register" and args:
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
            return ir.SetHandler("error", self.target_label(args[0]) if args else None, (), span)
        if name in TRIP_EVENTS:
            label_node = handler_label(res)
            others = tuple(self.expr(a) for a in args if a is not label_node)
            label = self.target_label(label_node) if label_node is not None else None
            return ir.SetHandler(TRIP_EVENTS[name], label, others, span)
        return ir.Native(DIALECT, name, tuple(self.native_arg(command, a) for a in args),
                         form="=" if stmt.form == "assign" else (" " if args else ""), axis=axis, span=span)

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
                return ir.Var(upper, node.span)
            if upper == "PI":
                return ir.Func("pi", (), node.span)
            if upper in self.resolver.names.labels:
                return ir.LabelRef(upper, node.span)
            meaning = command.ir if command is not None else ""
            index = command.index if command is not None else None
            return ir.DeviceRef(DIALECT, upper, meaning, "", index, node.span)
        if isinstance(node, st.Unary):
            operand = self.expr(node.operand)
            if node.op == "-" and isinstance(operand, ir.Const):
                return ir.Const(-operand.value, unit, node.span)
            return ir.UnOp("-" if node.op == "-" else "~", operand, node.span)
        if isinstance(node, st.Binary):
            return ir.BinOp(BINARY_OPS.get(node.op, node.op), self.expr(node.left), self.expr(node.right), node.span)
        if isinstance(node, st.FuncCall):
            return ir.Func(FUNCTIONS.get(node.name, node.name.lower()), (self.expr(node.operand),), node.span)
        if isinstance(node, st.String):
            return ir.Text(node.text, node.span)
        if isinstance(node, st.Juxtaposed):
            return self.item(node.first)
        if isinstance(node, st.Comparison):
            return self.cond(node)
        raise TypeError(f"unexpected node {type(node).__name__}")

    def cond(self, node: st.Node):
        if isinstance(node, st.Comparison):
            return ir.Compare(COMPARE_OPS.get(node.op, node.op), self.expr(node.left), self.expr(node.right), node.span)
        return ir.Truth(self.expr(node), node.span)


def first_node_key(node: st.Node) -> str:
    if isinstance(node, st.Name):
        return node.key
    return str(node.value) if isinstance(node, st.Number) else ""
