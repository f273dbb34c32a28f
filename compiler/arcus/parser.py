"""Parsing Arcus text into the syntax tree, with recovery at line ends.

The common case (a file without syntax errors) is one LALR pass with the tree built directly by
the parser's callbacks. When that pass fails, the file is parsed again line by line with the
`line` start symbol, so a file with three bad lines gets three diagnostics and every other line is
still checked. This is the scheme of compiler/mcode/parser.py.
"""

from __future__ import annotations

import re
from functools import lru_cache
from pathlib import Path

from mcc.grammars import arcus_tables
from mcc.grammars.lark_runtime import (Lark, LarkError, Token, UnexpectedCharacters, UnexpectedEOF, UnexpectedInput,
                                       UnexpectedToken)

from mcc.compiler.arcus import syntax as st
from mcc.compiler.arcus.lines import parse_lines
from mcc.compiler import limits, recovery
from mcc.compiler.diagnostics import Diagnostics
from mcc.compiler.span import SourceFile

GRAMMAR = Path(__file__).resolve().parent.parent.parent / "grammars" / "arcus.lark"

TOKEN_NAMES = {
    "WORD": "a keyword", "NUMBER": "a number", "COMMENT": "a comment", "_NL": "the end of the line",
    "$END": "the end of the file", "EQ": "'='", "CONDKW": "IF/ELSEIF/WHILE", "LOGIC": "AND/OR",
    "PLUS": "'+'", "MINUS": "'-'", "STAR": "'*'", "SLASH": "'/'", "PERCENT": "'%'", "AMP": "'&'",
    "PIPE": "'|'", "SHL": "'<<'", "SHR": "'>>'", "LE": "'<='", "GE": "'>='", "NE": "'!='", "LT": "'<'",
    "GT": "'>'", "TILDE": "'~'", "COLON": "':'",
}

# Binding strength of the binary operators. The language allows one operator per statement
# (L2675), so precedence only matters for the expressions mcc reports as errors; it follows C so
# that the IR keeps the meaning a reader expects.
OPENER = re.compile(r"\s*(ELSEIF|IF|WHILE)(?![A-Za-z])", re.IGNORECASE)
FLATTENED = re.compile(r"\b(ENDIF|ENDWHILE)\b", re.IGNORECASE)

PRECEDENCE = {"|": 1, "&": 2, "<<": 3, ">>": 3, "+": 4, "-": 4, "*": 5, "/": 5, "%": 5}


def _climb(operands: list, ops: list[str], position: list[int], min_prec: int):
    """Precedence climbing from operand `position[0]` (a one-item list the calls share). A function
    of its own, not a closure: a recursive closure refers to itself, a reference cycle per
    expression that only the garbage collector frees."""
    left = operands[position[0]]
    while position[0] < len(ops) and PRECEDENCE[ops[position[0]]] >= min_prec:
        op = ops[position[0]]
        position[0] += 1
        right = _climb(operands, ops, position, PRECEDENCE[op] + 1)
        left = st.Binary(op, left, right, left.span.to(right.span))
    return left


class Builder(recovery.PositionedBuilder):
    """Builds `syntax` nodes from the parser's callbacks. The deltas shift positions when one line
    is parsed on its own (recovery mode)."""

    # lines ---------------------------------------------------------------------------------------
    def line(self, children):
        line = st.Line(0)
        for child in children:
            if isinstance(child, Token):
                if child.type == "COMMENT":
                    line.comment = st.Comment(str(child), self.span(child))
            else:
                line.statement = child
        return line

    # statements ----------------------------------------------------------------------------------
    def command(self, children):
        parts = [c for c in children if isinstance(c, st.Part)]
        colon = next((c for c in children if isinstance(c, list)), [])
        end = colon[-1].span if colon else parts[-1].span
        return st.Command(parts, colon, parts[0].span.to(end))

    def colon_args(self, children):
        return [c for c in children if not isinstance(c, Token)]

    def part(self, children):
        word = children[0]
        part = st.Part(str(word), self.span(word))
        for tok in children[1:]:
            if tok.type == "NUMBER":
                part.number, part.number_span = str(tok), self.span(tok)
            else:
                part.sign, part.sign_span = str(tok), self.span(tok)
        return part

    def assignment(self, children):
        target, _, value = children
        return st.Assignment(target, value, target.span.to(value.span))

    def conditional(self, children):
        keyword, condition = children
        span = self.span(keyword)
        return st.Conditional(str(keyword).upper(), span, condition, span.to(condition.span))

    def condition(self, children):
        first = children[0]
        cond = st.Condition(first, first.span)
        for i in range(1, len(children) - 1, 2):
            cond.more.append((str(children[i]).upper(), children[i + 1]))
        cond.span = first.span.to(children[-1].span)
        return cond

    def comparison(self, children):
        left, op, right = children[0], children[1], children[2]
        comp = st.Comparison(str(op), left, right, left.span.to(right.span))
        for i in range(3, len(children) - 1, 2):
            comp.chained.append((str(children[i]), children[i + 1]))
        comp.span = left.span.to(children[-1].span)
        return comp

    def cmp_op(self, children):
        return children[0]

    def binop(self, children):
        return children[0]

    def expr(self, children):
        """Operands and operators in a row; folded by precedence climbing, left-associative."""
        operands = children[0::2]
        ops = [str(t) for t in children[1::2]]
        if not ops:
            return operands[0]
        return _climb(operands, ops, [0], 0)

    # operands ------------------------------------------------------------------------------------
    def number(self, children):
        return st.Number(str(children[0]), self.span(children[0]))

    def negative(self, children):
        sign, digits = children
        return st.Number("-" + str(digits), self.span(sign).to(self.span(digits)))

    def number_plus(self, children):
        sign, digits = children
        return st.Number(str(digits), self.span(sign).to(self.span(digits)))

    def bitnot(self, children):
        tilde, operand = children
        return st.Unary("~", operand, self.span(tilde).to(operand.span))

    def ref(self, children):
        part = st.Part(str(children[0]), self.span(children[0]))
        if len(children) > 1:
            part.number, part.number_span = str(children[1]), self.span(children[1])
        return st.Ref(part)


@lru_cache(maxsize=1)
def _parser() -> tuple[Lark, Builder]:
    builder = Builder()
    parser = recovery.lalr_parser(arcus_tables, builder)
    return parser, builder


def bare_parser():
    """The same grammar with no callbacks, by the `lark` package: the baseline the benchmark
    compares against."""
    return recovery.bare_parser(GRAMMAR.read_text(encoding="utf-8"))


def describe_error(exc: UnexpectedInput) -> str:
    if isinstance(exc, UnexpectedCharacters):
        char = exc.char
        shown = repr(char) if not char.isprintable() or char == " " else f"'{char}'"
        hint = ""
        if char in "()":
            hint = ": Arcus has no parentheses; compute one operation per line into a variable"
        elif char == ".":
            hint = ": Arcus numbers are whole numbers (angles in 1/1000 degree, ARC 45000 = 45 degrees)"
        elif char == '"':
            hint = ": the standalone language has no text strings"
        return f"unexpected character {shown}{hint}"
    if isinstance(exc, (UnexpectedToken, UnexpectedEOF)):
        tok = getattr(exc, "token", None)
        if tok is None or tok.type in ("$END", "_NL"):
            return "this statement is incomplete: a value is missing at the end of the line"
        if tok.type == "WORD" or tok.type == "CONDKW":
            return (f"unexpected '{tok}': one statement per line (put '{tok}' on its own line; "
                    "the manual's examples were flattened by the PDF conversion)")
        expected = sorted({TOKEN_NAMES.get(t, f"'{t}'") for t in getattr(exc, "expected", ()) if t != "COMMENT"})
        name = TOKEN_NAMES.get(tok.type, "")
        found = f"{name} '{tok}'" if name and name != f"'{tok}'" else f"'{tok}'"
        hint = f" (expected {', '.join(expected[:6])})" if expected else ""
        return f"unexpected {found}{hint}"
    return str(exc).splitlines()[0]


def parse(source: SourceFile, diags: Diagnostics) -> st.SyntaxTree:
    parser, builder = _parser()

    def bad_line(number: int, text: str, exc: LarkError) -> st.Line:
        if not isinstance(exc, UnexpectedInput):  # pragma: no cover - other parser failures
            diags.add("A001", source.line_span(number), str(exc).splitlines()[0])
            return st.Line(number, error=True)
        diags.add("A001", recovery.error_span(source, number, text, exc), describe_error(exc))
        line = st.Line(number, error=True, span=source.line_span(number))
        opener = OPENER.match(text)
        if opener and not FLATTENED.search(text):  # `IF V1=1 X1000 ENDIF` opens nothing
            line.keyword = opener.group(1).upper()
        return line

    text, refused = limits.readable(source, ";'", diags)
    lines = parse_lines(text, parser, builder, bad_line)
    limits.refuse_deep(source, lines, refused, diags)
    return st.SyntaxTree(source.path, lines)
