"""The Arcus formatter: layout, and the two properties (same IR, idempotent) over every sample and
over generated programs."""

from __future__ import annotations

from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from conftest import sample_files
from mcc.compiler import driver
from mcc.compiler.arcus.format import format_text
from mcc.compiler.ir_compare import differences


def assert_same_meaning(before: str, after: str) -> None:
    old = driver.check_file("f.prg", "arcus", text=before)
    new = driver.check_file("f.prg", "arcus", text=after)
    assert differences(old.analysis.module, new.analysis.module) == []
    assert sorted(d.code for d in old.diagnostics) == sorted(d.code for d in new.diagnostics)


def test_layout() -> None:
    text = ("hspd = 20000\nwhile v1 != 2\nif di1 = 1 ;on\nx1000 y-200\nelseif v2 < 3\n   gosub   1\nelse\n"
            "arcp 0 : 100 : 30000\nendif\n\n\nv1 = v1 + 1   ; count\nendwhile\nend\nsub 1\nxv4\nwaitx\nendsub\n")
    assert format_text(text) == ("HSPD=20000\nWHILE V1!=2\n" + "  IF DI1=1".ljust(24) + ";on\n    X1000Y-200\n"
                                 "  ELSEIF V2<3\n    GOSUB 1\n  ELSE\n    ARCP0:100:30000\n  ENDIF\n\n"
                                 + "  V1=V1+1".ljust(24) + "; count\nENDWHILE\nEND\nSUB 1\n  XV4\n  WAITX\nENDSUB\n")


def test_comments_before_a_closer_take_the_closer_indentation() -> None:
    assert format_text("IF V1=1\nDO1=1\n; done\nENDIF\n") == "IF V1=1\n  DO1=1\n; done\nENDIF\n"


def test_bad_lines_are_kept_and_structure_errors_do_not_break_the_layout() -> None:
    assert format_text("ENDIF\n  X1000 $$\nIF V1=1\n") == "ENDIF\n  X1000 $$\nIF V1=1\n"


def test_words_are_never_run_together() -> None:
    out = format_text("ABORT STOP\n")
    assert out == "ABORT STOP\n"


@pytest.mark.parametrize("path", sample_files("arcus"), ids=lambda p: p.name)
def test_samples_keep_their_meaning(path: Path) -> None:
    text = path.read_text(encoding="utf-8")
    once = format_text(text)
    assert_same_meaning(text, once)
    assert format_text(once) == once


WORDS = ["X", "Y", "Z", "U"]
REFS = ["V1", "V2", "v10", "PX", "EY", "DI", "DI3", "DO", "MSTX", "TR", "ACC"]
OPS = ["+", "-", "*", "/", "%", "&", "|", "<<", ">>"]
CMPS = ["=", "!=", "<", "<=", ">", ">="]


def sp(draw) -> str:
    return draw(st.sampled_from(["", " ", "  "]))


@st.composite
def operand(draw) -> str:
    kind = draw(st.integers(0, 3))
    if kind == 0:
        return str(draw(st.integers(0, 99999)))
    if kind == 1:
        return "-" + str(draw(st.integers(1, 999)))
    if kind == 2:
        return "~" + draw(st.sampled_from(REFS))
    return draw(st.sampled_from(REFS))


@st.composite
def expression(draw) -> str:
    out = draw(operand())
    for _ in range(draw(st.integers(0, 2))):
        out += sp(draw) + draw(st.sampled_from(OPS)) + sp(draw) + draw(operand())
    return out


@st.composite
def statement(draw) -> str:
    kind = draw(st.integers(0, 11))
    if kind == 0:
        axes = draw(st.lists(st.sampled_from(WORDS), min_size=1, max_size=3, unique=True))
        return sp(draw).join(f"{a}{draw(st.sampled_from(['', '-']))}{draw(st.integers(0, 5000))}" for a in axes)
    if kind == 1:
        return f"V{draw(st.integers(0, 70))}{sp(draw)}={sp(draw)}{draw(expression())}"
    if kind == 2:
        keyword = draw(st.sampled_from(["IF", "ELSEIF", "WHILE", "if", "While"]))
        cond = draw(operand()) + sp(draw) + draw(st.sampled_from(CMPS)) + sp(draw) + draw(operand())
        if draw(st.integers(0, 5)) == 0:
            cond += " AND V1=1"
        return f"{keyword} {cond}"
    if kind == 3:
        return draw(st.sampled_from(["ELSE", "ENDIF", "ENDWHILE", "END", "ENDSUB", "endif", "ABS", "INC"]))
    if kind == 4:
        return f"{draw(st.sampled_from(['GOSUB', 'SUB', 'gosub']))}{sp(draw) or ' '}{draw(st.integers(0, 33))}"
    if kind == 5:
        return f"{draw(st.sampled_from(['HSPD', 'LSPDX', 'ACCY', 'DELAY', 'DO3', 'EO', 'TR']))}{sp(draw)}={sp(draw)}" \
               f"{draw(st.sampled_from(['100', 'V2', '5000']))}"
    if kind == 6:
        return draw(st.sampled_from(["JOGX+", "jogy-", "STOP", "STOPZ", "ABORT", "WAITX", "HOMEU+", "ZHOMEX-",
                                     "SYNXO", "ECLEARY"]))
    if kind == 7:
        return f"{draw(st.sampled_from(['ARCP', 'ARCN', 'CIRP']))}{draw(st.integers(0, 99))}:{draw(st.integers(0, 99))}" \
               + draw(st.sampled_from(["", ":9000"]))
    if kind == 8:
        return draw(st.sampled_from(["X1000 $", "V1=", "IF", "@@", "X1000 Y", "SSPDMX=9"]))
    if kind == 9:
        return f"{draw(st.sampled_from(WORDS))}V{draw(st.integers(0, 9))}"
    if kind == 10:
        return f"SSPD{draw(st.sampled_from(WORDS))}={draw(st.integers(0, 90000))}"
    return f"SCV{draw(st.sampled_from(WORDS))}={draw(st.integers(0, 1))}"


@st.composite
def program(draw) -> str:
    lines = []
    for _ in range(draw(st.integers(0, 25))):
        indent = draw(st.sampled_from(["", " ", "\t", "    "]))
        kind = draw(st.integers(0, 8))
        if kind == 0:
            lines.append("")
        elif kind == 1:
            lines.append(indent + draw(st.sampled_from([";", "'"])) + draw(st.text(st.sampled_from("ab ;'*"), max_size=8)))
        else:
            line = indent + draw(statement())
            if draw(st.booleans()):
                line += draw(st.sampled_from(["", " ", "   "])) + draw(st.sampled_from(["; note", ";***x", "' dxf"]))
            lines.append(line + draw(st.sampled_from(["", " "])))
    return "\n".join(lines) + draw(st.sampled_from(["", "\n"]))


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
