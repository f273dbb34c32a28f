"""The MCode formatter: the canonical layout, comments kept, and two properties over every sample
and over generated programs — formatting never changes the IR, and formatting twice changes
nothing more than formatting once."""

from __future__ import annotations

import re
import textwrap
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from conftest import sample_files
from mcc.compiler import driver
from mcc.compiler.ir_compare import differences
from mcc.compiler.mcode.format import format_text

LENGTH_CODES = {"M109", "M110"}  # alignment may move a trailing comment; the checks measure it


def fmt(text: str) -> str:
    return format_text(textwrap.dedent(text).lstrip("\n"))


def assert_same_meaning(before: str, after: str, path: str = "f.mxt") -> None:
    old = driver.check_file(path, "mcode", text=before)
    new = driver.check_file(path, "mcode", text=after)
    assert differences(old.analysis.module, new.analysis.module) == []
    assert sorted(d.code for d in old.diagnostics if d.code not in LENGTH_CODES) == \
        sorted(d.code for d in new.diagnostics if d.code not in LENGTH_CODES)


# the canonical layout -------------------------------------------------------------------------

def test_case_spacing_and_indentation() -> None:
    assert fmt("""
        is = 1, 0 , 1
        pg 1
            lb G1
        ma   2000
          br G1 , i1 = 0
        R1 = R2 * 2
        f1 = cs  f2
        pr "Pos: " , p ;
        e
        pg
    """) == ("IS=1,0,1\nPG 1\nLB G1\n  MA 2000\n  BR G1,I1=0\n  R1=R2*2\n  F1=CS F2\n"
             "  PR \"Pos: \",P;\n  E\nPG\n")


def test_user_names_party_names_and_text_keep_their_spelling() -> None:
    assert fmt("""
        va Np = 0
        aPr "Mixed Case"
        *vm=1000
        pg 1
        lb k1
        ic Np
        br k1
        pg
    """) == 'VA Np=0\naPR "Mixed Case"\n*VM=1000\nPG 1\nLB k1\n  IC Np\n  BR k1\nPG\n'


def test_assignment_or_space_form_is_kept() -> None:
    assert fmt("O2 0\nO2 = 0\nTI 1, X1\nTi = 1, X1\n") == "O2 0\nO2=0\nTI 1,X1\nTI=1,X1\n"


def test_comments_are_kept_and_aligned_per_block() -> None:
    assert fmt("""
        ` Setup
        MS=256 ` microsteps
        VM=768000   ' fast

        PG 1
        LB G1   ` start
        ` the loop
        MA 100 `go
        E
        PG
    """) == ("` Setup\nMS=256                  ` microsteps\nVM=768000               ' fast\n\nPG 1\n"
             "LB G1                   ` start\n  ` the loop\n  MA 100                `go\n  E\nPG\n")


def test_long_code_moves_the_comment_column() -> None:
    out = fmt("""
        PR "a long text that is long",P ` one
        MA 1 ` two
    """)
    first, second = out.splitlines()
    assert first == 'PR "a long text that is long",P  ` one'
    assert second.index("`") == first.index("`")


def test_alignment_never_overflows_the_line_buffer() -> None:
    line = "MA 1 ` " + "x" * 55  # 62 characters: fits, but not at column 25
    assert fmt(line + "\n") == line + "\n"
    assert len(fmt("MA 1 `" + "x" * 40 + "\n").rstrip()) <= 64


def test_blank_lines_collapse_and_edges_are_trimmed() -> None:
    assert fmt("\n\n\nVA Q1\n\n\n\nPR Q1\n\n\n") == "VA Q1\n\nPR Q1\n"


def test_lines_with_syntax_errors_are_left_verbatim() -> None:
    text = "  ma (100   \nvm = 5\n"
    assert fmt(text) == "  ma (100   \nVM=5\n"


def test_comment_before_a_label_stays_at_column_zero_in_a_program() -> None:
    assert fmt("PG 1\n` [SUBROUTINES]\nLB K1\n  ` body\n  RT\n` trailing\nPG\n") == \
        "PG 1\n` [SUBROUTINES]\nLB K1\n  ` body\n  RT\n` trailing\nPG\n"


def test_canonical_operator() -> None:
    assert fmt("PG 1\nLB G1\nBR G1,I5 =< 20\nPG\n") == "PG 1\nLB G1\n  BR G1,I5<=20\nPG\n"


def test_samples_are_already_formatted() -> None:
    for path in sample_files("mcode"):
        text = path.read_text(encoding="utf-8")
        assert format_text(text, str(path)) == text, path.name


# properties -----------------------------------------------------------------------------------

@pytest.mark.parametrize("path", sample_files("mcode"), ids=lambda p: p.name)
def test_samples_keep_their_meaning_messed_up_and_formatted(path: Path) -> None:
    text = path.read_text(encoding="utf-8")
    messy = "\n".join("    " + re.sub(r"(?<=[a-z0-9])=(?=[a-z0-9-])", " = ", line.lower().replace(",", " , "))
                      if '"' not in line and "`" not in line and "'" not in line else line
                      for line in text.splitlines()) + "\n\n\n"
    assert_same_meaning(text, messy, str(path))
    formatted = format_text(messy, str(path))
    assert_same_meaning(text, formatted, str(path))
    assert format_text(formatted, str(path)) == formatted


NAMES = ["R1", "R2", "F1", "F2", "P", "C1", "I1", "Q1", "Np", "VM", "A"]
LABELS = ["G1", "K1", "X1", "k2"]
FUNCS = ["CS", "SQ", "AB"]
OPS = ["+", "-", "*", "/", "&", "|", "^"]
RELOPS = ["=", "<>", "<", "<=", ">", ">=", "=<"]


@st.composite
def spaced(draw, token: str) -> str:
    return draw(st.sampled_from(["", " ", "  "])) + token + draw(st.sampled_from(["", " "]))


@st.composite
def cased(draw, word: str) -> str:
    return "".join(c.lower() if draw(st.booleans()) else c for c in word)


@st.composite
def atom(draw) -> str:
    kind = draw(st.integers(0, 3))
    if kind == 0:
        return str(draw(st.integers(0, 100000)))
    if kind == 1:
        return "-" + str(draw(st.integers(1, 500)))
    if kind == 2:
        return f"{draw(st.sampled_from(FUNCS))} {draw(st.sampled_from(NAMES))}"
    return draw(cased(draw(st.sampled_from(NAMES))))


@st.composite
def expr(draw) -> str:
    out = draw(atom())
    for _ in range(draw(st.integers(0, 2))):
        out += draw(spaced(draw(st.sampled_from(OPS)))) + draw(atom())
    return out


@st.composite
def statement(draw) -> str:
    kind = draw(st.integers(0, 13))
    sep = draw(spaced("="))
    comma = draw(spaced(","))
    label = draw(st.sampled_from(LABELS))
    if kind == 0:
        return f"{draw(cased(draw(st.sampled_from(['MA', 'MR', 'SL']))))} {draw(expr())}"
    if kind == 1:
        return f"{draw(cased(draw(st.sampled_from(['R1', 'R3', 'F1', 'Q1', 'VM']))))}{sep}{draw(expr())}"
    if kind == 2:
        cond = draw(expr()) + draw(spaced(draw(st.sampled_from(RELOPS)))) + draw(expr())
        return f"{draw(cased(draw(st.sampled_from(['BR', 'CL']))))} {label}{comma}{cond}"
    if kind == 3:
        text = draw(st.text(st.sampled_from("abc XYZ:=,'`"), max_size=12))
        return f'PR "{text}"{comma}{draw(expr())}' + draw(st.sampled_from(["", ";", " ;"]))
    if kind == 4:
        return f"LB {label}"
    if kind == 5:
        return draw(st.sampled_from(["PG 1", "PG", "pg 100", "E", "RT", "H", "H 100", "S"]))
    if kind == 6:
        return f"VA {draw(st.sampled_from(['Q1', 'Np']))}" + draw(st.sampled_from(["", f"{sep}5"]))
    if kind == 7:
        return f"{draw(cased('IS'))}{sep}1{comma}0{comma}1"
    if kind == 8:
        return draw(st.sampled_from(["TI 1, X1", "TE = 1", "OE K1", "TP=100 , X1", "TA = 4, K1"]))
    if kind == 9:
        return draw(st.sampled_from(["*VM=1000", "aMR 100", "!PR P", "^MA 0", "bpr p"]))
    if kind == 10:
        return draw(st.sampled_from(["MA (1", 'PR "open', "R1=R2 ! R3", "MX 5", "PG1", "@@"]))
    if kind == 11:
        return f"{draw(cased('IC'))} Q1"
    if kind == 12:
        return f"PR \"a\" {draw(expr())}"
    return str(draw(st.integers(-100, 100)))


@st.composite
def program(draw) -> str:
    lines = []
    for _ in range(draw(st.integers(0, 25))):
        indent = draw(st.sampled_from(["", " ", "  ", "\t", "    "]))
        kind = draw(st.integers(0, 9))
        if kind == 0:
            lines.append("")
        elif kind == 1:
            lines.append(indent + draw(st.sampled_from(["`", "'"])) + draw(st.text(st.sampled_from("ab `'\""),
                                                                                   max_size=10)))
        else:
            line = indent + draw(statement())
            if draw(st.booleans()):
                line += draw(st.sampled_from(["", " ", "   "])) + draw(st.sampled_from(["` note", "'x", "` a'b"]))
            lines.append(line + draw(st.sampled_from(["", " ", "\t"])))
    return "\n".join(lines) + draw(st.sampled_from(["", "\n", "\n\n"]))


PROPERTY = settings(max_examples=300, deadline=None, suppress_health_check=[HealthCheck.too_slow])


@PROPERTY
@given(text=program())
def test_formatting_never_changes_the_ir(text: str) -> None:
    assert_same_meaning(text, format_text(text))


@PROPERTY
@given(text=program())
def test_formatting_is_idempotent(text: str) -> None:
    once = format_text(text)
    assert format_text(once) == once
