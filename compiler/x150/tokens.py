"""Reading one X150 command token: `[address][B][MNEMONIC][argument]`, written without separators.

The grammar (grammars/x150.lark) cuts a line into command tokens; this module reads each token:

1. an optional device address (leading digits; its range is a check, not syntax);
2. the `B` prefix, recognised only when the rest begins with an immediate `*` command (L185), so
   `B`, `BS` and `BDL` keep their meaning;
3. the mnemonic, by **longest match against the catalog** (a "longest run of letters" rule would
   eat pattern arguments: `SKEX1`, `INLXXXX10X_1XX1X0XX`, `DLEDXX1`);
4. the argument, parsed by the catalog's argument class (number, pattern17, composite, ...).

Findings are attached to the node as `Problem`s and reported by the parser once it knows the
command is final: a space inside a command is tolerated by re-joining two tokens, which needs a
silent trial parse first.
"""

from __future__ import annotations

import re
from typing import Callable

from mcc.compiler.span import Span
from mcc.compiler.suggest import close_matches
from mcc.compiler.x150 import syntax as st
from mcc.compiler.x150.catalog import Command as CatalogCommand
from mcc.compiler.x150.catalog import X150Catalog

NUMBER = re.compile(r"[+-]?(?:[0-9]+\.?[0-9]*|\.[0-9]+)(?:[Ee][+-]?[0-9]+)?")
DIGITS = re.compile(r"[0-9]+")
ASCII_DIGITS = "0123456789"
VAR_SUBST = re.compile(r"\(\s*[Vv][Aa][Rr]([0-9]+)\s*\)")
VAR_NAME = re.compile(r"[Vv][Aa][Rr]([0-9]+)")
WORD = re.compile(r"[A-Za-z]+")
# An operand of VARn=: VAR_NAME, WORD or NUMBER, the first that matches (read_operand)
OPERAND = re.compile(rf"{VAR_NAME.pattern}|({WORD.pattern})|{NUMBER.pattern}")
IO_FUNCTION = re.compile(r"([0-9]+)([A-Za-z])")
PATTERN_CHARS = re.compile(r"[01Xx_]*")
RELOP = re.compile(r"[<>=!]+")
SPACES = re.compile(r"\s*")
BIT_CLASSES = {  # argument class -> (characters, min length, max length)
    "pattern6": ("01X", 1, 6),
    "led8": ("01X", 1, 8),
    "bits8": ("01", 8, 8),
    "bits6": ("01", 6, 6),
}
INPUT_GROUPS = (7, 10)  # dedicated inputs, then user inputs IN1-IN10 (L3778-L3779)
INPUTS, OUTPUTS = 10, 6


class Piece:
    """The text of one command token and where each character sits in the source.

    A token is contiguous, except when the tolerance rule re-joins a command and an argument
    written after a space (`IF (...)`, `1OUTL XX10X1`): then the second part starts at `start2`.
    """

    __slots__ = ("text", "start", "gap", "start2")

    def __init__(self, text: str, start: int, gap: int | None = None, start2: int = 0):
        self.text = text
        self.start = start
        self.gap = len(text) if gap is None else gap
        self.start2 = start2

    def offset(self, index: int) -> int:
        if index < self.gap:
            return self.start + index
        return self.start2 + index - self.gap

    def end_offset(self, index: int) -> int:
        """Source offset just after character `index - 1` (exclusive end)."""
        if index <= 0:
            return self.start
        return self.offset(index - 1) + 1


class LineSpans:
    """Spans on one line, without a search: a command never crosses a line end."""

    __slots__ = ("path", "line", "line_start")

    def __init__(self, path: str, line: int, line_start: int):
        self.path = path
        self.line = line
        self.line_start = line_start

    def at(self, start: int, end: int) -> Span:
        base = self.line_start - 1
        return Span(self.path, self.line, start - base, self.line, end - base, start, end)


class ArgError(Exception):
    """A malformed argument: message and the character range (in the token) it is about."""

    def __init__(self, message: str, begin: int, end: int):
        super().__init__(message)
        self.message = message
        self.begin = begin
        self.end = end


HUGE = 10**18  # stands for any whole number with more digits than that: out of every range the checks know


def whole(digits: str) -> int:
    """int() of a digit string of any length: Python refuses more than 4300 digits, and no
    controller value has more than a handful, so a longer one is read as HUGE (still reported as
    out of range by the checks, never an internal error)."""
    if len(digits) <= 18:  # the common case: int() takes it as it is
        return int(digits)
    significant = digits.lstrip("+-").lstrip("0")
    if len(significant) > 18:
        return -HUGE if digits.startswith("-") else HUGE
    return int(digits)


def number_value(text: str) -> int | float:
    if "." in text or "e" in text or "E" in text:
        return float(text)
    return whole(text)


def add_problem(cmd: st.Command, problem: st.Problem) -> None:
    cmd.problems += (problem,)  # a tuple: most commands have none, and share the empty one


class CommandReader:
    """Reads command tokens against the catalog. One instance per catalog (cached by the parser)."""

    def __init__(self, cat: X150Catalog):
        self.cat = cat
        self.names = sorted(cat.commands)
        self.input_functions = frozenset(cat.input_functions())
        self.output_functions = frozenset(cat.output_functions())
        self.relational = frozenset(cat.relational)
        self.sources = {name.upper() for name in cat.sources}
        self.arithmetic = {name.upper() for name in cat.arithmetic_sources}

    # -- the token -------------------------------------------------------------------------------
    def read(self, piece: Piece, spans: LineSpans) -> st.Command:
        """The command a token is, its argument written after a space re-joined or not."""
        text = piece.text
        size = len(text)
        if piece.gap >= size:
            return self.read_token(text, piece.start, spans)
        at = spans.at

        def sub(begin: int, end: int) -> Span:
            start = piece.offset(begin) if begin < size else piece.end_offset(size)
            return at(start, piece.end_offset(end) if end > begin else start)

        return self.read_command(st.Command(text, at(piece.start, piece.end_offset(size))), text, sub, False)

    def read_token(self, text: str, base: int, spans: LineSpans) -> st.Command:
        """The command a contiguous token is, `base` the offset of its first character: the common
        case (no re-joined space), whose spans are made by addition."""
        size = len(text)
        path = spans.path
        line = spans.line
        column = base - spans.line_start + 1  # of the token's first character

        def sub(begin: int, end: int) -> Span:
            start = begin if begin < size else size
            stop = (end if end < size else size) if end > begin else start
            return Span(path, line, column + start, line, column + stop, base + start, base + stop)

        # The address and mnemonic spans are characters of the command's span (st.Command): lazy.
        return self.read_command(st.Command(text, Span(path, line, column, line, column + size, base, base + size)),
                                 text, sub, True)

    def read_again(self, text: str, base: int, spans: LineSpans, readings: dict) -> st.Command:
        """`read_token`, for a text read before in the same file: a copy of the first reading
        with its spans moved to this place (`Reading`). A program repeats its commands (`1G`,
        `1D4000`): the catalog match, the number and the argument's structure are worked out once
        per distinct text, and each further occurrence costs only its new nodes and spans. The
        result is the one `read_token` gives, field for field: a token's reading depends on its
        text only, its spans on where it stands (all on one line: a token does not cross a line
        end). Not for a token with problems, or one that is host data (their spans are given,
        not lazy): those are read each time, as are texts seen once."""
        found = readings.get(text)
        if found is None:
            cmd = self.read_token(text, base, spans)
            readings[text] = Reading.of(cmd, base) or False
            return cmd
        if found is False:
            return self.read_token(text, base, spans)
        first = found.cmd
        path = spans.path
        line = spans.line
        column = base - spans.line_start + 1
        size = len(text)
        cmd = st.Command(text, Span(path, line, column, line, column + size, base, base + size), first.address,
                         first.address_chars, None, first.buffered, first.mnemonic, first.written,
                         first.mnemonic_from, first.mnemonic_to, None, first.info)
        arg = first.arg
        if arg is not None:
            arg = MOVERS[type(arg)](arg, path, line, column - found.column, base - found.base)
            cmd.arg = arg
            cmd.arg_span = arg.span
        return cmd

    def read_command(self, cmd: st.Command, text: str, sub, lazy: bool) -> st.Command:
        first = text[0]
        if first == "!":
            return self.read_host(cmd, text, sub)
        pos = 0
        if "0" <= first <= "9":
            pos = len(text) - len(text.lstrip(ASCII_DIGITS))  # DIGITS.match, without the expression
            digits = text[:pos]
            cmd.address = int(digits) if pos <= 18 else whole(digits)
            if lazy:
                cmd.address_chars = pos  # sub(0, pos): pos > 0
            else:
                cmd.address_span = sub(0, pos)
            if pos == len(text):
                add_problem(cmd, st.Problem("X003", cmd.span,
                                               f"'{text}' is a device address with no command after it; "
                                               "write the command right after the address (1A10)"))
                return cmd
        cat = self.cat
        info = None
        if text[pos] in "Bb":
            prefixed = cat.match(text, pos + 1)
            if prefixed is not None and prefixed.b_prefixable:
                cmd.buffered = True
                info = prefixed
                pos += 1
        if info is None:
            info = cat.match(text, pos)
            if info is None:
                self.unknown(cmd, text, pos, sub)
                return cmd
        end = pos + len(info.name)
        cmd.info = info
        cmd.mnemonic = info.name
        cmd.written = text[pos:end]
        if lazy:  # sub(begin, end): the mnemonic is inside the token, and not empty
            cmd.mnemonic_from = pos - 1 if cmd.buffered else pos
            cmd.mnemonic_to = end
        else:
            cmd.mnemonic_span = sub(pos - (1 if cmd.buffered else 0), end)
        kind = info.arg
        if end == len(text) and kind in EMPTY_IS_NONE:  # no argument, and none needed
            return cmd
        try:
            arg = ARG_READERS.get(kind, CommandReader.read_none)(self, cmd, text, end, sub)
        except ArgError as exc:
            add_problem(cmd, st.Problem("X002", sub(exc.begin, max(exc.end, exc.begin)), exc.message))
            return cmd
        if arg is not None:
            cmd.arg = arg
            cmd.arg_span = arg.span
        return cmd

    def read_host(self, cmd: st.Command, text: str, sub) -> st.Command:
        cmd.host = True
        cmd.mnemonic = cmd.written = "!"
        cmd.mnemonic_span = sub(0, 1)
        if NUMBER.fullmatch(text, 1):
            cmd.arg = st.Number(text[1:], number_value(text[1:]), sub(1, len(text)))
            cmd.arg_span = cmd.arg.span
        else:
            add_problem(cmd, st.Problem("X002", sub(1, len(text)),
                                           "host data for VARn=RSIN is '!' followed by a number (!12.34, L3604)"))
        return cmd

    def unknown(self, cmd: st.Command, text: str, pos: int, sub) -> None:
        word = WORD.match(text, pos)
        if word is None:
            add_problem(cmd, st.Problem(
                "X003", sub(pos, len(text)),
                f"'{text[pos:]}' is not an X150 command: a command starts with its mnemonic (after an optional "
                "device address)"))
            return
        name = word.group()
        cmd.written = name
        cmd.mnemonic_span = sub(pos, word.end())
        close = close_matches(name.upper(), self.names, n=3, cutoff=0.6)
        hint = f" (did you mean {', '.join(close)}?)" if close else ""
        add_problem(cmd, st.Problem("X101", cmd.mnemonic_span,
                                       f"'{name}' is not an X150 command{hint}; see the command list in "
                                       "docs/dialects/x150.md"))

    # -- argument classes ------------------------------------------------------------------------
    def read_none(self, cmd: st.Command, text: str, pos: int, sub):
        if pos == len(text):
            return None
        rest = text[pos:]
        hint = ""
        if cmd.mnemonic == "B":  # B1CPG50, BV5: a B prefix written the wrong way
            digits = DIGITS.match(text, pos)
            after = self.cat.match(text, digits.end() if digits else pos)
            if digits and after is not None and after.b_prefixable:
                hint = f"; put the device address before the B: {digits.group()}B{text[digits.end():]}"
            elif after is not None and not digits:
                hint = (f"; only the immediate '*' commands have a buffered B form, and {after.name} is not "
                        "one of them")
        raise ArgError(f"{cmd.mnemonic} takes no value, but '{rest}' follows it{hint}", pos, len(text))

    def read_subst(self, cmd: st.Command, text: str, pos: int, sub):
        match = VAR_SUBST.fullmatch(text, pos)
        if match is None:
            return None
        if not (cmd.info and cmd.info.var_subst):
            raise ArgError(f"{cmd.mnemonic} cannot take its value from a variable: (VARn) works only for the "
                           "commands the manual lists (L4575-L4590)", pos, len(text))
        return st.VarRef(whole(match.group(1)), sub(pos, len(text)))

    def read_number(self, cmd: st.Command, text: str, pos: int, sub):
        size = len(text)
        if pos == size:
            return None
        if text[pos] == "(":  # only then can it be (VARn)
            found = self.read_subst(cmd, text, pos, sub)
            if found is not None:
                return found
        written = text[pos:]
        if written.isdigit() and written.isascii():  # the common case, without the expression: [0-9]+
            return st.Number(written, int(written) if size - pos <= 18 else whole(written), sub(pos, size))
        if NUMBER.fullmatch(text, pos) is None:
            match = NUMBER.match(text, pos)
            bad = match.end() if match else pos
            raise ArgError(f"{cmd.mnemonic} takes a number (10, -2.5, 1.2E-3)"
                           + (" or (VARn)" if cmd.info and cmd.info.var_subst else "")
                           + f"; '{text[bad:]}' is not part of one", bad, size)
        return st.Number(written, number_value(written), sub(pos, size))

    def read_int(self, cmd: st.Command, text: str, pos: int, sub):
        size = len(text)
        if pos == size:
            return None
        if text[pos] == "(":  # only then can it be (VARn)
            found = self.read_subst(cmd, text, pos, sub)
            if found is not None:
                return found
        written = text[pos:]
        if not (written.isdigit() and written.isascii()):  # [0-9]+ (ASCII: `isdigit` takes other digits too)
            match = DIGITS.match(text, pos)
            bad = match.end() if match else pos
            raise ArgError(f"{cmd.mnemonic} takes a whole number; '{text[bad:]}' is not part of one",
                           bad, size)
        return st.Number(written, int(written) if size - pos <= 18 else whole(written), sub(pos, size))

    def pattern17(self, text: str, pos: int, end: int, sub, what: str) -> st.Pattern:
        bits = text[pos:end].upper()
        groups = bits.split("_")
        if len(groups) > 2:
            raise ArgError(f"{what}: an input pattern has at most one '_' (dedicated inputs _ user inputs)",
                           pos, end)
        for group, size in zip(groups, INPUT_GROUPS):
            if len(group) > size:
                raise ArgError(f"{what}: '{group}' has {len(group)} positions, but that group has {size} inputs "
                               "(7 dedicated inputs, '_', then IN1-IN10; L3778)", pos, end)
        return st.Pattern(bits, sub(pos, end))

    def read_pattern17(self, cmd: st.Command, text: str, pos: int, sub):
        if pos == len(text):
            return None
        match = PATTERN_CHARS.match(text, pos)
        if match.end() != len(text):
            raise ArgError(f"{cmd.mnemonic} takes an input pattern of 0, 1 and X (e.g. _XX1); "
                           f"'{text[match.end()]}' cannot appear in one", match.end(), len(text))
        return self.pattern17(text, pos, len(text), sub, cmd.mnemonic)

    def read_bits(self, cmd: st.Command, text: str, pos: int, sub):
        if pos == len(text):
            return None
        chars, low, high = BIT_CLASSES[cmd.info.arg]
        bits = text[pos:].upper()
        bad = next((i for i, ch in enumerate(bits) if ch not in chars), None)
        if bad is not None or not low <= len(bits) <= high:
            size = f"{low}" if low == high else f"{low}-{high}"
            where = pos + bad if bad is not None else pos
            raise ArgError(f"{cmd.mnemonic} takes {size} positions of {' or '.join(chars)}; got '{text[pos:]}'",
                           where, len(text))
        return st.Pattern(bits, sub(pos, len(text)))

    def read_io_function(self, cmd: st.Command, text: str, pos: int, sub, count: int, functions) -> st.IoFunction | None:
        if pos == len(text):
            return None
        match = IO_FUNCTION.fullmatch(text, pos)
        kind = "input" if count == INPUTS else "output"
        if match is None:
            raise ArgError(f"{cmd.mnemonic} takes an {kind} number and a function letter ({cmd.mnemonic}3B)",
                           pos, len(text))
        index, letter = whole(match.group(1)), match.group(2).upper()
        if not 1 <= index <= count:
            raise ArgError(f"{kind} {index} does not exist: the {kind}s are 1-{count}", pos, match.end(1))
        if letter not in functions:
            raise ArgError(f"'{letter}' is not an {kind} function (known: {' '.join(sorted(functions))})",
                           match.start(2), len(text))
        return st.IoFunction(index, letter, sub(pos, len(text)))

    def read_in_function(self, cmd, text, pos, sub):
        return self.read_io_function(cmd, text, pos, sub, INPUTS, self.input_functions)

    def read_out_function(self, cmd, text, pos, sub):
        return self.read_io_function(cmd, text, pos, sub, OUTPUTS, self.output_functions)

    def read_fields(self, cmd: st.Command, text: str, pos: int, sub):
        info = cmd.info
        fields = info.fields
        if not fields:  # a raw argument without a field list: keep the text
            return st.Text(text[pos:], sub(pos, len(text))) if pos < len(text) else None
        if pos == len(text):
            if 0 in info.counts:
                return None
            raise ArgError(f"{cmd.mnemonic} needs {self.describe_fields(info)}", pos, pos)
        sep = info.separator
        values: list[int] = []
        spans: list[Span] = []
        cursor = pos
        tail = None
        for index, spec in enumerate(fields):
            if index and sep:
                if cursor >= len(text) or text[cursor] != sep:
                    break
                cursor += 1
            match = DIGITS.match(text, cursor)
            if match is None:
                break
            end = cursor + spec.digits if spec.digits else match.end()
            if spec.digits and match.end() - cursor < spec.digits:
                raise ArgError(f"{cmd.mnemonic}: the {spec.name} is always written with {spec.digits} digits "
                               f"({self.example(info)})", cursor, match.end())
            values.append(whole(text[cursor:end]))
            spans.append(sub(cursor, end))
            cursor = end
        if info.tail:
            if len(values) == len(fields) and cursor < len(text) and text[cursor] == sep:
                tail = text[cursor + 1:]
                cursor = len(text)
            elif len(values) == len(fields) and cursor == len(text):
                tail = ""
        if cursor != len(text) or len(values) not in info.counts:
            raise ArgError(f"{cmd.mnemonic} takes {self.describe_fields(info)} ({self.example(info)}); "
                           f"'{text[pos:]}' does not fit", pos, len(text))
        return st.Fields(values, spans, tail, sub(pos, len(text)))

    @staticmethod
    def describe_fields(info: CatalogCommand) -> str:
        names = ", ".join(f.name for f in info.fields)
        counts = info.counts
        if 0 in counts and len(counts) == 2:
            return f"either nothing or all of: {names}"
        return names + (" and a text" if info.tail else "")

    @staticmethod
    def example(info: CatalogCommand) -> str:
        parts = [str(f.low).rjust(f.digits, "0") if f.digits else str(f.low) for f in info.fields]
        count = max(info.counts)
        text = info.separator.join(parts[:count])
        return info.name + text + (info.separator + "TEXT" if info.tail else "")

    def read_string(self, cmd: st.Command, text: str, pos: int, sub):
        if cmd.mnemonic == '"':  # the quote command is its own opening quote: 1"2XR1"
            body_start = pos
        else:
            if pos == len(text) or text[pos] != '"':
                raise ArgError(f'{cmd.mnemonic} takes quoted text: {cmd.mnemonic}"TEXT"', pos, len(text))
            body_start = pos + 1
        close = text.find('"', body_start)
        if close < 0:
            raise ArgError("the text has no closing '\"'", pos, len(text))
        if close != len(text) - 1:
            raise ArgError(f"'{text[close + 1:]}' follows the closing quote; end the command after it",
                           close + 1, len(text))
        return st.Text(text[body_start:close], sub(body_start, close))

    # -- variables ---------------------------------------------------------------------------------
    def read_variable(self, cmd: st.Command, text: str, pos: int, sub):
        match = DIGITS.match(text, pos)
        if match is None:
            hint = " (write VARn=VARm to copy a variable)" if text.startswith("(", pos) else ""
            raise ArgError(f"{cmd.mnemonic} needs a variable number: {cmd.mnemonic}1 to {cmd.mnemonic}50{hint}",
                           pos, len(text))
        var = st.VarRef(whole(match.group()), sub(pos, match.end()))
        cursor = match.end()
        if cursor == len(text):
            return st.VarStatement(var, None, sub(pos, len(text)))
        if text[cursor] != "=":
            raise ArgError(f"expected '=' after {cmd.mnemonic}{var.number}, not '{text[cursor:]}'",
                           cursor, len(text))
        chain = self.read_chain(text, cursor + 1, sub)
        first = chain.first
        if isinstance(first, st.Source) and first.name in self.cat.statements:
            cmd.info = self.cat.statements[first.name]
        return st.VarStatement(var, chain, sub(pos, len(text)))

    def read_operand(self, text: str, pos: int, sub) -> tuple[st.Operand, int]:
        # VAR_NAME, else WORD (a source), else NUMBER, tried in that order by one expression
        found = OPERAND.match(text, pos)
        if found is not None:
            number, word = found.group(1, 2)
            end = found.end()
            if number is not None:
                return st.VarRef(whole(number), sub(pos, end)), end
            if word is None:
                written = found.group()
                return st.Number(written, number_value(written), sub(pos, end)), end
            if word.upper() in self.sources:
                return st.Source(word.upper(), sub(pos, end)), end
        raise ArgError("expected VARn, a number or one of " + " ".join(sorted(self.sources))
                       + (f", not '{text[pos:]}'" if pos < len(text) else " after the operator"), pos, len(text))

    def read_chain(self, text: str, pos: int, sub) -> st.Chain:
        first, cursor = self.read_operand(text, pos, sub)
        rest: list[tuple[str, st.Operand]] = []
        starts = [pos]
        while cursor < len(text):
            op = text[cursor]
            if op not in "+-*/":
                raise ArgError(f"expected + - * or / here, not '{text[cursor:]}'", cursor, len(text))
            starts.append(cursor + 1)
            operand, cursor = self.read_operand(text, cursor + 1, sub)
            rest.append((op, operand))
        if rest:
            for start, operand in zip(starts, [first] + [o for _, o in rest]):
                if isinstance(operand, st.Source) and operand.name not in self.arithmetic:
                    raise ArgError(f"{operand.name} must stand alone on the right of '=' (VAR1={operand.name}); "
                                   f"only {' and '.join(sorted(self.arithmetic))} take part in arithmetic",
                                   start, start + len(operand.name))
        return st.Chain(first, rest, sub(pos, len(text)))

    # -- conditions --------------------------------------------------------------------------------
    def read_condition(self, cmd: st.Command, text: str, pos: int, sub):
        if pos == len(text) or text[pos] != "(":
            raise ArgError(f"{cmd.mnemonic} needs a condition in parentheses: {cmd.mnemonic}(VAR1>5 AND IN_XX1)",
                           pos, len(text))
        close = text.find(")", pos)
        if close < 0:
            raise ArgError("the condition has no closing ')'", pos, len(text))
        if close != len(text) - 1:
            raise ArgError(f"'{text[close + 1:]}' follows the condition; end the command after ')'",
                           close + 1, len(text))
        terms: list[st.Term] = []
        joins: list[str] = []
        cursor = SPACES.match(text, pos + 1).end()
        if cursor == close:
            raise ArgError("the condition is empty: write a term such as VAR1>5 or IN_XX1", pos, len(text))
        while True:
            term, cursor = self.read_term(text, cursor, close, sub)
            terms.append(term)
            cursor = SPACES.match(text, cursor, close).end()
            if cursor >= close:
                break
            word = WORD.match(text, cursor, close)
            if word is None or word.group().upper() not in ("AND", "OR"):
                raise ArgError(f"expected AND or OR between two terms, not '{text[cursor:close]}'", cursor, close)
            joins.append(word.group().upper())
            cursor = SPACES.match(text, word.end(), close).end()
            if cursor >= close:
                raise ArgError(f"a term must follow {joins[-1]}", word.start(), close)
        return st.Condition(terms, joins, sub(pos, len(text)))

    def read_term(self, text: str, pos: int, close: int, sub) -> tuple[st.Term, int]:
        if text[pos:pos + 2].upper() == "IN" and (pos + 2 >= close or text[pos + 2] in "01Xx_ "):
            start = SPACES.match(text, pos + 2, close).end()
            end = PATTERN_CHARS.match(text, start, close).end()
            if end == start:
                raise ArgError("IN needs an input pattern: IN_1 is input 1, IN_XX1 input 3", pos, close)
            pattern = self.pattern17(text, start, end, sub, "IN")
            return st.InputTerm(pattern, "_" in pattern.bits, sub(pos, end)), end
        var = VAR_NAME.match(text, pos, close)
        if var is None:
            raise ArgError("a condition term is VARn<op>value or IN<pattern> (VAR1>5, IN_XX1)", pos, close)
        left = st.VarRef(whole(var.group(1)), sub(pos, var.end()))
        cursor = SPACES.match(text, var.end(), close).end()
        rel = RELOP.match(text, cursor, close)
        if rel is None or rel.group() not in self.relational:
            shown = rel.group() if rel else text[cursor:close]
            raise ArgError(f"X150 conditions compare with {', '.join(sorted(self.relational))} only, not '{shown}'",
                           cursor, rel.end() if rel else close)
        cursor = SPACES.match(text, rel.end(), close).end()
        right_var = VAR_NAME.match(text, cursor, close)
        if right_var:
            right: st.Operand = st.VarRef(whole(right_var.group(1)), sub(cursor, right_var.end()))
            end = right_var.end()
        else:
            number = NUMBER.match(text, cursor, close)
            if number is None:
                raise ArgError(f"expected VARn or a number after '{rel.group()}'", cursor, close)
            right = st.Number(number.group(), number_value(number.group()), sub(cursor, number.end()))
            end = number.end()
        return st.Comparison(left, rel.group(), right, sub(pos, end)), end


class Reading:
    """A token's first reading, kept to be copied for each later occurrence of the same text
    (`CommandReader.read_again`): the command and where it was read (its first column and offset)."""

    __slots__ = ("cmd", "column", "base")

    def __init__(self, cmd: st.Command, column: int, base: int):
        self.cmd = cmd
        self.column = column
        self.base = base

    @staticmethod
    def of(cmd: st.Command, base: int) -> "Reading | None":
        """The reading to keep, or None when `cmd` is not copied but read again each time: it has
        problems (reported with each occurrence), or spans that are not the token's lazy ones."""
        if cmd.problems or cmd.host or cmd.given_address_span is not None or cmd.given_mnemonic_span is not None \
                or (cmd.arg is not None and type(cmd.arg) not in MOVERS):
            return None
        return Reading(cmd, cmd.span.column, base)


# Copies of an argument node with its spans moved by `chars` columns and `offset` characters to
# `line` of `path` (a token's spans are all on its line). Lists are copied; the values in them are
# numbers and strings, shared.
def _moved(span: Span, path: str, line: int, chars: int, offset: int) -> Span:
    return Span(path, line, span.column + chars, line, span.end_column + chars, span.start + offset, span.end + offset)


def _move_number(arg: st.Number, path: str, line: int, chars: int, offset: int) -> st.Number:
    span = arg.span
    return st.Number(arg.text, arg.value, Span(path, line, span.column + chars, line, span.end_column + chars,
                                                span.start + offset, span.end + offset))


def _move_var(arg: st.VarRef, path: str, line: int, chars: int, offset: int) -> st.VarRef:
    return st.VarRef(arg.number, _moved(arg.span, path, line, chars, offset))


def _move_source(arg: st.Source, path: str, line: int, chars: int, offset: int) -> st.Source:
    return st.Source(arg.name, _moved(arg.span, path, line, chars, offset))


def _move_pattern(arg: st.Pattern, path: str, line: int, chars: int, offset: int) -> st.Pattern:
    return st.Pattern(arg.bits, _moved(arg.span, path, line, chars, offset))


def _move_io(arg: st.IoFunction, path: str, line: int, chars: int, offset: int) -> st.IoFunction:
    return st.IoFunction(arg.index, arg.function, _moved(arg.span, path, line, chars, offset))


def _move_text(arg: st.Text, path: str, line: int, chars: int, offset: int) -> st.Text:
    return st.Text(arg.text, _moved(arg.span, path, line, chars, offset))


def _move_fields(arg: st.Fields, path: str, line: int, chars: int, offset: int) -> st.Fields:
    return st.Fields(list(arg.values), [_moved(span, path, line, chars, offset) for span in arg.spans], arg.tail,
                     _moved(arg.span, path, line, chars, offset))


def _move_chain(arg: st.Chain, path: str, line: int, chars: int, offset: int) -> st.Chain:
    first = arg.first
    return st.Chain(MOVERS[type(first)](first, path, line, chars, offset),
                    [(op, MOVERS[type(operand)](operand, path, line, chars, offset)) for op, operand in arg.rest],
                    _moved(arg.span, path, line, chars, offset))


def _move_statement(arg: st.VarStatement, path: str, line: int, chars: int, offset: int) -> st.VarStatement:
    value = arg.value
    return st.VarStatement(_move_var(arg.var, path, line, chars, offset),
                           None if value is None else _move_chain(value, path, line, chars, offset),
                           _moved(arg.span, path, line, chars, offset))


def _move_comparison(arg: st.Comparison, path: str, line: int, chars: int, offset: int) -> st.Comparison:
    left, right = arg.left, arg.right
    return st.Comparison(MOVERS[type(left)](left, path, line, chars, offset), arg.op,
                         MOVERS[type(right)](right, path, line, chars, offset),
                         _moved(arg.span, path, line, chars, offset))


def _move_input(arg: st.InputTerm, path: str, line: int, chars: int, offset: int) -> st.InputTerm:
    return st.InputTerm(_move_pattern(arg.pattern, path, line, chars, offset), arg.underscore,
                        _moved(arg.span, path, line, chars, offset))


def _move_condition(arg: st.Condition, path: str, line: int, chars: int, offset: int) -> st.Condition:
    return st.Condition([MOVERS[type(term)](term, path, line, chars, offset) for term in arg.terms],
                        list(arg.joins), _moved(arg.span, path, line, chars, offset))


MOVERS: dict[type, Callable] = {
    st.Number: _move_number, st.VarRef: _move_var, st.Source: _move_source, st.Pattern: _move_pattern,
    st.IoFunction: _move_io, st.Text: _move_text, st.Fields: _move_fields, st.Chain: _move_chain,
    st.VarStatement: _move_statement, st.Comparison: _move_comparison, st.InputTerm: _move_input,
    st.Condition: _move_condition,
}

# The reader of each argument class (catalog `arg`); a class not listed takes no value. Plain
# functions, not bound methods kept by the reader (a reference cycle: tests/test_no_cycles.py).
ARG_READERS: dict[str, Callable] = {
    "none": CommandReader.read_none, "query": CommandReader.read_none,
    "number": CommandReader.read_number, "int": CommandReader.read_int, "sequence": CommandReader.read_int,
    "pattern17": CommandReader.read_pattern17, "pattern6": CommandReader.read_bits, "led8": CommandReader.read_bits,
    "bits8": CommandReader.read_bits, "bits6": CommandReader.read_bits,
    "in_func": CommandReader.read_in_function, "out_func": CommandReader.read_out_function,
    "composite": CommandReader.read_fields, "raw": CommandReader.read_fields, "string": CommandReader.read_string,
    "variable": CommandReader.read_variable, "condition": CommandReader.read_condition,
}
# The argument classes whose reader finds nothing, and nothing wrong, in an empty argument: a
# command written without a value (`1G`, `1A`) is not sent to its reader.
EMPTY_IS_NONE = frozenset(kind for kind, reader in ARG_READERS.items()
                          if reader not in (CommandReader.read_fields, CommandReader.read_string,
                                            CommandReader.read_variable, CommandReader.read_condition))
