"""VA of a user variable already declared: the device refuses it with Error 28 (M141)."""

from __future__ import annotations

from mcc.compiler import driver
from mcc.compiler.codes import registry


def codes(text: str) -> list[tuple[int, str]]:
    return sorted((d.span.line, d.code) for d in driver.check_file("p.mxt", text=text).diagnostics)


def test_the_registered_examples() -> None:
    info = registry().get("M141")
    assert ("M141" in [c for _, c in codes(info.bad)]) and "M141" not in [c for _, c in codes(info.good)]


def test_second_declaration_is_reported_once_at_its_line() -> None:
    text = "VA Q1=10\nVA Q2\nPG 1\n  VA Q1=3\n  Q2=Q1\n  E\nPG\n"
    result = driver.check_file("p.mxt", text=text)
    found = [d for d in result.diagnostics if d.code == "M141"]
    assert [(d.span.line, d.span.column) for d in found] == [(4, 6)]
    assert "line 1" in found[0].message and "Error 28" in found[0].message
