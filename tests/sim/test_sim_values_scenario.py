"""Each dialect's arithmetic, and the scenario file format with its error messages."""

from __future__ import annotations

from decimal import Decimal

import pytest
from hypothesis import given
from hypothesis import strategies as st

from mcc.compiler.ir import VarType
from mcc.sim import values
from mcc.sim.scenario import ScenarioError, parse


@given(st.integers(-(2 ** 40), 2 ** 40))
def test_int32_storage_wraps_like_twos_complement(n):
    stored = values.store(n, VarType.INT32)
    assert -(2 ** 31) <= stored < 2 ** 31 and (stored - n) % 2 ** 32 == 0


@given(st.integers(-10 ** 6, 10 ** 6), st.integers(-1000, 1000).filter(bool))
def test_integer_division_truncates_and_the_remainder_keeps_the_dividends_sign(a, b):
    q, r = values.binary("/", a, b), values.binary("%", a, b)
    assert q * b + r == a and abs(r) < abs(b) and (r == 0 or (r > 0) == (a > 0))


def test_mixed_operands():
    assert values.binary("/", 7, 2.0) == 3.5
    assert values.binary("/", Decimal(7), 2) == Decimal("3.5")
    assert values.store(10 / 3, VarType.DECIMAL) == Decimal("3.333333")
    assert values.binary("<<", 1, 31) == -(2 ** 31)
    with pytest.raises(values.ArithmeticFault, match="division by zero"):
        values.binary("%", 1, 0)
    with pytest.raises(values.ArithmeticFault, match="undefined"):
        values.function("sqrt", [-1])


def test_trigonometry_is_in_degrees():
    assert values.function("sin", [30]) == pytest.approx(0.5)
    assert values.function("atan", [1]) == pytest.approx(45)


def test_a_full_scenario():
    text = """
until = 12.5
[inputs]
1 = 1
[analog]
2 = 512
[[events]]
at = 0.5
input = 2
value = 1
[[events]]
axis = "X"
passes = 4000
input = 3
value = 1
[axes.X]
home = -200
limit_plus = 50000
"""
    s = parse(text)
    assert s.until == 12.5 and s.inputs == {1: 1} and s.analog == {2: 512}
    assert [(e.input, e.at, e.axis, e.passes) for e in s.events] == [(2, 0.5, "", 0.0), (3, None, "X", 4000)]
    assert s.switches("X").home == -200 and s.switches("X").limit_plus == 50000 and s.switches("Y").home == 0
    assert s.inputs_driven() == {1, 2, 3}


@pytest.mark.parametrize("text, message", [
    ("until = 'soon'", "expected a number"),
    ("[[events]]\ninput = 1\nvalue = 1", "needs 'at'"),
    ("[[events]]\nat = 1", "needs 'input' and 'value'"),
    ("[inputs]\nzero = 1", "not an input number"),
    ("[inputs]\n0 = 1", "start at 1"),
    ("[axes.X]\nhome_switch = 3", "unknown key 'home_switch'"),
    ("speed = 3", "unknown key 'speed'"),
    ("[[events]]\nat = -1\ninput = 1\nvalue = 1", "'at' must be >= 0"),
    ("[inputs", "invalid TOML"),
])
def test_scenario_errors_say_what_is_wrong(text, message):
    with pytest.raises(ScenarioError, match=message):
        parse(text, "s.toml")


@pytest.mark.parametrize(("value", "spec", "signed", "text"), [
    (Decimal("987.12345"), "fixed 3 magnitude", False, "987.123"),   # parker-x150.md L4481: 1TX1,0,3,3V
    (Decimal("987.12345"), "fixed 0", True, "+987"),                 # L4482: 1TX1,1,0,2D
    (Decimal("987.12345"), "fixed 5 magnitude", False, "987.12345"),  # L4483: 1TX1,0,5,2VAR3=
    (Decimal("-7.59"), "fixed 1 magnitude", False, "7.5"),            # digits past p dropped, no sign (m=0)
    (Decimal("-7.59"), "fixed 1", True, "-7.5"),
    (0b1001, "bits 10", False, "1001000000"),                          # L2141: input 1 first
    (1, "pad 2", False, "01"),                                          # L3217: ;*01!
])
def test_print_formats(value, spec, signed, text):
    """The print formats of docs/IR.md ("Print formats"), with the manual's examples."""
    assert values.formatted(value, spec, signed) == text
