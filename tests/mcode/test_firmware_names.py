"""Names that became math functions in firmware 6.0.01 (AB, LO, SQ, ...) are plain names before it.

The grammar reserves none of them; the profile's firmware decides what they are.
"""

from __future__ import annotations

import pytest

from mcc.compiler import driver, profiles
from mcc.compiler.profiles import Profile


def fw5(tmp_path) -> Profile:
    path = tmp_path / "fw5.toml"
    path.write_text('extends = "lmd-c"\nname = "fw5"\nfirmware = "5.0"\n', encoding="utf-8")
    return profiles.load(str(path))


def diags(text: str, profile: Profile | None = None) -> list[tuple[int, str]]:
    result = driver.check_file("p.mxt", "mcode", profile, text=text)
    return sorted((d.span.line, d.code) for d in result.diagnostics)


@pytest.mark.parametrize("name", ["AB", "CS", "C_", "LO", "L_", "SI", "S_", "SQ", "TG", "T_"])
def test_no_function_name_is_a_syntax_error(name: str, tmp_path) -> None:
    text = f"PG 1\nLB {name}\n  CL {name},P<0\n  E\nPG\n"
    assert not [c for _, c in diags(text) if c == "M001"]
    if "_" not in name:  # a label name is two letters or a letter and a digit
        assert diags(text, fw5(tmp_path)) == []


def test_firmware_6_reports_each_use_as_a_name_and_names_the_firmware() -> None:
    result = driver.check_file("p.mxt", "mcode", None, text="VA LO=12200\nPG 1\n  R1=AB\n  E\nPG\n")
    found = [(d.code, d.message) for d in result.diagnostics]
    assert sorted(c for c, _ in found) == ["M104", "M119"]
    assert all("6.0.01" in message for _, message in found)


def test_a_function_call_on_firmware_5_needs_firmware_6(tmp_path) -> None:
    result = driver.check_file("p.mxt", "mcode", fw5(tmp_path), text="PG 1\n  R1=AB P\n  E\nPG\n")
    assert [(d.code, "6.0.01" in d.message) for d in result.diagnostics] == [("M115", True)]


def test_two_values_side_by_side_are_reported_once() -> None:
    assert diags("PG 1\n  R1=XY R2\n  E\nPG\n") == [(2, "M119")]
    assert diags("PG 1\n  R1=R2 -5\n  F1=SQ AB R2\n  F2=Q1*PI\n  E\nPG\n") == [(4, "M117")]


def test_a_function_of_a_negative_value_and_a_subtraction() -> None:
    from mcc.compiler.mcode import syntax as st

    result = driver.check_file("p.mxt", "mcode", None, text="PG 1\n  F6=AB -12\n  R1=R2 -5\n  R3=R2-5\n  E\nPG\n")
    assert result.diagnostics == []
    stmts = [line.statement for line in result.analysis.tree.lines if line.statement is not None]
    assert isinstance(stmts[1].args[0], st.FuncCall)
    assert isinstance(stmts[2].args[0], st.Binary) and isinstance(stmts[3].args[0], st.Binary)
