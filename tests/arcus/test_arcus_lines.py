"""The Arcus line reader (compiler/arcus/lines.py) makes what the LALR parser makes.

The parser reads a line the reader leaves to it; every line the reader reads itself must give the
node the parser's callbacks give, with the same spans, and a whole text the same lines and
diagnostics as the parser alone (`recovery.parse_lines`, the path before the reader).
"""

from __future__ import annotations

from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as hs

from mcc.compiler import recovery
from mcc.compiler.arcus import lines, parser
from mcc.compiler.arcus import syntax as st
from mcc.compiler.diagnostics import Diagnostics
from mcc.compiler.span import SourceFile, Span

# Pieces of lines near the edges of the shapes the reader knows: words that open conditions or
# join them (in either case, glued to more letters or not), every operator and comparison, signs,
# `~`, `:`, comments of both kinds, blanks, and characters no terminal matches.
PIECES = ["X", "Y", "V", "DI", "DO", "HSPD", "GOSUB", "END", "ENDIF", "ELSE", "JOGX", "ABS", "IF", "if",
          "ELSEIF", "ElseIf", "WHILE", "IFX", "WHILEV", "AND", "OR", "and", "ANDY", "ORX", "0", "1", "7", "25",
          "1000", "007", "+", "-", "*", "/", "%", "&", "|", "<<", ">>", "<", ">", "<=", ">=", "!=", "=", "==",
          "~", ":", "!", " ", "  ", "\t", ";note", "; x=1", "'old", ".", "(", "é"]


def lark_line(text: str, number: int = 1, start: int = 0):
    """The parser's node for one line placed at `number` and offset `start`, or None when it rejects it."""
    lark, builder = parser._parser()
    builder.path = "t.prg"
    builder.line_delta, builder.offset_delta = number - 1, start
    try:
        line = lark.parse(text + "\n", start="line")
    except Exception:  # noqa: BLE001 - any rejection
        return None
    finally:
        builder.line_delta = builder.offset_delta = 0
    line.number = number
    return line


def parse_both(text: str):
    """(lines, diagnostics) of the parser with the reader, and of the parser alone."""
    results = []
    for parse_lines in (lines.parse_lines, recovery.parse_lines):
        lark, builder = parser._parser()
        diags = Diagnostics()
        source = SourceFile("t.prg", text)

        def bad_line(number, line_text, exc):
            diags.add("A001", recovery.error_span(source, number, line_text, exc), parser.describe_error(exc))
            return st.Line(number, error=True, span=source.line_span(number))

        found = parse_lines(source, lark, builder, bad_line)
        results.append((found, [(d.code, d.message, d.span) for d in diags.items]))
    return results


@settings(max_examples=1500, deadline=None)
@given(hs.lists(hs.sampled_from(PIECES), max_size=9), hs.integers(1, 40), hs.integers(0, 500))
def test_a_line_the_reader_reads_is_the_line_the_parser_reads(pieces: list[str], number: int, start: int) -> None:
    text = "".join(pieces)
    read = lines.LineReader("t.prg").read(text, number, start)
    if read is not None:
        assert read == lark_line(text, number, start)


@settings(max_examples=300, deadline=None)
@given(hs.lists(hs.lists(hs.sampled_from(PIECES), max_size=7).map("".join), max_size=8),
       hs.sampled_from(["", "\n"]))
def test_a_text_gives_the_lines_and_diagnostics_of_the_parser_alone(texts: list[str], end: str) -> None:
    text = "\n".join(texts) + end
    with_reader, alone = parse_both(text)
    assert with_reader == alone


ROOT = Path(__file__).resolve().parents[2]
PROGRAMS = sorted([*ROOT.glob("samples/arcus/*.prg"), *ROOT.glob("tests/golden/arcus/*/*.prg")])


@pytest.mark.parametrize("path", PROGRAMS, ids=lambda p: f"{p.parent.name}/{p.name}")
def test_the_programs_and_their_mutations_read_as_by_the_parser_alone(path: Path) -> None:
    text = path.read_text(encoding="utf-8")
    texts = [text, text.rstrip("\n")]
    rows = text.split("\n")
    for k in range(0, len(rows), 3):  # a line deleted, a line doubled
        texts += ["\n".join(rows[:k] + rows[k + 1:]), "\n".join(rows[:k + 1] + rows[k:])]
    for variant in texts:
        with_reader, alone = parse_both(variant)
        assert with_reader == alone


def test_the_common_shapes_are_read_without_the_parser() -> None:
    reader = lines.LineReader("t.prg")
    for text in ["X1000Y-2000 ;move", "JOGX+", "GOSUB 1", "ENDIF", "V1=V2+1", "HSPD = 20000", "DO1=1 'set",
                 "V3=-5", "V3=+5", "V1=V2--3", "IF DI1=1", "elseif V2>=7", "WHILE V3 < 5", "IF1=2", "", "  ",
                 "; only a comment", "ARCP0:100:30000", "CIRN 0 : -2000 ;c", "ARCN V1:V2:+90000"]:
        found = reader.read(text, 3, 40)
        assert found is not None, text
        assert found == lark_line(text, 3, 40), text
    line = reader.read("  X1000Y-2000 ;move", 3, 40)
    assert line.statement.span == Span("t.prg", 3, 3, 3, 14, 42, 53)
    assert [p.key for p in line.statement.parts] == ["X1000", "Y-2000"]
    assert line.comment.text == ";move"
    assert reader.read("IF1=2", 1, 0).statement.keyword == "IF"
    arc = reader.read("ARCP0:100:-30000 ;arc", 1, 0).statement
    assert [n.text for n in arc.colon] == ["100", "-30000"]
    assert arc.span == Span("t.prg", 1, 1, 1, 17, 0, 16)


def test_other_lines_are_left_to_the_parser() -> None:
    reader = lines.LineReader("t.prg")
    for text in ["ARCP0:~1", "V1=~V2", "V1=V2<<2", "IF V1=1 AND V2=2", "V1=V2+V3+V4", "IF V1=V2=V3",
                 "IF V1+1=2", "IF", "WHILE", "X1000 5", "V1=(V2)", "IFX", "ELSEIF"]:
        assert reader.read(text, 1, 0) is None or text == "IFX", text
    assert reader.read("IFX", 1, 0) == lark_line("IFX")  # a command named IFX: not a condition


def test_the_grammar_still_has_the_terminals_the_reader_assumes() -> None:
    lark, _ = parser._parser()
    terminals = {t.name: t.pattern.to_regexp() for t in lark.terminals}
    assert terminals["WORD"] == lines.WORD_PATTERN
    assert terminals["NUMBER"] == lines.NUMBER_PATTERN
    assert terminals["COMMENT"] == lines.COMMENT_PATTERN
    ignored = [terminals[name] for name in lark.lexer_conf.ignore]
    assert ignored == [lines.IGNORED_PATTERN]
    assert {name: terminals[name] for name in ("CONDKW", "LOGIC")} == {
        "CONDKW": "(?i:ELSEIF|IF|WHILE)(?![A-Za-z])", "LOGIC": "(?i:AND|OR)(?![A-Za-z0-9])"}
