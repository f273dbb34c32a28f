"""No input, however malformed, makes mcc raise: random and mutated text through check and compile."""

from __future__ import annotations

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from conftest import EXTENSIONS, dialects_with, sample_files
from mcc.compiler import driver

ALPHABET = st.characters(codec="utf-8", exclude_categories=("Cs",))
TOKENS = {
    "mcode": ["MA", "MR", "PG", "LB", "BR", "CL", "RT", "E", "VA", "PR", "=", ",", "\"", "`", "'", "-", "*",
              "!", "^", "1", "100", "K1", "G1", " ", "\n", "IS", "S1", "<>", "I1", "F1", "CS", ";", "H"],
    "arcus": ["IF", "ELSE", "ELSEIF", "ENDIF", "WHILE", "ENDWHILE", "SUB", "ENDSUB", "GOSUB", "END", "X", "Y",
              "V1", "=", "+", "-", ";", "HSPDX", "JOGX+", "DO7", "1000", ":", " ", "\n", "!=", "~", "WAITX"],
    "x150": ["XD1", "XT", "XE1", "1A10", "V5", "D-100", "G", "L5", "N", "IF(", ")", "VAR1", "=", " ", "\n", ";",
             "\"", "1OUT3B", "TRE_X1", "ELSE", "NIF", "WHILE(", "NWHILE", "REPEAT", "UNTIL(", "XR2", "AND"],
}


def mutate(text: str, data) -> str:
    ops = data.draw(st.lists(st.tuples(st.integers(0, 3), st.integers(0, max(0, len(text))), st.text(ALPHABET, max_size=4)),
                             max_size=6))
    for kind, pos, piece in ops:
        if kind == 0:
            text = text[:pos] + piece + text[pos:]
        elif kind == 1:
            text = text[:pos] + text[pos + len(piece) + 1:]
        elif kind == 2:
            text = text[:pos] + piece + text[pos + 1:]
        else:
            text = text[:pos] + text[pos:pos + 8] + text[pos:]
    return text


def run_everything(dialect: str, text: str) -> None:
    for result in (driver.check_file(f"f{EXTENSIONS[dialect]}", dialect, text=text),
                   driver.compile_file(f"f{EXTENSIONS[dialect]}", dialect, text=text)):
        internal = [d.message for d in result.diagnostics if d.kind.value == "internal"]
        assert not internal, internal


FUZZ = settings(max_examples=150, deadline=None, suppress_health_check=[HealthCheck.too_slow])


@pytest.mark.parametrize("dialect", dialects_with("backend"))
@FUZZ
@given(data=st.data())
def test_random_text_never_crashes(dialect: str, data) -> None:
    text = data.draw(st.text(ALPHABET, max_size=200))
    run_everything(dialect, text)


@pytest.mark.parametrize("dialect", dialects_with("backend"))
@FUZZ
@given(data=st.data())
def test_token_soup_never_crashes(dialect: str, data) -> None:
    pieces = data.draw(st.lists(st.sampled_from(TOKENS[dialect]), max_size=40))
    run_everything(dialect, "".join(pieces))


@pytest.mark.parametrize("dialect", dialects_with("backend"))
@FUZZ
@given(data=st.data())
def test_mutated_samples_never_crash(dialect: str, data) -> None:
    samples = sample_files(dialect)
    if not samples:
        pytest.skip(f"no {dialect} samples")
    text = data.draw(st.sampled_from(samples)).read_text(encoding="utf-8")
    run_everything(dialect, mutate(text, data))
