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
    """Every sample and golden program of `dialect`, and the simulator's own golden programs."""
    golden = sorted(GOLDEN.joinpath(dialect).glob(f"*/*{EXTENSIONS[dialect]}"))
    return sample_files(dialect) + golden + sim_golden(dialect)


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
