"""Checks that depend on the profile, the fixes, and the rules' edge cases."""

from __future__ import annotations

from pathlib import Path

import pytest

from mcc.compiler import driver, profiles
from mcc.compiler.diagnostics import Diagnostic

from x150_helpers import check, codes, compile_, src

PROFILES = ["x150-blhx", "x150-pdhx", "x150-x150ds", "x150e-bdhxe", "x150e-pdhxe"]


@pytest.mark.parametrize("name", PROFILES)
def test_profiles_load_with_their_limits(name):
    profile = profiles.load(name)
    assert profile.dialect == "x150"
    assert profile.get("limits.sequence_store_bytes") == 8000
    assert profile.get("limits.command_buffer_bytes") == 2000
    assert profile.get("limits.nesting") == 16
    high = 32 if name.startswith("x150e") else 16
    assert profile.get("limits.addresses") == [1, high]
    assert profile.firmware == ("6.2" if name.startswith("x150e") else "5.9")


def test_address_range_follows_the_profile():
    assert "X116" in codes("20A10\n")
    assert "X116" not in codes("20A10\n", "x150e-pdhxe")
    assert "X116" in codes("33A10\n", "x150e-pdhxe")


def test_products_follow_the_profile():
    assert "X121" in codes("1CPG50\n")  # servo gain on the PDHX stepper
    assert "X121" not in codes("1CPG50\n", "x150-blhx")
    assert "X121" in codes("1CER4000\n", "x150-blhx")  # stepper encoder resolution on a servo
    assert "X121" in codes("1ICON00000001\n", "x150-blhx")  # X150E only
    assert "X121" not in codes("1ICON00000001\n", "x150e-bdhxe")
    assert "X121" in codes("1CDR1\n", "x150e-pdhxe")  # BDHX-E only


def test_firmware_version_is_compared():
    # the manual gives the PDHX v6.2 for DPE (a misprint or not, the catalog keeps it)
    result = check("1DPE\n")
    assert any(d.code == "X121" and "v6.2" in d.message for d in result.diagnostics)


def profile_file(tmp_path: Path, body: str) -> profiles.Profile:
    path = tmp_path / "mine.toml"
    path.write_text('extends = "x150-pdhx"\nname = "mine"\n' + body)
    return profiles.load(str(path))


@pytest.mark.parametrize("policy,expected", [("warn", "warning"), ("error", "error"), ("ignore", None)])
def test_case_policy(tmp_path, policy, expected):
    prof = profile_file(tmp_path, f'[x150]\ncase = "{policy}"\n')
    result = driver.check_file("p.x150", "x150", prof, text="1a10\n")
    found = [d.severity.value for d in result.diagnostics if d.code == "X102"]
    assert found == ([expected] if expected else [])


def test_memory_budget_follows_the_profile(tmp_path):
    prof = profile_file(tmp_path, "[limits]\nsequence_store_bytes = 20\n")
    text = "1XE1\n1XD1\n1D100000\n1D100000\n1G\n1XT\n1SV\n"
    result = driver.check_file("p.x150", "x150", prof, text=text)
    assert [d.code for d in result.diagnostics] == ["X123"]


def apply(text: str, diag: Diagnostic) -> str:
    for edit in sorted(diag.fix.edits, key=lambda e: e.span.start, reverse=True):
        text = text[:edit.span.start] + edit.text + text[edit.span.end:]
    return text


@pytest.mark.parametrize("code,text", [
    ("X114", "1XE1\n1XD1\n1CUR800\n1XT\n1SV\n"),
    ("X103", "1OUTL XX10X1\n"),
    ("X102", '1dtxt"Mixed Case"\n'),
    ("X126", "1XD1\n1G\n1XT\n1SV\n"),
    ("X120", "1XE1\n1XD1\nA10\n1XT\n1SV\n"),
])
def test_fixes_remove_their_diagnostic(code, text):
    result = check(text)
    diag = next(d for d in result.diagnostics if d.code == code)
    assert diag.fix is not None
    fixed = apply(src(text), diag)
    assert code not in codes(fixed), fixed


def test_lowercase_text_in_quotes_is_kept():
    result = check('1dtxt"Mixed Case"\n')
    diag = next(d for d in result.diagnostics if d.code == "X102")
    assert apply(src('1dtxt"Mixed Case"\n'), diag) == '1DTXT"Mixed Case"\n'
    assert "X102" not in codes('1DTXT"Mixed Case"\n')


def test_unmarked_policies_warn():
    for command in ("1PR", "1CER2000", "1ICON00000001", "1FSB1"):
        result = check(f"1XE1\n1XD1\n{command}\n1XT\n1SV\n", "x150e-pdhxe")
        assert [d.severity.value for d in result.diagnostics if d.code == "X115"] == ["warning"], command


def test_b_prefixed_command_outside_a_sequence_is_fine():
    assert codes("1BCPE2000\n1BY\n") == []


def test_host_data_inside_a_sequence():
    assert "X113" in codes("1XE1\n1XD1\n!12.34\n1XT\n1SV\n")


def test_goto_out_of_nested_ifs_needs_as_many_nifs():
    text = "1XE2\n1XD2\n1NIF\n1G\n1XT\n1XE1\n1XD1\n1IF(IN_1)\n1IF(IN_01)\n1XG2\n1NIF\n1NIF\n1XT\n1SV\n"
    result = check(text)
    assert any(d.code == "X112" and "2 NIFs" in d.message for d in result.diagnostics)
    assert "X112" not in codes(text.replace("1XD2\n1NIF\n", "1XD2\n1NIF\n1NIF\n"))


def test_goto_outside_an_if_needs_no_nif():
    assert codes("1XE2\n1XD2\n1G\n1XT\n1XE1\n1XD1\n1IF(IN_1)\n1NIF\n1XG2\n1XT\n1SV\n") == []


def test_nesting_counts_each_construct_separately():
    text = "\n".join(["1XE1", "1XD1"] + ["1L2"] * 16 + ["1IF(IN_1)"] * 16 + ["1G"] + ["1NIF"] * 16 + ["1N"] * 16
                     + ["1XT", "1SV"]) + "\n"
    assert codes(text) == []


def test_memory_counts_broadcast_sequences_on_every_device():
    body = ["1D100000"] * 80
    text = []
    for n in range(1, 7):
        text += [f"XE{n}", f"XD{n}"] + [b[1:] for b in body] + ["XT"]
    for n in range(7, 13):
        text += [f"1XE{n}", f"1XD{n}"] + body + ["1XT"]
    result = check("\n".join(text + ["1SV"]) + "\n")
    assert [d.code for d in result.diagnostics if d.code.startswith("X12")] == ["X123"]


def test_undefined_and_dynamic_targets():
    assert codes("XR7\n") == ["X127"]
    assert codes("VAR1=7\nXR(VAR1)\n") == []


def test_pathological_inputs_never_raise():
    deep = "\n".join(["1XE1", "1XD1"] + ["1L2"] * 3000 + ["1G"] + ["1N"] * 3000 + ["1XT"]) + "\n"
    wide = "1XE1\n1XD1\n1IF(" + " AND ".join(["IN_1"] * 700) + ")\n1NIF\n1XT\n"
    chain = "1VAR1=" + "+".join(["VAR2"] * 1500) + "\n"
    huge = "1XE1\n1XD1\n1IF(" + " AND ".join(["IN_1"] * 3000) + ")\n1NIF\n1XT\n"  # 30,000 characters
    for text in (deep, wide, chain, huge):
        for result in (check(text), driver.compile_file("p.x150", "x150", text=text)):
            assert not [d for d in result.diagnostics if d.kind.value == "internal"]
    assert "X110" in codes(deep) and "X111" in codes(wide)
    assert codes(huge).count("G007") == 1 and "X111" not in codes(huge)  # reported once, not analysed


def test_nesting_summed_across_calls_is_an_inferred_warning_not_an_error() -> None:
    loops = lambda n: "\n".join(["1L2"] * n)  # noqa: E731
    ends = lambda n: "\n".join(["1N"] * n)  # noqa: E731
    text = f"1XE2\n1XD2\n{loops(8)}\n1G\n{ends(8)}\n1XT\n1XE1\n1XD1\n{loops(10)}\n1XR2\n{ends(10)}\n1XT\n1XR1\n"
    found = [d for d in check(text).diagnostics if d.code == "X140"]
    assert len(found) == 1 and found[0].severity.value == "warning"
    assert "inferred" in found[0].message and "L1750" in found[0].message
    assert compile_(text).listing is not None  # a warning: the program still compiles


@pytest.mark.parametrize("text,expected", [("1GH0\n", ["X122"]), ("1GH0.005\n", ["X122"]), ("1GH-0.01\n", []),
                                           ("1GH100\n", []), ("1GH-100.5\n", ["X122"])])
def test_gh_speed_has_a_hole_around_zero(text, expected):
    """GH n: n from 0.01 to 100 rev/s in either direction (L1706); GH0 homes nowhere."""
    assert codes(text) == expected
