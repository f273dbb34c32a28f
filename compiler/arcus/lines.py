"""Reading the common Arcus lines with regular expressions instead of the LALR parser.

Every line of `grammars/arcus.lark` stands on its own (`start: line*`), and the lines programs are
made of have a few shapes: a command of parts (`X1000Y2000`, `WAITX`, `GOSUB 1`, `ENDIF`), maybe
with `:` operands (`ARCP0:100:30000`), an assignment with at most one operator (`V1=V2+1`,
`HSPD=20000`), a condition with one comparison of two operands (`IF DI1=1`, `WHILE V3<5`), a
comment, nothing. A line of one of these shapes is matched by one regular expression and its
syntax nodes are made from the groups of the match, exactly as the parser's callbacks
(`parser.Builder`) make them from the tokens: the same words, numbers and spans. That costs about
a quarter of the parse (docs/PERFORMANCE.md).

Any other line (`~`, `<<`, AND/OR, a chain of operators or comparisons, a character the grammar
does not know, a syntax error) is left to the parser: each run of such lines in one `parse` call,
positioned where the run stands, and line by line (with recovery) when that call fails, as
`recovery.parse_lines` does for a whole text. The grammar is what defines a line:
`tests/arcus/test_arcus_lines.py` compares what this module reads with what the parser reads on
generated lines, and checks that the grammar's terminals are still the ones written below.
"""

from __future__ import annotations

import re
from typing import Callable

from mcc.compiler import recovery
from mcc.compiler.arcus import syntax as st
from mcc.compiler.span import SourceFile, Span
from mcc.grammars.lark_runtime import Lark, LarkError

# The grammar's terminals, as the patterns below assume them (the test compares them).
WORD_PATTERN = "[A-Za-z]+"
NUMBER_PATTERN = "[0-9]+"
COMMENT_PATTERN = "[;'][^\n]*"
IGNORED_PATTERN = "[ \t]+"

# A word or a number ends where its letters or digits end (the lexer's longest match), so no
# backtracking splits one.
_WORD = r"[A-Za-z]+(?![A-Za-z])"
_NUMBER = r"[0-9]+(?![0-9])"
_WS = r"[ \t]*"
_COMMENT = r"(?P<comment>[;'].*)?"  # a line holds no "\n", so `.` reaches the end of the line
# The words that open a condition: at the start of a line the lexer reads them as CONDKW (its
# priority is above WORD's) when the run of letters is exactly one of them.
CONDITION_WORDS = frozenset({"IF", "ELSEIF", "WHILE"})


def _operand(k: int) -> str:
    """`operand` without `~`: a number (signed or not: `negative`, `number_plus`) or a name."""
    return (rf"(?:(?P<sign{k}>[-+])?{_WS}(?P<digits{k}>{_NUMBER})"
            rf"|(?P<word{k}>{_WORD}){_WS}(?P<number{k}>{_NUMBER})?)")


# Parts of a command: a word, then optionally a sign, then optionally a number (`part`); then
# optionally `:` operands (`colon_args`: ARCP0:100:30000, CIRN0:2000).
_PART = rf"{_WORD}{_WS}(?:[-+]{_WS})?(?:{_NUMBER}{_WS})?"
PART = re.compile(rf"({_WORD}){_WS}(?:([-+]){_WS})?({_NUMBER})?")
_COLON_OPERAND = rf":{_WS}{_operand(0)}"
COLON_OPERAND = re.compile(_COLON_OPERAND)
COMMAND = re.compile(rf"{_WS}(?P<body>(?:{_PART})+)(?P<colon>(?:{_COLON_OPERAND}{_WS})+)?{_COMMENT}")
# A target without a sign, "=", one operand or two with one binary operator (not << or >>).
ASSIGNMENT = re.compile(rf"{_WS}(?P<word>{_WORD}){_WS}(?P<number>{_NUMBER})?{_WS}={_WS}{_operand(1)}"
                        rf"(?:{_WS}(?P<op>[-+*/%&|]){_WS}{_operand(2)})?{_WS}{_COMMENT}")
# IF/ELSEIF/WHILE and one comparison of two operands. `<` and `>` before a second `<`/`>` would be
# a shift operator, and before `=` the longer terminal.
CONDITIONAL = re.compile(rf"{_WS}(?P<keyword>{_WORD}){_WS}{_operand(1)}{_WS}(?P<op><=|>=|!=|<(?!<)|>(?!>)|=)"
                         rf"{_WS}{_operand(2)}{_WS}{_COMMENT}")
EMPTY = re.compile(rf"{_WS}{_COMMENT}")


class LineReader:
    """Makes the syntax nodes of the lines of one text (positions are those of the whole file)."""

    def __init__(self, path: str) -> None:
        self.path = path

    def read(self, text: str, number: int, start: int) -> st.Line | None:
        """The node of line `number` (its `text` starts at offset `start`), or None when the line
        has none of the shapes read here."""
        # A first word that opens a condition is read as IF/ELSEIF/WHILE by the lexer, never as a
        # command or the target of an assignment.
        found = COMMAND.fullmatch(text)
        if found is not None and PART.match(text, found.start("body")).group(1).upper() not in CONDITION_WORDS:
            return self.line(number, self.command(text, number, start, found), text, start, found)
        found = ASSIGNMENT.fullmatch(text)
        if found is not None and found.group("word").upper() not in CONDITION_WORDS:
            return self.line(number, self.assignment(number, start, found), text, start, found)
        found = CONDITIONAL.fullmatch(text)
        if found is not None and found.group("keyword").upper() in CONDITION_WORDS:
            return self.line(number, self.conditional(number, start, found), text, start, found)
        found = EMPTY.fullmatch(text)
        if found is not None:
            return self.line(number, None, text, start, found)
        return None

    def span(self, number: int, start: int, begin: int, end: int) -> Span:
        """The span of the characters `begin`..`end` of line `number` (which starts at `start`)."""
        return Span(self.path, number, begin + 1, number, end + 1, start + begin, start + end)

    def line(self, number: int, statement: st.Statement | None, text: str, start: int, found: re.Match) -> st.Line:
        begin = found.start("comment")
        if begin < 0:
            return st.Line(number, statement)
        end = found.end("comment")
        return st.Line(number, statement, st.Comment(text[begin:end], self.span(number, start, begin, end)))

    def command(self, text: str, number: int, start: int, found: re.Match) -> st.Command:
        parts = []
        span = self.span
        first = last = 0
        for part in PART.finditer(text, found.start("body"), found.end("body")):
            begin, last = part.span(1)
            word = st.Part(part.group(1), span(number, start, begin, last))
            sign = part.start(2)
            if sign >= 0:
                last = sign + 1
                word.sign, word.sign_span = text[sign], span(number, start, sign, last)
            digits = part.start(3)
            if digits >= 0:
                last = part.end(3)
                word.number, word.number_span = text[digits:last], span(number, start, digits, last)
            if not parts:
                first = begin
            parts.append(word)
        colon = []
        if found.start("colon") >= 0:
            operand = self.operand
            colon = [operand(number, start, item, 0)
                     for item in COLON_OPERAND.finditer(text, found.start("colon"), found.end("colon"))]
            last = colon[-1].span.end - start
        return st.Command(parts, colon, span(number, start, first, last))

    def part(self, number: int, start: int, found: re.Match, word: str, digits: str) -> st.Part:
        """A word with the number glued to it, if any (groups `word` and `digits` of the match)."""
        begin, end = found.span(word)
        part = st.Part(found.group(word), self.span(number, start, begin, end))
        begin, end = found.span(digits)
        if begin >= 0:
            part.number, part.number_span = found.group(digits), self.span(number, start, begin, end)
        return part

    def operand(self, number: int, start: int, found: re.Match, k: int) -> st.Node:
        """The operand `k` of a match, as `Builder.number`, `negative`, `number_plus` or `ref`."""
        begin, end = found.span(f"digits{k}")
        if begin < 0:
            return st.Ref(self.part(number, start, found, f"word{k}", f"number{k}"))
        digits = found.group(f"digits{k}")
        sign = found.start(f"sign{k}")
        if sign < 0:
            return st.Number(digits, self.span(number, start, begin, end))
        text = "-" + digits if found.group(f"sign{k}") == "-" else digits
        return st.Number(text, self.span(number, start, sign, end))

    def assignment(self, number: int, start: int, found: re.Match) -> st.Assignment:
        target = self.part(number, start, found, "word", "number")
        value = self.operand(number, start, found, 1)
        if found.start("op") >= 0:
            right = self.operand(number, start, found, 2)
            value = st.Binary(found.group("op"), value, right, value.span.to(right.span))
        return st.Assignment(target, value, target.span.to(value.span))

    def conditional(self, number: int, start: int, found: re.Match) -> st.Conditional:
        begin, end = found.span("keyword")
        keyword = self.span(number, start, begin, end)
        left = self.operand(number, start, found, 1)
        right = self.operand(number, start, found, 2)
        span = left.span.to(right.span)
        condition = st.Condition(st.Comparison(found.group("op"), left, right, span), span)
        return st.Conditional(found.group("keyword").upper(), keyword, condition, keyword.to(span))


def parse_lines(source: SourceFile, parser: Lark, builder: recovery.PositionedBuilder,
                on_error: Callable[[int, str, LarkError], object]) -> list:
    """The line nodes of `source`, numbered, as `recovery.parse_lines` makes them: the lines of the
    shapes above read here, each run of other lines parsed by `parser` (with `builder`, positioned
    where the run stands), and line by line with `on_error` for a bad line when that fails."""
    text = source.text
    texts = text.split("\n")
    if texts[-1] == "":
        texts.pop()  # the empty remainder after the final newline is no line
    reader = LineReader(source.path)
    read = reader.read
    out: list = []
    start = 0
    pending: list[int] = []  # 0-based indices of a run of lines left to the parser
    starts: list[int] = []
    for index, line_text in enumerate(texts):
        line = read(line_text, index + 1, start)
        if line is None:
            pending.append(index)
            starts.append(start)
            out.append(None)
        else:
            if pending:
                _parse_run(source, texts, pending, starts, parser, builder, on_error, out)
                pending, starts = [], []
            out.append(line)
        start += len(line_text) + 1
    if pending:
        _parse_run(source, texts, pending, starts, parser, builder, on_error, out)
    return out


def _parse_run(source: SourceFile, texts: list[str], run: list[int], starts: list[int], parser: Lark,
               builder: recovery.PositionedBuilder, on_error: Callable, out: list) -> None:
    """Parse the consecutive lines `run` (0-based, starting at the offsets `starts`) in one call,
    or one by one with recovery when that call fails; put their nodes in `out`."""
    builder.path = source.path
    first = run[0]
    try:
        builder.line_delta, builder.offset_delta = first, starts[0]
        try:
            lines = parser.parse("\n".join(texts[first:run[-1] + 1]) + "\n", start="start")
        except LarkError:
            lines = None
        if lines is not None and len(lines) == len(run):
            for index, line in zip(run, lines):
                line.number = index + 1
                out[index] = line
            return
        for index, begin in zip(run, starts):
            number = index + 1
            builder.line_delta, builder.offset_delta = index, begin
            try:
                line = parser.parse(texts[index] + "\n", start="line")
            except LarkError as exc:
                line = on_error(number, texts[index], exc)
            line.number = number
            out[index] = line
    finally:
        builder.line_delta = builder.offset_delta = 0
