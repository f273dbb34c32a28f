"""The fast paths of the X150 reader give what the slow ones give (docs/PERFORMANCE.md).

- The line scanner (one regular expression of the grammar's terminals) cuts a text into exactly
  the tokens, comments and lines that the Lark parser of grammars/x150.lark finds, and refuses
  exactly the texts that parser rejects (those go through the parser's per-line recovery).
- The catalog's remembered longest match is the longest match.
"""

from __future__ import annotations

from hypothesis import given, settings
from hypothesis import strategies as st

from mcc.compiler.x150 import catalog as cat
from mcc.compiler.x150 import parser

# Characters that matter to the grammar: delimiters, quotes, parentheses, comments, characters no
# terminal matches (form feed, CR, vertical tab, a non-ASCII space), and command text.
ALPHABET = ' \t\n;"()\x0c\x0b\r\u00a0_=,+-.' + "1234567890" + "ADGHIKLMNOPRSTVXabdgr" + "é"


def lark_lines(text: str) -> list | None:
    """What the Lark parser (with the parser's own callbacks) reads, in the scanner's form."""
    lark, collector = parser._parser()
    collector.line_delta = 0
    try:
        raw = lark.parse(text, start="start")
    except Exception:  # noqa: BLE001 - any rejection: the scanner must refuse the text too
        return None
    return [(number, [(str(t), t.start_pos) for t in tokens],
             (str(comment), comment.start_pos, comment.end_pos) if comment is not None else None)
            for number, tokens, comment in raw]


@settings(max_examples=400, deadline=None)
@given(st.text(alphabet=ALPHABET, max_size=80))
def test_the_scanner_reads_what_the_grammar_reads(body: str) -> None:
    text = body if body.endswith("\n") or not body else body + "\n"
    assert parser._scan(text) == lark_lines(text)


def test_the_scanner_on_the_manuals_forms() -> None:
    text = '1A10 1V5 ; set up\nDTXT"DEMO PROGRAM" IF(VAR1>5 AND IN_XX1) 1D(VAR5)\n\n1"2XR1"\n'
    lines = parser._scan(text)
    assert lines == lark_lines(text)
    assert [t for t, _ in lines[1][1]] == ['DTXT"DEMO PROGRAM"', "IF(VAR1>5 AND IN_XX1)", "1D(VAR5)"]
    assert lines[0][2] == ("; set up", 9, 17)
    assert parser._scan('1DTXT"OPEN\n') is None  # an unterminated quote: the parser reports the line


def longest_match(catalog: cat.X150Catalog, text: str, start: int) -> cat.Command | None:
    """The definition: the longest catalog mnemonic the text begins with, case-insensitively."""
    rest = text[start:].upper()
    found = [name for name in catalog.commands if rest.startswith(name)]
    return catalog.commands[max(found, key=len)] if found else None


@settings(max_examples=300, deadline=None)
@given(st.text(alphabet="ABCDEFGHIKLMNOPQRSTUVWXYZabcdehilnoprstvx+-\"#_0123(", max_size=9), st.integers(0, 3))
def test_the_remembered_match_is_the_longest_match(text: str, start: int) -> None:
    catalog = cat.load()
    assert catalog.match(text, start) is longest_match(catalog, text, start)
    assert catalog.match(text, start) is longest_match(catalog, text, start)  # asked again: remembered
