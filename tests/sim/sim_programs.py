"""The dialect programs the simulator's oracle runs on, and whether each keeps the IR contract.

A dialect's frontend joins the contract when it is converted (issue 8); until then its programs
are skipped with the first violation named, so the tests switch on by themselves as dialects are
converted."""

from __future__ import annotations

from pathlib import Path

import pytest

from conftest import EXTENSIONS, GOLDEN, ROOT, sample_files

SIM_GOLDEN = ROOT / "tests" / "sim" / "golden"
DIALECTS = tuple(EXTENSIONS)


def programs(dialect: str) -> list[Path]:
    """Every sample and golden program of `dialect` that checks clean, and the simulator's own
    golden programs. A golden case whose expected diagnostics hold an error (it exists to test
    that error) is not a program to run: it is left out here rather than skipped one test at a
    time, so a skip in these tests means something unexpected."""
    golden = sorted(p for p in GOLDEN.joinpath(dialect).glob(f"*/*{EXTENSIONS[dialect]}") if not expects_error(p))
    return sample_files(dialect) + golden + sim_golden(dialect)


def expects_error(program: Path) -> bool:
    """Whether the golden case `program` has an error when checked as these tests run it (its
    dialect's default profile): such a case exists to test that error."""
    from mcc.compiler import driver

    return driver.check_file(str(program)).has_errors


def sim_golden(dialect: str) -> list[Path]:
    return sorted(SIM_GOLDEN.joinpath(dialect).glob(f"*{EXTENSIONS[dialect]}"))


def contract_module(path: Path, dialect: str):
    """The module of `path` when it checks clean and keeps the IR contract; otherwise skip."""
    from mcc.compiler import driver
    from mcc.compiler.ir_verify import verify

    result = driver.check_file(str(path), dialect)
    if result.has_errors or result.analysis is None or result.analysis.module is None:
        pytest.skip(f"{path.name} has errors; only clean programs are simulated")
    problems = verify(result.analysis.module)
    if problems:
        pytest.skip(f"the {dialect} frontend does not keep the IR contract yet ({problems[0]})")
    return result


def scenarios_for(path: Path, module) -> list | None:
    """The scenario stored next to a program (`homing.toml` beside `homing.prg`), run with the
    default ones that drive every input the program reads; None (the defaults only) when there is
    none."""
    from mcc.sim.scenario import load
    from mcc.sim.verify import default_scenarios

    stored = path.with_suffix(".toml")
    if not stored.exists():
        return None
    return [load(str(stored))] + default_scenarios(module)
