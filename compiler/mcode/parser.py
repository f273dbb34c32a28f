"""Parsing MCode text into the syntax tree, with recovery at line ends.

See `mcc.compiler.recovery`: one LALR pass over the whole file, and line by line when it fails,
so a file with three bad lines gets three diagnostics and every other line is still checked.
"""

from __future__ import annotations

from functools import lru_cache
from pathlib import Path

from mcc.grammars import mcode_tables
from mcc.grammars.lark_runtime import (Lark, LarkError, Token, UnexpectedCharacters, UnexpectedEOF, UnexpectedInput,
                                       UnexpectedToken)

from mcc.compiler import limits, recovery
from mcc.compiler.diagnostics import Diagnostics
from mcc.compiler.mcode import syntax as st
from mcc.compiler.span import SourceFile

GRAMMAR = Path(__file__).resolve().parent.parent.parent / "grammars" / "mcode.lark"

TOKEN_NAMES = {
    "WORD": "a name", "NUMBER": "a number", "STRING": "a string", "COMMENT": "a comment",
    "_NL": "the end of the line", "$END": "the end of the file", "COMMA": "','", "EQUAL": "'='",
    "BINOP": "an operator", "RELOP": "a comparison", "MINUS": "'-'",
    "PARTY_ALL": "'*'", "PARTY_QUEUED": "'^'", "PARTY_DEFAULT": "'!'",
}


class Builder(recovery.PositionedBuilder):
    """Builds `syntax` nodes from the parser's callbacks. Offsets shift positions when one line is
    parsed on its own (recovery mode)."""

    # lines and statements -------------------------------------------------------------------
    def line(self, children):
        line = st.Line(0)
        for child in children:
            if isinstance(child, st.Statement):
                line.statement = child
            elif isinstance(child, Token) and child.type == "COMMENT":
                line.comment = st.Comment(str(child), self.span(child))
        return line

    def _statement(self, children, form):
        party = ""
        if isinstance(children[0], str) and not isinstance(children[0], Token):
            party = children[0]
            children = children[1:]
        head_tok = children[0]
        head = st.Name(str(head_tok), self.span(head_tok))
        args = children[1] if len(children) > 1 else []
        end = args[-1].span if args else head.span
        return st.Statement(head, form, args, head.span.to(end), party)

    def bare(self, children):
        return self._statement(children, "bare")

    def assign(self, children):
        return self._statement(children, "assign")

    def command(self, children):
        return self._statement(children, "command")

    def command_nonl(self, children):
        stmt = self._statement(children, "command")
        stmt.suffix = ";"
        return stmt

    def number(self, children):
        return self._number_statement(children, negative=False)

    def neg_number(self, children):
        return self._number_statement(children, negative=True)

    def _number_statement(self, children, negative):
        party = ""
        if isinstance(children[0], str) and not isinstance(children[0], Token):
            party, children = children[0], children[1:]
        first = children[0]
        tok = children[-1]
        span = self.span(first).to(self.span(tok))
        head = st.Name("", span)
        value: st.Node = st.Number(str(tok), self.span(tok))
        if negative:
            value = st.Unary("-", value, span)
        return st.Statement(head, "number", [value], span, party)

    def party(self, children):
        return str(children[0])

    def args(self, children):
        return [self._value(child) for child in children]

    # values ------------------------------------------------------------------------------------
    def juxt(self, children):
        first = st.String(str(children[0])[1:-1], self.span(children[0]))
        second = self._value(children[1])
        return st.Juxtaposed(first, second, first.span.to(second.span))

    def _value(self, child):
        if isinstance(child, Token):  # a STRING standing alone as an item
            return st.String(str(child)[1:-1], self.span(child))
        return child

    def __default_token__(self, token):  # pragma: no cover - visit_tokens is off
        return token

    def compare(self, children):
        left, op, right = children
        return st.Comparison(str(op), self._value(left), self._value(right), left.span.to(right.span))

    def compare_eq(self, children):
        left, right = children
        return st.Comparison("=", left, right, left.span.to(right.span))

    def _binary(self, children):
        left, op, right = children
        return st.Binary(str(op), left, right, left.span.to(right.span))

    binary = xor = times = bang = _binary

    def minus(self, children):
        """`AB -12` is the function AB of -12 (spaced like a prefix operand), `R2-5` and `R2 - 5` are a
        subtraction. The grammar cannot tell them apart by tokens (no word is reserved for functions),
        so the spacing of a function name decides (docs/dialects/mcode.md)."""
        left, op, right = children
        op_span = self.span(op)
        if isinstance(left, st.Name) and left.key in function_names() and left.span.end < op_span.start \
                and op_span.end == right.span.start:
            operand = st.Unary("-", right, op_span.to(right.span))
            return st.FuncCall(left.key, operand, left.span.to(right.span))
        return self._binary(children)

    def neg(self, children):
        op, operand = children
        return st.Unary("-", operand, self.span(op).to(operand.span))

    def not_(self, children):
        op, operand = children
        return st.Unary("!", operand, self.span(op).to(operand.span))

    def func(self, children):
        name, operand = children
        return st.FuncCall(str(name).upper(), operand, self.span(name).to(operand.span))

    def num(self, children):
        return st.Number(str(children[0]), self.span(children[0]))

    def name(self, children):
        return st.Name(str(children[0]), self.span(children[0]))


@lru_cache(maxsize=1)
def function_names() -> frozenset[str]:
    from mcc.compiler.mcode import catalog

    return frozenset(catalog.load().functions)


@lru_cache(maxsize=1)
def _parser() -> tuple[Lark, Builder]:
    builder = Builder()
    parser = recovery.lalr_parser(mcode_tables, builder)
    return parser, builder


def bare_parser():
    """The same grammar with no callbacks, by the `lark` package: the baseline the benchmark
    compares against."""
    return recovery.bare_parser(GRAMMAR.read_text(encoding="utf-8"))


def describe_error(exc: UnexpectedInput) -> str:
    if isinstance(exc, UnexpectedCharacters):
        char = exc.char
        if char == '"':
            return "unterminated string: add the closing '\"' on the same line"
        shown = repr(char) if not char.isprintable() or char == " " else f"'{char}'"
        return f"unexpected character {shown}"
    if isinstance(exc, (UnexpectedToken, UnexpectedEOF)):
        tok = getattr(exc, "token", None)
        if tok is None or tok.type in ("$END", "_NL"):
            return "this statement is incomplete: a value or name is missing at the end of the line"
        expected = sorted({TOKEN_NAMES.get(t, f"'{t}'") for t in getattr(exc, "expected", ()) if t != "COMMENT"})
        found = f"'{tok}'" if tok.type not in TOKEN_NAMES else f"{TOKEN_NAMES[tok.type]} '{tok}'"
        hint = f" (expected {', '.join(expected[:6])})" if expected else ""
        return f"unexpected {found}{hint}"
    return str(exc).splitlines()[0]


def parse(source: SourceFile, diags: Diagnostics) -> st.SyntaxTree:
    parser, builder = _parser()

    def bad_line(number: int, text: str, exc: LarkError) -> st.Line:
        message = describe_error(exc) if isinstance(exc, UnexpectedInput) else str(exc).splitlines()[0]
        diags.add("M001", recovery.error_span(source, number, text, exc), message)
        return st.Line(number, error=True)

    text, refused = limits.readable(source, "`'", diags)
    lines = recovery.parse_lines(text, parser, builder, bad_line)
    limits.refuse_deep(source, lines, refused, diags)
    return st.SyntaxTree(source.path, lines)
