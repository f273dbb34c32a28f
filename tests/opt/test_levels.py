"""Every sample and golden program of every dialect, through every level and every pass alone:
the verifier runs after each pass (`optimize(..., verify=True)`), the meaning half of the contract
stays kept where the program kept it, and the oracle sees the same behaviour."""

from __future__ import annotations

import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "ir"))

from ir_programs import lowered, program_files  # noqa: E402
from opt_oracle import same_behaviour  # noqa: E402
from mcc.compiler import ir, profiles  # noqa: E402
from mcc.compiler.ir_verify import verify  # noqa: E402
from mcc.compiler.opt import LEVELS, PASSES, optimize  # noqa: E402

PROGRAMS = [(dialect, path) for dialect in ("mcode", "arcus", "x150") for path in program_files(dialect)]
DEFAULT_PROFILE = {"mcode": "lmd-c", "arcus": "pmx-4ex-sa", "x150": "x150-x150ds"}


def run(module: ir.Module, dialect: str, level: str, passes: str | None = None) -> ir.Module:
    work = ir.copy_module(module)
    optimize(work, level, profiles.load(DEFAULT_PROFILE[dialect]), passes, verify=True)
    return work


@pytest.mark.parametrize("dialect,path", PROGRAMS, ids=[f"{d}/{p.parent.name}/{p.name}" for d, p in PROGRAMS])
def test_every_level_and_pass_keeps_contract_and_behaviour(dialect, path):
    module = lowered(path, dialect)
    if module is None:
        pytest.skip("the program has errors: it never reaches the optimizer")
    meaning_kept = not verify(module)
    choices = [(level, None) for level in LEVELS] + [("Os", name) for name in PASSES]
    for level, passes in choices:
        optimized = run(module, dialect, level, passes)
        if meaning_kept:
            assert verify(optimized) == [], (level, passes)
        same_behaviour(module, optimized)


def test_the_programs_exist():
    assert len(PROGRAMS) > 50
    assert {d for d, _ in PROGRAMS} == {"mcode", "arcus", "x150"}
