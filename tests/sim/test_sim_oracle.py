"""The oracle: every sample and golden program, compiled (to its own dialect and to each other one
where it compiles), formatted and fixed, behaves in the simulator like its source."""

from __future__ import annotations

import shutil

import pytest

from mcc.compiler import driver
from mcc.compiler.config import Settings
from mcc.compiler.lint import engine, formatting
from mcc.sim.verify import check_translation
from conftest import ROOT
from sim_programs import DIALECTS, contract_module, programs, scenarios_for

CASES = [(d, p) for d in DIALECTS for p in programs(d)]
IDS = [f"{d}/{p.parent.name}/{p.name}" for d, p in CASES]
REFUSALS_FILE = ROOT / "tests" / "sim" / "expected_refusals.toml"


def expected_refusals() -> dict[tuple[str, str], str]:
    """(program, target) -> the code of the error that refuses it, from expected_refusals.toml."""
    from mcc.compiler import toml

    table = toml.loads(REFUSALS_FILE.read_text(encoding="utf-8")).get("refusal", [])
    return {(entry["program"], entry["target"]): entry["code"] for entry in table}


REFUSALS = expected_refusals()


def refusal(compiled) -> tuple[str, str] | None:
    """The first error of a compile, as (code, message), or None when it wrote a program."""
    errors = sorted((d for d in compiled.diagnostics if d.severity.value == "error"), key=lambda d: d.sort_key())
    if errors:
        return errors[0].code, errors[0].message
    return None if compiled.listing is not None else ("none", "no listing")


def check_refusal(path, target: str, compiled) -> bool:
    """Whether the compile was refused, as expected_refusals.toml says it is; a program that starts
    or stops compiling to `target`, or is refused with another code, fails here."""
    key = (str(path.relative_to(ROOT)), target)
    found = refusal(compiled)
    expected = REFUSALS.get(key)
    if found is None:
        assert expected is None, f"{key[0]} now compiles to {target}: remove it from {REFUSALS_FILE.name} " \
                                 f"(expected refusal {expected})"
        return False
    assert expected == found[0], f"{key[0]} is refused for {target} with {found[0]}: {found[1]}; " \
                                 f"expected {expected or 'a program'} ({REFUSALS_FILE.name})"
    return True


def test_the_expected_refusals_name_programs_the_oracle_runs():
    """Every entry of expected_refusals.toml is a program and target of the oracle (a stale entry
    would hide nothing, but says something false)."""
    known = {(str(p.relative_to(ROOT)), t) for _, p in CASES for t in DIALECTS}
    assert set(REFUSALS) <= known, sorted(set(REFUSALS) - known)


@pytest.mark.parametrize("target", DIALECTS)
@pytest.mark.parametrize("dialect, path", CASES, ids=IDS)
def test_compiled_program_behaves_like_its_source(dialect, path, target):
    """The compile as `mcc compile` runs it, validated in the simulator on the default scenarios and
    the program's own: it writes a program (which then behaves like the source) or is refused as
    expected_refusals.toml says; a program the validation refuses (S010) is wrong code the
    backend would have written, listed there until the backend is fixed."""
    result = contract_module(path, dialect)
    compiled = driver.compile_file(str(path), dialect, target, always_verify=True,
                                   scenarios=scenarios_for(path, result.analysis.module))
    check_refusal(path, target, compiled)


@pytest.mark.parametrize("dialect, path", CASES, ids=IDS)
def test_formatted_and_fixed_programs_behave_like_their_source(dialect, path, tmp_path):
    result = contract_module(path, dialect)
    copy = tmp_path / path.name
    shutil.copy(path, copy)
    if formatting.formatter(dialect) is not None:
        outcome = formatting.format_file(str(copy), Settings(), formatting.Options(verify=True))
        assert "--verify" not in outcome.error
    fixed = engine.lint_file(str(copy), Settings(), engine.Options(fix=True, verify=True))
    assert [d.message for d in fixed.diagnostics if d.code == "S010"] == []
    scenarios = scenarios_for(path, result.analysis.module)
    if scenarios is not None:  # the program's own scenario too (fmt and lint --verify use the defaults)
        after = copy.read_text(encoding="utf-8")
        assert check_translation(str(path), dialect, result.analysis.module, after, scenarios=scenarios) == ""


@pytest.mark.parametrize("level", ["O0", "O1", "O2", "Os"])
@pytest.mark.parametrize("dialect, path", CASES, ids=IDS)
def test_every_optimization_level_behaves_like_the_source(dialect, path, level):
    """The optimizer's oracle (issue 10): each level's output runs like the program as written."""
    result = contract_module(path, dialect)
    compiled = driver.compile_file(str(path), dialect, opt_level=level, always_verify=True,
                                   scenarios=scenarios_for(path, result.analysis.module))
    assert refusal(compiled) is None, f"{path.name} at -{level}: {refusal(compiled)}"


def test_a_stop_of_an_axis_at_standstill_is_no_difference():
    """X150 `SB` unaddressed stops device 1; Arcus `STOP` stops all four axes. Stopping an axis that
    does not move does nothing, so the oracle does not count it (like a move to where it is)."""
    compiled = driver.compile_file("s.x150", "x150", "arcus", text="1A10\n1V1\n1D4000\n1G\nSB\n")
    assert not compiled.has_errors, [(d.code, d.message) for d in compiled.diagnostics]
    moving = driver.compile_file("s.x150", "x150", "arcus", text="1A10\n1V1\n1MC\n1G\nT1\nSB\nT1\n")
    assert not moving.has_errors, [(d.code, d.message) for d in moving.diagnostics]
