"""Parsing with recovery at line ends, shared by the line-oriented frontends.

The common case (a file without syntax errors) is one LALR pass over the whole text, with the
syntax tree built by the parser's callbacks. When that pass fails the text is parsed again one
line at a time with the grammar's `line` start symbol, so each bad line costs one diagnostic and
every other line is still checked. The builder shifts token positions by the line's place in the
file (`line_delta`, `offset_delta`), so spans stay file-relative in both modes.
"""

from __future__ import annotations

from types import ModuleType
from typing import Callable

from mcc.compiler.span import SourceFile, Span
from mcc.grammars.lark_runtime import Lark, LarkError, Token, Transformer, UnexpectedInput, UnexpectedToken, load


class PositionedBuilder(Transformer):
    """Base of the parsers' tree builders: token spans shifted by the place of the line being
    parsed, so they are file-relative when one line is parsed on its own."""

    def __init__(self) -> None:
        super().__init__(visit_tokens=False)
        self.path = ""
        self.line_delta = 0
        self.offset_delta = 0

    def span(self, tok: Token) -> Span:
        return Span(self.path, tok.line + self.line_delta, tok.column, tok.end_line + self.line_delta,
                    tok.end_column, tok.start_pos + self.offset_delta, tok.end_pos + self.offset_delta)

    def start(self, children):
        return children


def lalr_parser(tables: ModuleType, builder: Transformer) -> Lark:
    """The LALR parser of a line grammar, its syntax tree built by the parser's callbacks (starts
    "start" and "line", for recovery). `tables` is the grammar's generated module
    (`mcc.grammars.<name>_tables`, grammars/generate.py): loading it costs a fraction of importing
    the `lark` package and building the parser from a cache (decision 0023)."""
    return load(tables.DATA, tables.MEMO, transformer=builder)


def bare_parser(grammar: str):
    """The grammar's LALR parser by the `lark` package, with the contextual lexer and Lark's own
    tree, no callbacks: the baseline the benchmarks compare a check against (docs/PERFORMANCE.md).
    The check never uses it, so `lark` is imported only here."""
    from lark import Lark as LarkPackage

    return LarkPackage(grammar, parser="lalr", lexer="contextual")


def with_final_newline(text: str) -> str:
    return text if text.endswith("\n") or not text else text + "\n"


def parse_lines(source: SourceFile, parser: Lark, builder: PositionedBuilder,
                on_error: Callable[[int, str, LarkError], object]) -> list:
    """The line nodes of `source`, numbered; `on_error(number, text, exc)` reports a bad line
    and returns the node that stands for it."""
    builder.path = source.path
    builder.line_delta = builder.offset_delta = 0
    try:
        lines = parser.parse(with_final_newline(source.text), start="start")
    except LarkError:
        lines = None
    if lines is not None:
        for number, line in enumerate(lines, 1):  # one line node per physical line, in order
            line.number = number
        return lines
    out = []
    starts = source.line_starts
    try:
        for number in range(1, source.line_count + 1):
            text = source.line_text(number)
            if number == source.line_count and not text:
                break  # the empty remainder after the final newline
            builder.line_delta = number - 1
            builder.offset_delta = starts[number - 1]
            try:
                line = parser.parse(text + "\n", start="line")
            except LarkError as exc:
                line = on_error(number, text, exc)
            line.number = number
            out.append(line)
    finally:
        builder.line_delta = builder.offset_delta = 0
    return out


def error_span(source: SourceFile, number: int, text: str, exc: LarkError) -> Span:
    """Where a line's syntax error is: the offending character, or the end of an unfinished line."""
    if not isinstance(exc, UnexpectedInput):
        return source.line_span(number)
    column = getattr(exc, "column", 1) or 1
    if isinstance(exc, UnexpectedToken) and exc.token.type in ("_NL", "$END"):
        column = len(text.rstrip()) + 1
    column = max(1, min(column, len(text) + 1))
    start = source.line_starts[number - 1] + column - 1
    width = 1 if column <= len(text) else 0
    return Span(source.path, number, column, number, column + width, start, start + width)
