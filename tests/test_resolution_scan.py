"""The scan for a target resolution that converts every position exactly (backends/resolution.py)
and the memory note of `mcc compile` stay cheap on programs far over the target's memory (issue 26:
a 150-deep MCode call chain compiled to X150 took half a minute of the suite)."""

from __future__ import annotations

import random
from fractions import Fraction

import pytest

from mcc.backends import resolution
from mcc.compiler import driver, units
from test_fuzz import nested

VALUES = [0, 1, -1, 7, 100, 512, 51200, -25600, 3.0, -2.0, 0.5, 1.25, True, Fraction(6, 1), Fraction(1, 3)]


@pytest.mark.parametrize("seed", range(20))
def test_the_integer_scan_agrees_with_the_fraction_test(seed: int) -> None:
    """`exact_at` answers as `exact` with the ratio of the two resolutions, for every kind of constant
    a program holds (ints, whole floats, fractions of a step) and every candidate."""
    rnd = random.Random(seed)
    found = resolution.Positions(rnd.sample(VALUES, rnd.randint(0, 5)), rnd.random() < 0.3, False)
    whole = resolution.whole_constants(found)
    for source in (0, -200, 200, 400, 51200, 25000):
        for target in list(range(1, 1200, 7)) + [source, 0, 32767, 102400]:
            assert resolution.exact_at(found, source, target, whole) == \
                resolution.exact(found, units.ratio(source, target)), (found, source, target)


def test_the_memory_note_is_worked_out_once_per_compile(monkeypatch) -> None:
    """A program over the X150's 64 sequences gets one X203 per sequence it lacks, each with the same
    note on the optimization levels: the levels are compiled once, not once per diagnostic."""
    calls = []
    real = driver.fits_at
    monkeypatch.setattr(driver, "fits_at", lambda *args: calls.append(args) or real(*args))
    result = driver.compile_file("f.mxt", target="x150", text=nested("mcode", "if", 80))
    budget = [d for d in result.diagnostics if d.code == "X203"]
    assert len(budget) > 1 and len(calls) == 1
    assert {d.notes for d in budget} == {("no optimization level makes it fit: shorten the program",)}
