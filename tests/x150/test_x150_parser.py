"""The syntax tree and the recovery at line ends."""

from __future__ import annotations

from mcc.compiler.diagnostics import Diagnostics
from mcc.compiler.span import SourceFile
from mcc.compiler.x150 import parser

from x150_helpers import check, codes


def parse(text: str):
    diags = Diagnostics()
    return parser.parse(SourceFile("t.x150", text), diags), diags


def test_lines_commands_and_comments():
    tree, diags = parse("XD1 ;Defines sequence #1\nA20\t;Sets acceleration\n\nXT\n")
    assert not diags
    assert [len(line.commands) for line in tree.lines] == [1, 1, 0, 1]
    assert tree.lines[0].comment.text == ";Defines sequence #1"
    assert tree.lines[0].comment.span.column == 5


def test_several_commands_on_a_line():
    tree, _ = parse("XE1 1SV\n")
    assert [c.text for c in tree.lines[0].commands] == ["XE1", "1SV"]


def test_spaces_inside_conditions_and_quotes():
    tree, diags = parse('IF(VAR1>5 AND IN_XXXX11) DTXT"DIGIPLAN DEMO"\n')
    assert not diags
    assert [c.mnemonic for c in tree.lines[0].commands] == ["IF", "DTXT"]


def test_three_bad_lines_three_diagnostics_the_rest_checked():
    text = 'DTXT"OPEN\n1A10\nIF(VAR1>5\n1V250\n1"NO END\n1G\n'
    result = check(text)
    syntax = [(d.code, d.span.line) for d in result.diagnostics if d.kind.value == "syntax"]
    assert syntax == [("X001", 1), ("X001", 3), ("X001", 5)]
    assert ("X122", 4) in [(d.code, d.span.line) for d in result.diagnostics]


def test_commands_before_a_bad_token_are_kept():
    tree, diags = parse('1XE1 1XD1 DTXT"OOPS\n1XT\n')
    assert [c.text for c in tree.lines[0].commands] == ["1XE1", "1XD1"]
    assert [d.code for d in diags] == ["X001"]


def test_crlf_and_no_final_newline():
    assert codes("1A10\r\n1V5\r\n1G") == []


def test_odd_whitespace_is_an_error_not_a_crash():
    result = check("1A10\u00a01V5\n\x0b\n")
    assert {d.code for d in result.diagnostics} == {"X001"}


def test_space_before_the_argument_is_rejoined_with_a_fix():
    result = check("1OUTL XX10X1\nIF (IN_XXX1 OR VAR1>20)\nNIF\n1GOTO 2\nVAR2 =RSIN\n")
    x103 = [d for d in result.diagnostics if d.code == "X103"]
    assert len(x103) == 4
    assert all(d.fix and d.fix.edits[0].text == "" for d in x103)
    tree = result.analysis.tree
    assert [c.text for c in tree.commands()] == ["1OUTLXX10X1", "IF(IN_XXX1 OR VAR1>20)", "NIF", "1GOTO2", "VAR2=RSIN"]


def test_no_rejoin_when_the_next_word_is_a_command():
    tree, diags = parse("1OUTL 1A10\n")
    assert [c.text for c in tree.commands()] == ["1OUTL", "1A10"]
    assert not diags


def test_every_node_has_a_span():
    tree, _ = parse("1VAR3=VAR1-VAR2 IF(VAR1>5 AND IN_1) 1DPC208 1TX1,0,3,A=\n")
    for command in tree.commands():
        assert command.span and command.mnemonic_span and command.arg.span
