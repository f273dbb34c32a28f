"""The IR reader: the text form of `mcc ir` (compiler/ir_print.py) parsed back into an `ir.Module`.

Operations and terminators are read by the syntax templates of the operation table
(compiler/ir_ops.py), the same the printer writes them by, so the two cannot drift apart:
`to_text(read_text(to_text(m))) == to_text(m)` for every module (tests/ir/test_ir_read.py). Tests
state IR directly with it, as MLIR's FileCheck tests do (`ir_from_text` in tests/ir/ir_text.py).

What the text form does not say is not read back: a span is the line of its `; L<n>` suffix
(column 1) in the file `path`; the module facts that the printer leaves out (`externals`,
`registers`, `device_values`, `print_texts`, `modes_stated`, `axis_sets`) are empty; a `Status`
or `DeviceRef` keeps what it prints (a `DeviceRef`'s meaning is empty). A bare name is the
variable a `var` line declares, else the reading of that name (`ir_names.STATUS`,
`ir_names.SETTINGS`), else a variable. Full-line comments start with `;`.

A text that is not the IR's raises `IRSyntaxError` with the line and column (1-based) of the first
problem. Every walk is iterative or bounded by the nesting of conditions and function calls, so a
long expression (thousands of operators) reads without deep recursion.
"""

from __future__ import annotations

import json
import re

from mcc.compiler import ir, ir_names, ir_ops
from mcc.compiler.ir_ops import Group, Kind, Ref, Text
from mcc.compiler.span import Span


class IRSyntaxError(ValueError):
    """A text that is not the IR's text form: `line`:`col` (1-based) and what was expected."""

    def __init__(self, line: int, col: int, message: str):
        super().__init__(f"{line}:{col}: {message}")
        self.line, self.col, self.message = line, col, message


class _Fail(Exception):
    """A parse that did not match at `pos` (caught where another reading is tried)."""

    def __init__(self, pos: int, message: str):
        super().__init__(message)
        self.pos, self.message = pos, message


def read_text(text: str, path: str = "") -> ir.Module:
    """The module that `text` (one `mcc ir` text form) prints; spans name `path`."""
    return _Reader(text, path).module()


# ---------------------------------------------------------------------------------------------
# Lines: the module's structure


_MODULE = re.compile(r"module (\S+) profile=(.*) steps_per_rev=(-?\d+)")
_ROUTINE = re.compile(r"routine (\S+) \((\w+)\)(?: number=(-?\d+))?(?: origin=(-?\d+))?")
_WHERE = re.compile(r"  ; L(\d+)$")


class _Reader:
    def __init__(self, text: str, path: str):
        self.lines = text.split("\n")
        self.path = path
        self.variables: dict[str, ir.Variable] = {}
        self.label_lines: dict[int, int] = {}  # a block (by id) -> the number of its label line

    def fail(self, number: int, col: int, message: str) -> IRSyntaxError:
        return IRSyntaxError(number, col, message)

    def module(self) -> ir.Module:
        module: ir.Module | None = None
        routine: ir.Routine | None = None
        block: ir.Block | None = None
        body: list[tuple[int, str]] = []  # the indented lines of the current block

        def close() -> None:
            if block is not None:
                self.block_body(block, body)
            body.clear()

        for number, line in enumerate(self.lines, 1):
            if not line.strip() or line.startswith(";"):
                continue
            if module is None:
                found = _MODULE.fullmatch(line)
                if found is None:
                    raise self.fail(number, 1, "expected the module line: module DIALECT profile=NAME steps_per_rev=N")
                module = ir.Module(found[1], found[2], self.variables, path=self.path, steps_per_rev=int(found[3]))
                continue
            if line.startswith("  "):
                if block is None:
                    raise self.fail(number, 1, "an operation outside a block: write a label line (LABEL:) first")
                body.append((number, line))
                continue
            if line.startswith("module "):
                raise self.fail(number, 1, "a second module: read one module per text")
            if line.startswith("var "):
                if module.routines:
                    raise self.fail(number, 1, "a var line after the first routine: declare variables first")
                self.variable(number, line)
                continue
            if line.startswith("routine "):
                close()
                block = None
                found = _ROUTINE.fullmatch(line)
                if found is None:
                    raise self.fail(number, 1, "expected a routine line: routine NAME (KIND) [number=N] [origin=N]")
                try:
                    kind = ir.RoutineKind(found[2])
                except ValueError:
                    raise self.fail(number, line.index("(") + 2, f"routine kind '{found[2]}' is not one of "
                                    f"{', '.join(k.value for k in ir.RoutineKind)}") from None
                routine = ir.Routine(found[1], kind, number=_int(found[3]), origin=_int(found[4]))
                module.routines.append(routine)
                continue
            label, named = (line[:-len(": ; named")], True) if line.endswith(": ; named") else (line[:-1], False)
            if not line.endswith(":") and not named or not label or " " in label:
                raise self.fail(number, 1, "expected a label line (LABEL: or LABEL: ; named), a routine line, "
                                "or an operation indented by two spaces")
            if routine is None:
                raise self.fail(number, 1, "a block outside a routine: write a routine line first")
            close()
            block = ir.Block(label, named=named)
            self.label_lines[id(block)] = number
            routine.blocks.append(block)
        if module is None:
            raise self.fail(max(len(self.lines), 1), 1, "no module line: the text is empty")
        close()
        return module

    def variable(self, number: int, line: str) -> None:
        text, span = self.where(number, line)
        cur = _Line(text, number, self)
        try:
            self._variable(cur, span)
        except _Fail as failed:
            raise self.fail(number, failed.pos + 1, failed.message) from None

    def _variable(self, cur: "_Line", span: Span | None) -> None:
        cur.expect("var ")
        name = cur.until(": ")
        cur.expect(": ")
        kind = cur.word()
        try:
            var_type = ir.VarType(kind)
        except ValueError:
            raise _Fail(cur.pos - len(kind), f"variable type '{kind}' is not one of "
                        f"{', '.join(t.value for t in ir.VarType)}") from None
        scope = "global"
        if cur.rest.startswith(" ") and not cur.rest.startswith(" = "):
            cur.expect(" ")
            scope = cur.word()
        init = None
        if cur.rest:
            cur.expect(" = ")
            init = cur.expr()
        if cur.rest:
            raise _Fail(cur.pos, f"unexpected text: {cur.rest[:20]!r}")
        self.variables[name] = ir.Variable(name, var_type, init, scope, span)

    def where(self, number: int, line: str) -> tuple[str, Span | None]:
        """A line without its `; L<n>` suffix, and the span the suffix names."""
        found = _WHERE.search(line)
        if found is None:
            return line, None
        n = int(found[1])
        return line[:found.start()], Span(self.path, n, 1, n, 1)

    def block_body(self, block: ir.Block, body: list[tuple[int, str]]) -> None:
        if not body:
            raise self.fail(self.label_lines[id(block)], 1, f"block {block.label} has no terminator line "
                            "(jump, branch, return, end, goto routine, fall off, <no terminator>)")
        for number, line in body[:-1]:
            block.ops.append(self.operation(number, line, ir_ops.OPERATIONS))
        number, line = body[-1]
        if line == "  <no terminator>":
            block.terminator = None
        else:
            block.terminator = self.operation(number, line, ir_ops.TERMINATORS)

    def operation(self, number: int, line: str, definitions: tuple[ir_ops.OpDef, ...]):
        text, span = self.where(number, line[2:])
        best: _Fail | None = None
        for definition in _candidates(text, definitions):
            cur = _Line(text, number, self)
            try:
                values = cur.template(definition, ir_ops.PIECES[definition.cls])
                if cur.rest:
                    raise _Fail(cur.pos, f"unexpected text after the {definition.name} operation")
            except _Fail as failed:
                if best is None or failed.pos > best.pos:
                    best = failed
                continue
            for name in _REQUIRED[definition.cls]:
                values.setdefault(name, None)  # a field no group of the line wrote (SetOutput's index)
            node = definition.cls(**values)
            node.span = span
            return node
        what = "a terminator" if definitions is ir_ops.TERMINATORS else "an operation"
        word = re.match(r"[^ (\[]*", text)[0]
        if definitions is ir_ops.OPERATIONS and any(word in _LEADING[d.cls] for d in ir_ops.TERMINATORS):
            raise self.fail(number, 3, f"'{word}' is a terminator: it is the last line of its block")
        if best is None or not any(word in _LEADING[d.cls] for d in definitions):
            # no operation starts with this word: say what may start a line, not why it is no assignment
            also = "" if definitions is ir_ops.TERMINATORS else " or an assignment (NAME = EXPRESSION)"
            raise self.fail(number, 3, f"expected {what}, one of: {_keywords(definitions)}{also}")
        raise self.fail(number, best.pos + 3, best.message)


def _int(text: str | None) -> int | None:
    return int(text) if text is not None else None


def _leading(parts: tuple) -> set[str]:
    """The words a template can start with (empty string: it starts with a field)."""
    if not parts:
        return {""}
    first = parts[0]
    if isinstance(first, Text):
        return {first.text.split(" ")[0].split("(")[0].split("[")[0]}
    if isinstance(first, Group):
        return _leading(first.then) | _leading(first.otherwise)
    return {""}


def _next_texts(definition: ir_ops.OpDef, parts: tuple, start: int, follow: frozenset) -> frozenset:
    """The texts that may come after the piece before `start` in `parts` (`follow`: after them):
    what ends an expression there, so a `%` before one is a percentage, not the remainder."""
    found: set[str] = set()
    for part in parts[start:]:
        if isinstance(part, Text):
            return frozenset(found | {part.text})
        if isinstance(part, Ref):
            if definition.field(part.field).kind is not Kind.FLAG:
                return frozenset(found)  # a field's own text: not known here
            continue
        found |= _next_texts(definition, part.then, 0, frozenset()) | _next_texts(definition, part.otherwise, 0,
                                                                                   frozenset())
    return frozenset(found | follow)


_REQUIRED = {d.cls: tuple(f.name for f in d.fields if d.default(f.name) is ir_ops.dataclasses.MISSING)
             for d in ir_ops.TABLE.values()}
_LEADING = {d.cls: _leading(ir_ops.PIECES[d.cls]) for d in ir_ops.TABLE.values()}


def _candidates(text: str, definitions) -> list[ir_ops.OpDef]:
    """The definitions whose template can start as `text` does: those of its first word first,
    then those that start with a field (an assignment)."""
    word = re.match(r"[^ (\[]*", text)[0]
    first = [d for d in definitions if word in _LEADING[d.cls]]
    return first + [d for d in definitions if "" in _LEADING[d.cls] and d not in first]


def _keywords(definitions) -> str:
    return ", ".join(sorted({w for d in definitions for w in _LEADING[d.cls] if w}))


# ---------------------------------------------------------------------------------------------
# One line: templates, conditions, expressions

_NUMBER = re.compile(r"-?\d+(?:\.\d+)?(?:[eE][+-]?\d+)?|-?inf|nan")
_UNITS = sorted((u.value for u in ir.Unit if u.value), key=len, reverse=True)
_IDENT = re.compile(r"[A-Za-z_%][A-Za-z0-9_%@#$]*(?:\.[A-Za-z_%][A-Za-z0-9_%@#$]*)?")
_WORD = re.compile(r"[^\s,()\[\]]+")
_TARGET_AXIS = re.compile(r"[^\s=,()\[\]]*")  # "" is MCode's "this drive"
_NEXT_TARGET = re.compile(r" [^\s=,()\[\]]*=")
_NAME = re.compile(r"[^\s,()\[\]]*")
# A binary operator as the printer writes it, neutral or not (the verifier judges the names):
# a run of operator characters that is not a comparison.
_OPERATOR = re.compile(r" ([-+*/%&|^<>!~=]+) ")
_COMPARE = sorted(ir_names.COMPARE_OPS, key=len, reverse=True)
_UNARY = tuple(ir_names.UNARY_OPS)
_END = frozenset({""})
_INTEGER = re.compile(r"[+-]?\d+")
_FORMAT = re.compile(r"[a-z]+ \d+(?: magnitude)?")


class _Line:
    """A cursor over one line's text; parse methods raise _Fail at the position they stop."""

    def __init__(self, text: str, number: int, reader: _Reader):
        self.text, self.pos, self.number, self.reader = text, 0, number, reader
        self.follow: frozenset = _END  # the texts that may follow the field being read

    @property
    def rest(self) -> str:
        return self.text[self.pos:]

    def expect(self, text: str) -> None:
        if not self.text.startswith(text, self.pos):
            raise _Fail(self.pos, f"expected {text.strip() or 'a space'!r}")
        self.pos += len(text)

    def until(self, stop: str) -> str:
        end = self.text.find(stop, self.pos)
        if end <= self.pos:
            raise _Fail(self.pos, f"expected a name before {stop.strip()!r}")
        value, self.pos = self.text[self.pos:end], end
        return value

    def word(self, pattern: re.Pattern = _WORD, what: str = "a name") -> str:
        found = pattern.match(self.text, self.pos)
        if found is None or not found[0] and pattern not in (_NAME, _TARGET_AXIS):
            raise _Fail(self.pos, f"expected {what}")
        self.pos = found.end()
        return found[0]

    def integer(self) -> int:
        found = _INTEGER.match(self.text, self.pos)
        if found is None:
            raise _Fail(self.pos, "expected an integer")
        return self.number_value(found, int)

    def number_value(self, found: re.Match, kind):
        """`found`'s number; one too long for Python's conversion (4,300 digits) is refused."""
        try:
            value = kind(found[0])
        except ValueError:
            raise _Fail(self.pos, f"the number {found[0][:20]}... has too many digits") from None
        self.pos = found.end()
        return value

    # -- templates -----------------------------------------------------------------------------

    def template(self, definition: ir_ops.OpDef, parts: tuple) -> dict:
        values: dict = {}
        self.parts(definition, parts, values, _END)
        return values

    def parts(self, definition: ir_ops.OpDef, parts: tuple, values: dict, follow: frozenset) -> None:
        """Read `parts`; `follow`: the texts that may come after them."""
        for index, part in enumerate(parts):
            if isinstance(part, Text):
                self.expect(part.text)
            elif isinstance(part, Ref):
                f = definition.field(part.field)
                if f.kind is Kind.FLAG:
                    values[f.name] = not definition.default(f.name)
                else:
                    self.follow = _next_texts(definition, parts, index + 1, follow)
                    values[f.name] = self.field(f, values)
            else:
                self.group(definition, part, values, _next_texts(definition, parts, index + 1, follow))

    def group(self, definition: ir_ops.OpDef, part: Group, values: dict, follow: frozenset) -> None:
        """An optional group: read when its text is there; once its leading text has matched, a
        problem inside it is the line's error (not a reason to try the other reading)."""
        start, saved, lead = self.pos, dict(values), _first_text(part.then)
        try:
            self.parts(definition, part.then, values, follow)
        except _Fail:
            if lead and self.text.startswith(lead, start):
                raise
            self.pos = start
            values.clear()
            values.update(saved)
            self.parts(definition, part.otherwise, values, follow)

    def field(self, f: ir_ops.Field, values: dict):
        kind = f.kind
        if kind is Kind.EXPR:
            return self.expr()
        if kind is Kind.COND:
            return self.cond()
        if kind is Kind.ARGS:
            return tuple(self.listed(self.cond, ")"))
        if kind is Kind.ITEMS:
            items, formats = self.items()
            if any(formats):
                values["formats"] = tuple(formats)
            return tuple(items)
        if kind is Kind.EXPR_PAIR:
            first = self.expr()
            self.expect(", ")
            return (first, self.expr())
        if kind in (Kind.AXIS, Kind.NAME, Kind.ROUTINE, Kind.LABEL):
            return self.word(_NAME, "a name")  # may be empty: "" is MCode's axis "this drive"
        if kind is Kind.AXIS_PAIR:
            first = self.word(re.compile(r"[^\s,()\[\]]+"), "an axis")
            self.expect(",")
            return (first, self.word(what="an axis"))
        if kind is Kind.AXIS_EXPRS:
            pairs = []
            while True:
                axis = self.word(_TARGET_AXIS, "an axis")
                self.expect("=")
                pairs.append((axis, self.expr()))
                if not _NEXT_TARGET.match(self.rest):
                    return tuple(pairs)
                self.pos += 1
        if kind is Kind.VAR:
            return ir.Var(self.word(_IDENT, "a variable"))
        if kind is Kind.ENUM:
            word = self.word()
            try:
                return f.enum(word)
            except ValueError:
                raise _Fail(self.pos - len(word), f"'{word}' is not one of "
                            f"{', '.join(e.value for e in f.enum)}") from None
        if kind is Kind.SIGN:
            if self.rest[:1] not in ("+", "-"):
                raise _Fail(self.pos, "expected + or -")
            self.pos += 1
            return 1 if self.text[self.pos - 1] == "+" else -1
        if kind in (Kind.SIGNED, Kind.INT):
            return self.integer()
        if kind is Kind.BOOL:
            for word, value in zip(f.words, (True, False)):
                if self.text.startswith(word, self.pos):
                    self.pos += len(word)
                    return value
            raise _Fail(self.pos, f"expected {f.words[0]} or {f.words[1]}")
        if kind is Kind.QUOTED:
            return self.string()
        # FORMATS: read with the ITEMS they format; a new kind needs its reading here (the table's
        # tests read every operation, so they name it)
        raise _Fail(self.pos, f"mcc cannot read a field of kind {kind.value} ({f.name})")

    def listed(self, parse, close: str) -> list:
        found = []
        if self.text.startswith(close, self.pos):
            return found
        while True:
            found.append(parse())
            if not self.text.startswith(", ", self.pos):
                return found
            self.pos += 2

    def items(self) -> tuple[list, list]:
        """Print items `e1 as fixed 3, e2`; none when no expression starts here."""
        items, formats = [], []
        if not self.operand_starts(self.pos):
            return items, formats
        self.follow = self.follow | {" as ", ", "}
        while True:
            items.append(self.expr())
            spec = ""
            if self.text.startswith(" as ", self.pos):
                self.pos += 4
                spec = self.word(_FORMAT, "a print format (fixed 3, bits 10, pad 2, ...)")
            formats.append(spec)
            if not self.text.startswith(", ", self.pos):
                while formats and not formats[-1]:
                    formats.pop()
                return items, formats
            self.pos += 2

    def string(self) -> str:
        if self.rest[:1] != '"':
            raise _Fail(self.pos, "expected a quoted text")
        try:
            value, end = json.JSONDecoder().raw_decode(self.text, self.pos)
        except json.JSONDecodeError as error:
            raise _Fail(error.pos, f"a quoted text: {error.msg}") from None
        self.pos = end
        return value

    # -- conditions ------------------------------------------------------------------------------

    def cond(self):
        """A condition as `ir_print.cond_text` writes it, or an expression used as one."""
        text = self.text
        if text.startswith("truth ", self.pos):
            self.pos += 6
            return ir.Truth(self.expr())
        if text.startswith("inputs match ", self.pos):
            self.pos += 13
            return ir.InputMatch(ir.Pattern(self.word(re.compile(r"[^\s,()]*"), "a pattern")))
        if text.startswith("not (", self.pos):
            self.pos += 5
            inner = self.cond()
            self.expect(")")
            return ir.Not(inner)
        if text.startswith("(", self.pos):
            close = self.matching(self.pos)
            for op in ir_names.LOGIC_OPS:
                if close is not None and text.startswith(f") {op} (", close):
                    self.pos += 1
                    left = self.cond()
                    self.expect(f") {op} (")
                    right = self.cond()
                    self.expect(")")
                    return ir.Logic(op, left, right)
        left = self.expr()
        for op in _COMPARE:
            if text.startswith(f" {op} ", self.pos):
                self.pos += len(op) + 2
                return ir.Compare(op, left, self.expr())
        return left

    def matching(self, pos: int) -> int | None:
        """The position of the `)` that closes the `(` at `pos` (quoted texts skipped)."""
        depth, text = 0, self.text
        while pos < len(text):
            char = text[pos]
            if char == '"':
                try:
                    pos = json.JSONDecoder().raw_decode(text, pos)[1]
                except json.JSONDecodeError:
                    return None
                continue
            if char == "(":
                depth += 1
            elif char == ")":
                depth -= 1
                if depth == 0:
                    return pos
            pos += 1
        return None

    # -- expressions -----------------------------------------------------------------------------

    def operand_starts(self, pos: int) -> bool:
        text = self.text
        if pos >= len(text):
            return False
        char = text[pos]
        if char.isalnum() or char in '_("@':
            return True
        if char in _UNARY:  # a unary operator against an operand (`-V1`, `!(a)`), not `!=`
            return self.operand_starts(pos + 1)
        if char == "%":  # a name such as %L1, not the remainder operator
            return pos + 1 < len(text) and (text[pos + 1].isalnum() or text[pos + 1] == "_")
        return False

    def expr(self):
        """An expression as `ir_print.expr_text` writes it: binary operators with one space each
        side, left to right (the printer parenthesises every operator below the top); unary
        operators written against their operand. Iterative: explicit stacks, no recursion per
        parenthesis."""
        text = self.text
        values: list = []
        ops: list = []  # "(" | ("u", op) | ("b", op)

        def reduce_unary() -> None:
            while ops and isinstance(ops[-1], tuple) and ops[-1][0] == "u":
                values.append(ir.UnOp(ops.pop()[1], values.pop()))

        def reduce_binary() -> None:
            if ops and isinstance(ops[-1], tuple) and ops[-1][0] == "b":
                right, left = values.pop(), values.pop()
                values.append(ir.BinOp(ops.pop()[1], left, right))

        depth = 0
        while True:
            # an operand
            char = text[self.pos:self.pos + 1]
            if char == "(":
                ops.append("(")
                depth += 1
                self.pos += 1
                continue
            if char in _UNARY and not _NUMBER.match(text, self.pos) and self.operand_starts(self.pos):
                ops.append(("u", char))
                self.pos += 1
                continue
            values.append(self.atom())
            reduce_unary()
            # operators and closing parentheses
            while True:
                if depth and text.startswith(")", self.pos):
                    self.pos += 1
                    reduce_binary()
                    ops.pop()  # its "(" (depth counts the open ones)
                    depth -= 1
                    reduce_unary()
                    continue
                break
            found = _OPERATOR.match(text, self.pos)
            op = found[1] if found is not None and found[1] not in ir_names.COMPARE_OPS else None
            if op is not None and self.operand_starts(self.pos + len(op) + 2):
                reduce_binary()
                ops.append(("b", op))
                self.pos += len(op) + 2
                continue
            if depth:
                raise _Fail(self.pos, "expected ')' or an operator")
            reduce_binary()
            return values.pop()

    def atom(self):
        text, pos = self.text, self.pos
        number = _NUMBER.match(text, pos)
        if number is not None and not (number[0][-1:].isalpha() and _IDENT.match(text, pos) is not None
                                       and _IDENT.match(text, pos).end() > number.end()):
            value = self.number_value(number, float if any(c in number[0] for c in ".eEn") else int)
            if value == 0 and number[0].startswith("-"):  # "-0" is a negation: the constant prints "0"
                return ir.UnOp("-", ir.Const(-value, self.unit()))
            return ir.Const(value, self.unit())
        char = text[pos:pos + 1]
        if char == '"':
            return ir.Text(self.string())
        if char == "@":
            self.pos += 1
            return ir.LabelRef(self.word(what="a label"))
        if text.startswith("pattern ", pos):
            self.pos += 8
            return ir.Pattern(self.word(re.compile(r"[^\s,()]*"), "a pattern"))
        name = self.word(_IDENT, "an expression")
        if "." in name:
            dialect, register = name.split(".", 1)
            axis, index = self.qualifiers()
            return ir.DeviceRef(dialect, register, axis=axis, index=index)
        if text.startswith("(", self.pos) and name in ir_names.FUNCTIONS:
            self.pos += 1
            args = self.listed(self.expr, ")")
            self.expect(")")
            return ir.Func(name, tuple(args))
        if text.startswith(("(", "["), self.pos) or (name not in self.reader.variables
                                                     and (name in ir_names.STATUS or name in ir_names.SETTINGS)):
            axis, index = self.qualifiers()
            return ir.Status(name, axis, index)
        return ir.Var(name)

    def qualifiers(self) -> tuple[str, int | None]:
        axis, index = "", None
        if self.text.startswith("(", self.pos):
            self.pos += 1
            axis = self.word(re.compile(r"[^\s()]+"), "an axis")
            self.expect(")")
        if self.text.startswith("[", self.pos):
            self.pos += 1
            index = self.integer()
            self.expect("]")
        return axis, index

    def unit(self) -> ir.Unit:
        """The unit written after a number (` steps`, ` s`, ` %`, ...), or none."""
        text, pos = self.text, self.pos
        if not text.startswith(" ", pos):
            return ir.Unit.NONE
        for unit in _UNITS:
            end = pos + 1 + len(unit)
            if not text.startswith(unit, pos + 1):
                continue
            after = text[end:end + 1]
            if after not in ("", " ", ")", ",", "]"):
                continue
            if unit == "%" and after == " " and self.operand_starts(end + 1) \
                    and not any(text.startswith(t, end) for t in self.follow if t.strip()) \
                    and not _NEXT_TARGET.match(text, end):
                continue  # the remainder operator, not a percentage before the template's next text
            self.pos = end
            return ir.Unit(unit)
        return ir.Unit.NONE


def _first_text(parts: tuple) -> str:
    for part in parts:
        if isinstance(part, Text):
            return part.text
        if not isinstance(part, Ref):  # a group: no text of its own to commit to
            return ""
    return ""
