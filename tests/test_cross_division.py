"""A division converted between products that round a quotient differently (issue 23).

MCode rounds an integer quotient down (lexium-mcode.txt L1249: -7/2 is -4), Arcus truncates toward
zero (a decision, docs/decisions/0008-division-rounding-per-product.md), X150 variables hold
decimals (parker-x150.md L4569-L4573: -7/2 is -3.5). A division whose value the target would
compute otherwise is refused upfront with G040 on its line (backends/division.py); one whose value
is the same in both products is written as it is and passes the validation. The fixtures are
written here, after the manuals' examples."""

from __future__ import annotations

import pytest

from mcc.backends import division
from mcc.compiler import driver, profiles

# Each fixture: (dialect, file name, text, the line of the division that may be negative or
# inexact). The other divisions are exact in every product: constants that divide, divisor 1.
MCODE = ("mcode", "div.mxt", "VA N1=0\nVA N2=0\nPG 100\nLB MN\n  N1=-7\n  N2=N1/2\n  E\nPG\n", 6)
ARCUS = ("arcus", "div.prg", "V1=-7\nV2=V1/2\nEND\n", 2)
X150 = ("x150", "div.x150", "1XE12\n1XD12\n1VAR1=-7\n1VAR2=VAR1/2\n1XT\n", 4)
SAFE = {
    "mcode": ("div.mxt", "VA N1=0\nVA N2=0\nPG 100\nLB MN\n  N1=-7\n  N2=N1/1\n  N2=8/2\n  E\nPG\n"),
    "arcus": ("div.prg", "V1=-7\nV2=V1/1\nV2=8/2\nV2=V1/-1\nEND\n"),
    "x150": ("div.x150", "1XE12\n1XD12\n1VAR1=-7\n1VAR2=VAR1/1\n1VAR2=8/2\n1XT\n"),
}
PAIRS = [(src, tgt) for src in (MCODE, ARCUS, X150) for tgt in ("mcode", "arcus", "x150") if tgt != src[0]]
RULE_WORDS = {"floor": "rounded down", "truncate": "truncated toward zero", "exact": "kept exact"}


def errors(result) -> list:
    return [d for d in result.diagnostics if d.severity.value == "error"]


@pytest.mark.parametrize("source,target", PAIRS, ids=lambda v: v[0] if isinstance(v, tuple) else v)
def test_a_division_that_may_round_otherwise_is_refused_on_its_line(tmp_path, source, target) -> None:
    """-7/2 differs in every pair: -4 in MCode (lexium-mcode.txt L1249), -3 in Arcus (decision
    0008), -3.5 in X150 (parker-x150.md L4569-L4573). The refusal is G040 on the division's line,
    names both rules and says what to do, and comes before the validation (no S010)."""
    dialect, name, text, line = source
    path = tmp_path / name
    path.write_text(text)
    result = driver.compile_file(str(path), dialect, target)
    found = [d for d in errors(result) if d.code == "G040"]
    assert [d.span.line for d in found] == [line], [(d.code, d.message) for d in errors(result)]
    message = found[0].message
    source_rule = division.rounding(profiles.load(driver.dialects.get(dialect).default_profile), dialect)
    target_rule = division.rounding(profiles.load(driver.dialects.get(target).default_profile), target)
    assert RULE_WORDS[source_rule] in message and RULE_WORDS[target_rule] in message
    assert f"compile to {dialect}" in message
    assert not [d for d in errors(result) if d.code == "S010"]


@pytest.mark.parametrize("source,target", PAIRS, ids=lambda v: v[0] if isinstance(v, tuple) else v)
def test_a_division_exact_in_both_products_is_written_and_validated(tmp_path, source, target) -> None:
    """A divisor of 1 or -1 and constants that divide (8/2) give the same quotient under every
    rule (lexium-mcode.txt L1249, parker-x150.md L4569-L4573): written, and the validation in the
    simulator finds the output behaving like the source."""
    dialect = source[0]
    name, text = SAFE[dialect]
    path = tmp_path / name
    path.write_text(text)
    result = driver.compile_file(str(path), dialect, target)
    assert not errors(result), [(d.code, d.span.line, d.message) for d in errors(result)]
    assert result.listing is not None


@pytest.mark.parametrize("source,target", [("mcode", "arcus"), ("arcus", "mcode")])
def test_non_negative_constants_round_alike_down_and_toward_zero(tmp_path, source, target) -> None:
    """Rounding down (lexium-mcode.txt L1249) and truncation (decision 0008) agree when both
    operands are non-negative: 7/2 is 3 in both, so it is written as it is."""
    name, text = {"mcode": ("div.mxt", "VA N2=0\nPG 100\nLB MN\n  N2=7/2\n  E\nPG\n"),
                  "arcus": ("div.prg", "V2=7/2\nEND\n")}[source]
    path = tmp_path / name
    path.write_text(text)
    result = driver.compile_file(str(path), source, target)
    assert not errors(result), [(d.code, d.message) for d in errors(result)]


@pytest.mark.parametrize("source,target", [("mcode", "x150"), ("arcus", "x150")])
def test_a_non_negative_inexact_quotient_is_refused_into_decimals(tmp_path, source, target) -> None:
    """7/2 is 3 in an integer product (lexium-mcode.txt L1249) but 3.5 in an X150 variable
    (parker-x150.md L4569-L4573): non-negative operands do not help, the fraction does."""
    name, text, line = {"mcode": ("div.mxt", "VA N2=0\nPG 100\nLB MN\n  N2=7/2\n  E\nPG\n", 4),
                        "arcus": ("div.prg", "V2=7/2\nEND\n", 1)}[source]
    path = tmp_path / name
    path.write_text(text)
    result = driver.compile_file(str(path), source, target)
    assert [(d.code, d.span.line) for d in errors(result)] == [("G040", line)]


def test_the_same_product_family_writes_every_division() -> None:
    """Within one product the rule is the same (lexium-mcode.txt L1249 for every Lexium MCode
    profile): nothing is refused."""
    result = driver.compile_file("div.mxt", "mcode", "mcode", text=MCODE[2])
    assert not errors(result)


def test_the_rule_comes_from_the_profile() -> None:
    """`[machine.arithmetic] integer_division` is data: MCode's profile says floor (L1249), Arcus
    has the default truncate (decision 0008), X150's decimal variables keep the fraction
    (parker-x150.md L4569-L4573)."""
    load = profiles.load
    assert division.rounding(load("lmd-c"), "mcode") == "floor"
    assert division.rounding(load("pmx-4ex-sa"), "arcus") == "truncate"
    assert division.rounding(load("x150-blhx"), "x150") == "exact"


def test_a_float_quotient_into_an_integer_product_is_refused() -> None:
    """An MCode float register keeps the fraction (F1-F8 are the exception to rounding down,
    lexium-mcode.txt L1249): -7/2 is -3.5 in F1, while an Arcus variable would hold -3 (decision
    0008): the fraction would be dropped, so it is refused like an X150 decimal quotient."""
    text = "VA N1=0\nPG 100\nLB MN\n  N1=-7\n  F1=N1/2\n  N1=F1\n  E\nPG\n"
    result = driver.compile_file("div.mxt", "mcode", "arcus", text=text)
    assert [(d.code, d.span.line) for d in errors(result)] == [("G040", 5)]
    assert "-3.5" in errors(result)[0].message
