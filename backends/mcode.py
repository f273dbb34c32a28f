"""The MCode backend: IR → a device-ready Lexium MCode listing.

Layout (the convention of every sample in the manual, L7617-L7658):

    VA declarations, then the immediate setup lines
    PG <address>
      the main routine: labels, body, E
      subroutines and handlers, each ending in RT
    PG
    S                (when the source saved)

Every line fits the 64-character device buffer (a longer one is an error, M201). Blocks the source
did not name get generated labels that follow the naming rules (two characters, a letter first,
never an MCode name) and never collide with the program's own names. Output is canonical (upper
case, `NAME=value` for settings, `MA 100` for instructions, no comments), so compiling the output
again gives the same text.
"""

from __future__ import annotations

import string

from mcc.backends.listing import Listing
from mcc.compiler import ir
from mcc.compiler.diagnostics import Diagnostics
from mcc.compiler.mcode import catalog as cat
from mcc.compiler.profiles import Profile

DIALECT = "mcode"
PARAM_NAMES = {ir.MotionParam.ACCEL: "A", ir.MotionParam.DECEL: "D", ir.MotionParam.INITIAL_SPEED: "VI",
               ir.MotionParam.MAX_SPEED: "VM", ir.MotionParam.RESOLUTION: "MS"}
COMPARE = {"=": "=", "!=": "<>", "<": "<", "<=": "<=", ">": ">", ">=": ">="}
NEGATE = {"=": "!=", "!=": "=", "<": ">=", "<=": ">", ">": "<=", ">=": "<"}  # in IR spelling
FUNCTIONS = {"abs": "AB", "cos": "CS", "acos": "C_", "ln": "LO", "log10": "L_", "sin": "SI", "asin": "S_",
             "sqrt": "SQ", "tan": "TG", "atan": "T_"}
TRIPS = {"input": "TI", "position": "TP", "capture": "TC", "time": "TT", "relative": "TR", "hmt": "TA",
         "power": "TM"}
UNIT_FACTORS = {ir.Unit.S: 1000}  # delays are written in ms


class Unsupported(Exception):
    """An IR construct this backend cannot write; reported as G003 at the operation's span."""


def format_number(value: int | float) -> str:
    if isinstance(value, float):
        if value.is_integer() and abs(value) < 1e15:
            return f"{value:.1f}"
        return repr(value)
    return str(value)


class Writer:
    def __init__(self, module: ir.Module, profile: Profile):
        self.module = module
        self.profile = profile
        self.cat = cat.load()
        self.listing = Listing(DIALECT)
        self.diags: Diagnostics = self.listing.diagnostics
        self.labels = self.allocate_labels()
        self.limit = int(profile.get("limits.line_length", 64))

    # labels --------------------------------------------------------------------------------------
    def used_names(self) -> set[str]:
        names = set(self.module.variables)
        for _, block in self.module.blocks():
            if not block.label.startswith(("%", "@")):
                names.add(block.label)
        return names

    def needed_blocks(self) -> set[str]:
        """Unnamed blocks that something jumps to, calls, or names as a handler need a label."""
        needed: set[str] = set()
        order = [b.label for _, b in self.module.blocks()]
        following = {label: order[i + 1] if i + 1 < len(order) else None for i, label in enumerate(order)}
        for _, block in self.module.blocks():
            term = block.terminator
            after = following.get(block.label)
            if isinstance(term, ir.Jump) and term.target != after:
                needed.add(term.target)
            elif isinstance(term, ir.Branch):  # mirrors Writer.branch
                if term.then == after and isinstance(term.cond, ir.Compare):
                    needed.add(term.otherwise)
                else:
                    needed.add(term.then)
                    if term.otherwise != after:
                        needed.add(term.otherwise)
            for op in block.ops:
                if isinstance(op, ir.Call):
                    needed.add(op.routine)
        for routine in self.module.routines:
            if routine.kind in (ir.RoutineKind.SUBROUTINE, ir.RoutineKind.HANDLER) and routine.entry:
                needed.add(routine.entry.label)
        return needed

    def allocate_labels(self) -> dict[str, str]:
        """Deterministic two-character names for the blocks that need one (Z0, Z1, ... skipping taken names)."""
        taken = self.used_names()
        reserved = self.cat.commands.keys() | self.cat.functions.keys() | self.cat.legacy.keys()
        candidates = (first + second for first in "ZYXWQJ" for second in string.digits + string.ascii_uppercase)
        mapping: dict[str, str] = {}
        for _, block in self.module.blocks():
            label = block.label
            if not label.startswith("%") or label not in self.needed_blocks_cache():
                continue
            for name in candidates:
                if name not in taken and name not in reserved:
                    mapping[label] = name
                    taken.add(name)
                    break
        return mapping

    _needed: set[str] | None = None

    def needed_blocks_cache(self) -> set[str]:
        if self._needed is None:
            self._needed = self.needed_blocks()
        return self._needed

    def label(self, block_label: str) -> str:
        if block_label.startswith("@"):
            return block_label[1:]
        return self.labels.get(block_label, block_label)

    # output --------------------------------------------------------------------------------------
    def line(self, text: str, *spans) -> None:
        if len(text) > self.limit:
            span = next((s for s in spans if s is not None), None)
            if span is not None:
                self.diags.add("M201", span, f"the generated line is {len(text)} characters, over the device's "
                                             f"{self.limit}: `{text[:40]}…`; split the expression in the source")
        self.listing.emit(text, *spans)

    def run(self) -> Listing:
        for var in self.module.variables.values():
            if var.scope == "global":
                init = f"={self.expr(var.init)}" if var.init is not None else ""
                self.line(f"VA {var.name}{init}", var.span)
        region_open = False
        order = [(r, b) for r in self.module.routines for b in r.blocks]
        for index, (routine, block) in enumerate(order):
            if routine.kind is ir.RoutineKind.IMMEDIATE:
                if region_open:
                    self.line("PG")
                    region_open = False
                for op in block.ops:
                    self.op(op)
                continue
            if routine.origin is not None and block is routine.entry:
                if region_open:
                    self.line("PG")
                self.line(f"PG {routine.origin}", routine.span)
                region_open = True
            next_label = order[index + 1][1].label if index + 1 < len(order) else None
            self.block(block, next_label)
        if region_open:
            self.line("PG")
        self.stats()
        return self.listing

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

    def block(self, block: ir.Block, next_label: str | None) -> None:
        if block.named or block.label in self.labels:
            self.line(f"LB {self.label(block.label)}", block.span)
        for op in block.ops:
            self.op(op)
        term = block.terminator
        span = getattr(term, "span", None)
        if isinstance(term, ir.Jump):
            if term.target != next_label:
                self.line(f"BR {self.label(term.target)}", span)
        elif isinstance(term, ir.Branch):
            self.branch(term, next_label)
        elif isinstance(term, ir.Return):
            self.line("RT", span)
        elif isinstance(term, ir.End):
            self.line("E", span)
        elif isinstance(term, ir.GotoRoutine):
            target = self.module.routine(term.routine)
            self.line(f"BR {self.label(target.entry.label if target and target.entry else term.routine)}", span)

    def branch(self, term: ir.Branch, next_label: str | None) -> None:
        try:
            if term.then == next_label and isinstance(term.cond, ir.Compare):
                negated = ir.Compare(NEGATE[term.cond.op], term.cond.left, term.cond.right, term.cond.span)
                self.line(f"BR {self.label(term.otherwise)},{self.cond(negated)}", term.span)
                return
            self.line(f"BR {self.label(term.then)},{self.cond(term.cond)}", term.span)
            if term.otherwise != next_label:
                self.line(f"BR {self.label(term.otherwise)}", term.span)
        except Unsupported as exc:
            self.unsupported(term.span, str(exc))

    def unsupported(self, span, what: str) -> None:
        if span is not None:
            self.diags.add("G003", span, f"{what} cannot be written in MCode")

    # operations ----------------------------------------------------------------------------------
    def op(self, op) -> None:
        try:
            text = self.op_text(op)
        except Unsupported as exc:
            self.unsupported(op.span, str(exc))
            return
        if text is not None:
            self.line(text, op.span)

    def prefix(self, axis: str) -> str:
        return axis if axis and axis not in ("1", ir.ALL_AXES) else ("*" if axis == ir.ALL_AXES else "")

    def op_text(self, op) -> str | None:
        if isinstance(op, ir.Native):
            return self.native(op)
        if isinstance(op, ir.Assign):
            return self.assign(op)
        if isinstance(op, ir.SetMotion):
            if op.param not in PARAM_NAMES:
                raise Unsupported(f"the motion setting {op.param.value}")
            if op.value and isinstance(op.value, ir.Const) and op.value.unit not in (ir.Unit.NONE, ir.Unit.STEPS_PER_S,
                                                                                   ir.Unit.STEPS_PER_S2, ir.Unit.STEPS):
                raise Unsupported(f"a {op.param.value} in {op.value.unit.value}")
            return f"{self.prefix(op.axis)}{PARAM_NAMES[op.param]}={self.expr(op.value)}"
        if isinstance(op, ir.Move):
            if len(op.targets) != 1 or op.mode is ir.MoveMode.MODAL:
                raise Unsupported("a multi-axis or modal move")
            axis, target = op.targets[0]
            name = "MA" if op.mode is ir.MoveMode.ABSOLUTE else "MR"
            args = [self.expr(target)] + [self.expr(value) for _, value in op.options]
            return f"{self.prefix(axis)}{name} {','.join(args)}"
        if isinstance(op, ir.Slew):
            if op.velocity is None:
                return f"{self.prefix(op.axis)}SL {'-' if op.direction < 0 else ''}VM"
            return f"{self.prefix(op.axis)}SL {self.expr(op.velocity)}"
        if isinstance(op, ir.Home):
            name = {"switch": "HM", "index": "HI", "offset": "HF"}.get(op.method)
            if name is None or op.mode is None:
                raise Unsupported(f"homing by {op.method}")
            return f"{self.prefix(op.axis)}{name} {self.expr(op.mode)}"
        if isinstance(op, ir.WaitMotion):
            return f"{self.prefix(op.axis)}H"
        if isinstance(op, ir.Delay):
            return f"H {self.delay(op.duration)}"
        if isinstance(op, ir.SetPosition):
            return f"{self.prefix(op.axis)}P={self.expr(op.value)}"
        if isinstance(op, ir.SetOutput):
            if op.index is None:
                return f"OT={self.expr(op.value)}"
            return f"O{op.index}={self.expr(op.value)}"
        if isinstance(op, ir.Print):
            items = ",".join(self.item(item) for item in op.items)
            return f"PR {items}{'' if op.newline else ';'}"
        if isinstance(op, ir.DriveEnable):
            return f"{self.prefix(op.axis)}DE={self.expr(op.on)}"
        if isinstance(op, ir.Call):
            target = self.call_label(op.routine)
            return f"CL {target}" + (f",{self.cond(op.cond)}" if op.cond is not None else "")
        if isinstance(op, ir.SetHandler):
            return self.handler(op)
        if isinstance(op, ir.Save):
            return "S"
        if isinstance(op, ir.Stop):
            if op.ramp:
                return f"{self.prefix(op.axis)}SL 0"
            raise Unsupported("an abort without deceleration (MCode stops with ESC, not a statement)")
        raise Unsupported(f"the operation {type(op).__name__}")

    def call_label(self, name: str) -> str:
        routine = self.module.routine(name)
        if routine is not None and routine.entry is not None:
            return self.label(routine.entry.label)
        return self.label(name)

    def assign(self, op: ir.Assign) -> str:
        target = op.target.name
        value = op.value
        if isinstance(value, ir.BinOp) and value.op in "+-" and value.left == op.target \
                and isinstance(value.right, ir.Const) and value.right.value == 1:
            return f"{'IC' if value.op == '+' else 'DC'} {target}"
        return f"{target}={self.expr(value)}"

    def handler(self, op: ir.SetHandler) -> str:
        label = self.call_label(op.routine) if op.routine else ""
        args = [self.expr(a) for a in op.args]
        if op.event == "error":
            return f"OE {label}"
        name = TRIPS.get(op.event)
        if name is None:
            raise Unsupported(f"a '{op.event}' event handler")
        if name == "TI":
            return f"TI {','.join(args[:1] + [label])}"
        if name in ("TC", "TM"):
            return f"{name}={label}"
        if name == "TR":
            return f"TR={','.join(args[:1] + [label] + args[1:])}"
        if name == "TA":
            return f"TA={','.join([label] + args)}"
        return f"{name}={','.join(args + [label])}"

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

    # expressions ---------------------------------------------------------------------------------
    def delay(self, duration) -> str:
        if isinstance(duration, ir.Const) and duration.unit in UNIT_FACTORS:
            value = duration.value * UNIT_FACTORS[duration.unit]
            return format_number(int(value) if float(value).is_integer() else value)
        return self.expr(duration)

    def item(self, node) -> str:
        if isinstance(node, ir.Text):
            return f'"{node.value}"'
        if isinstance(node, (ir.Compare, ir.Truth, ir.Logic, ir.Not, ir.InputMatch)):
            return self.cond(node)
        return self.expr(node)

    def expr(self, node) -> str:
        if isinstance(node, ir.Const):
            return format_number(node.value)
        if isinstance(node, ir.Var):
            return node.name
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
            return ("-" if node.op == "-" else "!") + operand
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
            if name is None or len(node.args) != 1:
                raise Unsupported(f"the function {node.name}")
            return f"{name} {self.expr(node.args[0])}"
        raise Unsupported(f"the value {type(node).__name__}")

    def cond(self, node) -> str:
        if isinstance(node, ir.Compare):
            return f"{self.expr(node.left)}{COMPARE[node.op]}{self.expr(node.right)}"
        if isinstance(node, ir.Truth):
            return self.expr(node.expr)
        raise Unsupported("a condition with AND/OR or an input pattern (MCode tests one condition)")


def emit(module: ir.Module, profile: Profile) -> Listing:
    return Writer(module, profile).run()
