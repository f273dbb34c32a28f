"""The X150 formatter: layout, and the two properties (same IR, idempotent) over every sample and
over generated command streams."""

from __future__ import annotations

from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from conftest import sample_files
from mcc.compiler import driver
from mcc.compiler.ir_compare import differences
from mcc.compiler.x150.format import format_text

STYLE_CODES = {"X102", "X103"}  # lower case and a space inside a command: what the formatter fixes


def assert_same_meaning(before: str, after: str) -> None:
    old = driver.check_file("f.x150", "x150", text=before)
    new = driver.check_file("f.x150", "x150", text=after)
    assert differences(old.analysis.module, new.analysis.module) == []
    assert sorted(d.code for d in old.diagnostics if d.code not in STYLE_CODES) == \
        sorted(d.code for d in new.diagnostics if d.code not in STYLE_CODES)
    introduced = {d.code for d in new.diagnostics} - {d.code for d in old.diagnostics}
    assert not introduced & STYLE_CODES


def test_layout() -> None:
    text = '1xe1   1xd1 ;start\n\n\n  1a10\t1v5\n1if (var1>5 and in_x1)\n1dtxt"Mixed Case"\n1nif\n1XT\n'
    assert format_text(text) == ('1XE1 1XD1'.ljust(24) + ';start\n\n1A10 1V5\n1IF(VAR1>5 AND IN_X1)\n'
                                 '1DTXT"Mixed Case"\n1NIF\n1XT\n')


def test_transmitted_text_keeps_its_case() -> None:
    assert format_text("1tx7,1,0,Gap=\n") == "1TX7,1,0,Gap=\n"


@pytest.mark.parametrize("path", sample_files("x150"), ids=lambda p: p.name)
def test_samples_keep_their_meaning(path: Path) -> None:
    text = path.read_text(encoding="utf-8")
    once = format_text(text)
    assert_same_meaning(text, once)
    assert format_text(once) == once


COMMANDS = ["1A10", "a5", "1V5", "V0", "1D4000", "D-200", "1G", "g", "1MN", "MPA", "1MPI", "1MC", "1H", "H+",
            "1T0.5", "1L", "L3", "1N", "1IF(VAR1>5)", "if (in_x1 or VAR2=3)", "1ELSE", "1NIF", "WHILE(VAR1<4)",
            "NWHILE", "REPEAT", "UNTIL(IN_1)", "1XR2", "XG3", "1XRT", "1VAR1=VAR2+3*VAR4", "var3=pos",
            "1TRE_X1", "1SB", "1S", "1ST1", "1ST0", "1OFF", "1ON", "1WHEN(IN_1)", "1XWHEN2", "1XP1", "1SV",
            '1DTXT"Hi you"', "1TX7,1,0,Gap=", "1OUTL XX10X1", "1IN5M", "1BY", "2IO10X", "1XR(VAR1)", "@@", "1Q#",
            '"open', "1XE1 1XD1", "1XT", "1XE2 1XD2", "XT"]


@st.composite
def stream(draw) -> str:
    lines = []
    for _ in range(draw(st.integers(0, 25))):
        kind = draw(st.integers(0, 6))
        if kind == 0:
            lines.append(draw(st.sampled_from(["", " ", "\t"])))
        elif kind == 1:
            lines.append(draw(st.sampled_from(["", " "])) + ";" + draw(st.text(st.sampled_from("ab ;'"), max_size=8)))
        else:
            sep = draw(st.sampled_from([" ", "  ", "\t"]))
            line = sep.join(draw(st.lists(st.sampled_from(COMMANDS), min_size=1, max_size=4)))
            if draw(st.booleans()):
                line += draw(st.sampled_from(["", " ", "   "])) + draw(st.sampled_from(["; note", ";x y"]))
            lines.append(draw(st.sampled_from(["", " "])) + line + draw(st.sampled_from(["", " "])))
    return "\n".join(lines) + draw(st.sampled_from(["", "\n"]))


PROPERTY = settings(max_examples=300, deadline=None, suppress_health_check=[HealthCheck.too_slow])


@PROPERTY
@given(text=stream())
def test_formatting_never_changes_the_ir(text: str) -> None:
    assert_same_meaning(text, format_text(text))


@PROPERTY
@given(text=stream())
def test_formatting_is_idempotent(text: str) -> None:
    once = format_text(text)
    assert format_text(once) == once
