"""Writing IR as X150 command text: the canonical form shared by the backend and the memory check.

The canonical form (docs/dialects/x150.md, "Backend"): upper case, one command per line, no spaces
inside a command (`GOTO2` is written `XG2`, `1OUTLXX10X1`), the device address in front, the `B`
prefix on immediate `*` commands stored in a sequence, no comments. Each sequence is written
`XEn XDn ... XT`. The memory check of the frontend counts the bytes of exactly these lines (each
character and its delimiter one byte, L241), so what mcc reports is what it would download.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from mcc.compiler import ir
from mcc.compiler.diagnostics import Diagnostics
from mcc.compiler.profiles import Profile
from mcc.compiler.span import Span
from mcc.compiler.x150 import catalog as cat
from mcc.compiler.x150 import naming
from mcc.compiler.x150.modes import get_mode, set_mode
from mcc.compiler.x150.structurer import LOOP_PREFIX, Step, Structurer, Unstructured, flat_steps

DIALECT = "x150"
KEYWORDS = {"L": "L", "IF": "IF", "ELSE": "ELSE", "NIF": "NIF", "WHILE": "WHILE", "NWHILE": "NWHILE",
            "REPEAT": "REPEAT", "UNTIL": "UNTIL", "N": "N"}
HANDLER_COMMANDS = {"powerup": "XP", "fault": "XFK", "when": "XWHEN"}
MOTION_COMMANDS = {ir.MotionParam.ACCEL: "A", ir.MotionParam.MAX_SPEED: "V"}
ARITHMETIC = "+-*/"
MAX_CONDITION_NODES = 32  # far above any writable condition; bounds the recursion on odd input


def number(value) -> str:
    """A number as the controller reads it: integers plain, decimals shortest, E notation (L152-L161)."""
    if isinstance(value, bool):
        value = int(value)
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


class CannotWrite(Exception):
    def __init__(self, message: str, code: str = "X202"):
        super().__init__(message)
        self.message = message
        self.code = code


class Writer:
    def __init__(self, module: ir.Module, profile: Profile):
        self.module = module
        self.profile = profile
        self.cat = cat.load()
        self.out = Written()
        self.numbers = self.sequence_numbers()
        self.variables = self.variable_numbers()
        self.entries = {r.blocks[0].label: r.name for r in module.routines if r.blocks}
        self.routine: ir.Routine | None = None
        self.device: int | None = None
        self.in_sequence = False
        self.position_mode: dict[str, ir.MoveMode] = {}
        self.foreign_reported: set[str] = set()

    # -- sequence numbers --------------------------------------------------------------------------
    def sequence_numbers(self) -> dict[str, int]:
        """Every non-immediate routine's sequence number (routines of other dialects get free ones)."""
        numbers: dict[str, int] = {}
        used = set()
        for routine in self.module.routines:
            if routine.kind is ir.RoutineKind.IMMEDIATE:
                continue
            n = naming.sequence_number(routine.name) or routine.number
            if self.module.dialect == DIALECT and n:
                numbers[routine.name] = n
                used.add(n)
        free = (n for n in range(1, 65) if n not in used)
        for routine in self.module.routines:
            if routine.kind is not ir.RoutineKind.IMMEDIATE and routine.name not in numbers:
                n = routine.number if routine.number and routine.number not in used and 1 <= routine.number <= 64 \
                    else next(free, 0)
                used.add(n)
                numbers[routine.name] = n
        return numbers

    def variable_numbers(self) -> dict[str, int]:
        """VARn keeps its number; variables of other dialects get the free VAR numbers in order."""
        numbers = {name: variable_number(name) for name in self.module.variables if variable_number(name)}
        used = set(numbers.values())
        free = (n for n in range(1, 51) if n not in used)
        for name in self.module.variables:
            if name not in numbers and not name.startswith(LOOP_PREFIX):
                numbers[name] = next(free, 0)
        return numbers

    def var_number(self, name: str) -> int:
        return self.variables.get(name) or variable_number(name)

    def number_of(self, name: str) -> int:
        if name in self.numbers:
            return self.numbers[name]
        return naming.sequence_number(name) or 0

    # -- module and routines -----------------------------------------------------------------------
    def write_module(self) -> Written:
        selected = set()
        for routine in self.module.routines:
            for block in routine.blocks:
                for op in block.ops:
                    if isinstance(op, ir.SetHandler) and op.event == "powerup" and op.routine:
                        selected.add(op.routine)
        for routine in self.ordered():
            self.write_routine(routine)
        for routine in self.module.routines:  # a power-up routine from another dialect: select it
            if routine.kind is ir.RoutineKind.POWERUP and routine.name not in selected:
                self.routine, self.in_sequence = routine, False
                self.emit(f"XP{self.number_of(routine.name)}", routine.span)
        return self.out

    def ordered(self) -> list[ir.Routine]:
        """X150 programs keep their stream order. A program of another dialect is written as its
        variables' initial values, then every sequence definition, then its immediate commands,
        so no sequence runs before it is stored."""
        routines = self.module.routines
        if self.module.dialect == DIALECT:
            return routines
        initial = [ir.Assign(ir.Var(v.name), v.init, v.span) for v in self.module.variables.values()
                   if v.init is not None and not v.name.startswith(LOOP_PREFIX)]
        first = [ir.Routine("initial values", ir.RoutineKind.IMMEDIATE, [ir.Block("%init", initial, ir.FallOff())])] \
            if initial else []
        return first + [r for r in routines if r.kind is not ir.RoutineKind.IMMEDIATE] + \
            [r for r in routines if r.kind is ir.RoutineKind.IMMEDIATE]

    def write_routine(self, routine: ir.Routine) -> None:
        self.routine = routine
        self.device = naming.device_of(routine.name) if self.module.dialect == DIALECT else None
        self.position_mode = {}
        self.in_sequence = routine.kind is not ir.RoutineKind.IMMEDIATE
        prefix = str(self.device) if self.device is not None else ""
        if self.in_sequence:
            n = self.number_of(routine.name)
            if not 1 <= n <= 64:
                self.out.diagnostics.add("X203", routine.span or self.fallback_span(),
                                         f"routine {routine.name} needs a sequence number, but all 64 are in use")
            first, _ = ends(routine.span)
            self.emit(f"{prefix}XE{n}", first, stored=False)
            self.emit(f"{prefix}XD{n}", getattr(routine.entry, "span", None) or first, stored=False)
        try:
            steps = Structurer(routine, self.entries).run()
        except Unstructured as exc:
            self.out.diagnostics.add("X201", exc.span or routine.span or self.fallback_span(),
                                     f"{exc.message} in {routine.name}: X150 sequences have no labels, so only "
                                     "L..N, IF..ELSE..NIF, WHILE..NWHILE and REPEAT..UNTIL can be written; "
                                     "restructure this part")
            steps = flat_steps(routine)
        for step in steps:
            self.write_step(step)
        if self.in_sequence:
            self.emit(f"{prefix}XT", self.definition_end(routine))

    def definition_end(self, routine: ir.Routine) -> Span | None:
        """The source of XT: the end of an X150 sequence's definition span (XEn..XT), else the last
        terminator (a routine of another dialect ends where its last statement is)."""
        span = routine.span
        if span is not None and span.end_line > span.line:
            return ends(span)[1]
        end = routine.blocks[-1].terminator if routine.blocks else None
        return getattr(end, "span", None) or span

    def fallback_span(self) -> Span:
        return Span(self.module.path or "<module>", 1, 1, 1, 1)

    def emit(self, text: str, *spans: Span | None, stored: bool = True) -> None:
        """Add a line; `stored` lines of a sequence count against its memory (XEn and XDn do not)."""
        sequence = self.routine.name if self.in_sequence and stored else None
        self.out.lines.append(Line(text, tuple(s for s in spans if s is not None), sequence))
        if sequence is not None:
            self.out.sequence_bytes[sequence] = self.out.sequence_bytes.get(sequence, 0) + len(text) + 1

    # -- steps ---------------------------------------------------------------------------------------
    def write_step(self, step: Step) -> None:
        try:
            if step.kind == "op":
                self.write_op(step.payload)
            elif step.kind == "term":
                self.write_term(step.payload)
            elif step.kind == "L":
                count = step.payload
                if count is None or (isinstance(count, ir.Const) and count.value == 0):
                    self.emit(self.address() + "L", step.span)
                else:
                    self.emit(self.address() + "L" + self.value(count), step.span)
            elif step.kind in ("IF", "WHILE", "UNTIL"):
                self.emit(f"{self.address()}{step.kind}({self.cond(step.payload)})", step.span)
            else:
                self.emit(self.address() + KEYWORDS[step.kind], step.span)
        except CannotWrite as exc:
            span = step.span or self.routine.span or self.fallback_span()
            self.out.diagnostics.add(exc.code, span, exc.message)

    def address(self, axis: str = ir.ALL_AXES) -> str:
        if self.device is not None:
            return str(self.device)
        return axis if axis.isdigit() else ""

    def target(self, name: str) -> tuple[str, int]:
        """The address and number to write for a command naming routine `name`."""
        device = naming.device_of(name) if self.module.dialect == DIALECT else None
        prefix = self.address() if self.device is not None else (str(device) if device is not None else "")
        return prefix, self.number_of(name)

    def write_term(self, term) -> None:
        span = term.span
        if isinstance(term, ir.GotoRoutine):
            prefix, n = self.target(term.routine)
            self.emit(f"{prefix}XG{n}", span)
        elif isinstance(term, ir.Return):
            self.emit(self.address() + "XRT", span)
        elif isinstance(term, ir.End):
            self.emit(self.address() + "HALT", span)

    def write_op(self, op) -> None:
        span = op.span
        if isinstance(op, ir.Native):
            if op.dialect != DIALECT:
                raise CannotWrite(f"{op.dialect} command {op.mnemonic} has no X150 equivalent; rewrite this part "
                                  "with X150 commands or compile to its own dialect", "G003")
            self.emit(self.native(op), span)
            role = info.ir if (info := self.cat.lookup(op.mnemonic)) is not None else ""
            if role in ("mode_absolute", "mode_incremental"):
                mode = ir.MoveMode.ABSOLUTE if role == "mode_absolute" else ir.MoveMode.RELATIVE
                set_mode(self.position_mode, op.axis, mode)
        elif isinstance(op, ir.SetMotion):
            command = MOTION_COMMANDS.get(op.param)
            if command is None:
                raise CannotWrite(f"X150 has no command for the {op.param.value.replace('_', ' ')}", "G003")
            self.emit(self.address(op.axis) + command + self.value(op.value, allow_var=True), span)
        elif isinstance(op, ir.Move):
            self.move(op)
        elif isinstance(op, ir.Delay):
            self.emit(self.address() + "T" + self.seconds(op.duration), span)
        elif isinstance(op, ir.WaitInput):
            self.emit(self.address() + self.wait(op.cond), span)
        elif isinstance(op, ir.Assign):
            self.emit(self.address() + self.assign(op), span)
        elif isinstance(op, ir.Save):
            self.emit(self.address() + "SV", span)
        elif isinstance(op, ir.Call):
            if op.cond is not None:
                raise CannotWrite("X150 has no conditional call: write IF(...) XRn NIF")
            prefix, n = self.target(op.routine)
            self.emit(f"{prefix}XR{n}", span)
        elif isinstance(op, ir.SetHandler):
            self.handler(op)
        else:
            raise CannotWrite(f"{type(op).__name__} has no X150 equivalent in mcc yet", "G003")

    def handler(self, op: ir.SetHandler) -> None:
        command = HANDLER_COMMANDS.get(op.event)
        if command is None:
            raise CannotWrite(f"X150 has no '{op.event}' handler (only power-up XP, fault XFK and WHEN)", "G003")
        if op.routine is not None:
            prefix, n = self.target(op.routine)
            self.emit(f"{prefix}{command}{n}", op.span)
        elif op.event == "when" and op.args:
            self.emit(f"{self.address()}WHEN({self.cond(op.args[0])})", op.span)
        else:
            self.emit(f"{self.address()}{command}0", op.span)

    def move(self, op: ir.Move) -> None:
        if len(op.targets) != 1:
            raise CannotWrite("X150 moves one axis per command; a multi-axis move has no equivalent", "G003")
        axis, target = op.targets[0]
        prefix = self.address(axis)
        span = op.span
        first, last = ends(span)
        if op.mode is not ir.MoveMode.MODAL and get_mode(self.position_mode, axis) is not op.mode:
            self.emit(prefix + ("MPA" if op.mode is ir.MoveMode.ABSOLUTE else "MPI"), span)
            set_mode(self.position_mode, axis, op.mode)
        if not (isinstance(target, ir.DeviceRef) and target.dialect == DIALECT and target.name == "D"):
            self.emit(prefix + "D" + self.value(target, allow_var=True), first)
        self.emit(prefix + "G", last)

    # -- operands ------------------------------------------------------------------------------------
    def value(self, expr, allow_var: bool = True) -> str:
        if isinstance(expr, ir.Const) and isinstance(expr.value, (int, float)):
            return number(expr.value)
        if allow_var and isinstance(expr, ir.Var) and self.var_number(expr.name):
            return f"(VAR{self.var_number(expr.name)})"
        raise CannotWrite(f"an X150 value is a number or (VARn); {describe(expr)} cannot be written here")

    def seconds(self, expr) -> str:
        if isinstance(expr, ir.Const) and expr.unit is ir.Unit.MS:
            return number(expr.value / 1000)
        return self.value(expr)

    def wait(self, cond) -> str:
        if isinstance(cond, ir.InputMatch):
            return "TRE" + cond.pattern.bits
        if isinstance(cond, ir.Not) and isinstance(cond.cond, ir.InputMatch):
            return "TRN" + cond.cond.pattern.bits
        raise CannotWrite("X150 waits only for an input pattern (TRE/TRN)", "G003")

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
            return number(expr.value)
        if isinstance(expr, ir.Var) and self.var_number(expr.name):
            return f"VAR{self.var_number(expr.name)}"
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
        if isinstance(cond, ir.Logic):
            self.terms(cond.left, terms, joins)
            joins.append(cond.op.upper())
            self.terms(cond.right, terms, joins)
        elif isinstance(cond, ir.InputMatch):
            terms.append("IN" + cond.pattern.bits)
        elif isinstance(cond, ir.Compare) and cond.op in self.cat.relational:
            terms.append(self.operand(cond.left) + cond.op + self.operand(cond.right))
        else:
            raise CannotWrite(f"{describe(cond)} is not an X150 condition (VARn>x, VARn<x, VARn=x, IN<pattern>, "
                              "joined by AND or OR)")

    # -- native commands -----------------------------------------------------------------------------
    def native(self, op: ir.Native) -> str:
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


def ends(span: Span | None) -> tuple[Span | None, Span | None]:
    """The first and the last character of a span: a Move made of `D..` and `G` maps each written
    line back to its own source line."""
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
            return expand(ir.Compare(NEGATED[inner.op], inner.left, inner.right, inner.span))
        if isinstance(inner, ir.Logic):  # De Morgan
            flipped = "or" if inner.op == "and" else "and"
            return ir.Logic(flipped, expand(ir.Not(inner.left)), expand(ir.Not(inner.right)), inner.span)
        return cond
    if isinstance(cond, ir.Compare) and cond.op in SPLIT:
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
    return f"this {type(expr).__name__.lower()}"


def write(module: ir.Module, profile: Profile) -> Written:
    return Writer(module, profile).write_module()


def sequence_sizes(module: ir.Module, profile: Profile) -> dict[str, int]:
    """The bytes each sequence routine stores, as the backend would write it (the memory check)."""
    writer = Writer(module, profile)
    for routine in module.routines:
        if routine.kind is not ir.RoutineKind.IMMEDIATE:
            writer.write_routine(routine)
    return writer.out.sequence_bytes
