"""Every sample and golden program of every dialect, through every level and every pass alone:
the verifier runs after each pass (`optimize(..., verify=True)`), the meaning half of the contract
stays kept where the program kept it, and the oracle sees the same behaviour."""

from __future__ import annotations

import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "ir"))

from ir_programs import lowered, program_files  # noqa: E402
from sim_behaviour import Baseline, same_behaviour  # noqa: E402
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
    baseline = Baseline(module)  # the source simulated once per scenario for all the choices
    for level, passes in choices:
        optimized = run(module, dialect, level, passes)
        if meaning_kept:
            assert verify(optimized) == [], (level, passes)
        same_behaviour(module, optimized, baseline=baseline)


def test_the_programs_exist():
    assert len(PROGRAMS) > 50
    assert {d for d, _ in PROGRAMS} == {"mcode", "arcus", "x150"}


def compiled_module(path: Path, dialect: str, level: str):
    """The IR of `path` compiled at `level` and read back (None when it does not compile clean)."""
    from mcc.compiler import driver

    result = driver.compile_file(str(path), dialect, opt_level=level)
    if result.has_errors or result.listing is None:
        return None, result
    back = driver.check_file(str(path), dialect, text=result.listing.text)
    assert not back.has_errors, [d.message for d in back.diagnostics]
    return back.analysis.module, result


ARCUS = [path for dialect, path in PROGRAMS if dialect == "arcus"]


@pytest.mark.parametrize("path", ARCUS, ids=[f"{p.parent.name}/{p.name}" for p in ARCUS])
def test_compiled_arcus_output_behaves_as_the_source_at_every_level(path):
    """End to end: the device program each level writes, read back, behaves as the source."""
    source = lowered(path, "arcus")
    if source is None:
        pytest.skip("the program has errors")
    if compiled_module(path, "arcus", "O0")[0] is None:
        pytest.skip("the program does not compile at -O0")
    for level in LEVELS:
        module, result = compiled_module(path, "arcus", level)
        assert module is not None, (level, [d.message for d in result.diagnostics])
        assert not result.optimization.fallback
        same_behaviour(source, module)


def repetitive_program() -> str:
    """A small machine-made program: pen subroutines, a loop over parts, the same gripper run at
    several places, a shape repeated as relative moves (what -Os outlines)."""
    lines = ["ABS", "HSPD=20000", "LSPD=500", "ACC=200", "V1=0", "WHILE V1<3"]
    for x in (1000, 2000, 3000):
        lines += [f"X{x}Y500", "WAITX", "WAITY", "Z-6000", "WAITZ", "DO1=1", "DELAY=250", "Z0", "WAITZ"]
    lines += ["V1=V1+1", "ENDWHILE"]
    for x in (5000, 9000, 13000):
        lines += ["ABS", f"X{x}Y0", "GOSUB 2", "INC", "X100Y0", "X0Y100", "X-100Y0", "X0Y-100", "ABS", "GOSUB 1"]
    lines += ["IF DI1=1", "X0Y0", "WAITX", "Z-6000", "WAITZ", "DO1=1", "DELAY=250", "Z0", "WAITZ", "ELSE",
              "X10Y0", "WAITX", "Z-6000", "WAITZ", "DO1=1", "DELAY=250", "Z0", "WAITZ", "ENDIF", "END",
              "SUB 1", "Z0", "WAITZ", "ENDSUB", "SUB 2", "Z-2000", "WAITZ", "ENDSUB"]
    return "\n".join(lines) + "\n"


def test_outlined_arcus_program_is_smaller_and_behaves_the_same(tmp_path):
    path = tmp_path / "cell.prg"
    path.write_text(repetitive_program())
    source = lowered(path, "arcus")
    sizes = {}
    for level in LEVELS:
        module, result = compiled_module(path, "arcus", level)
        assert module is not None, (level, [d.message for d in result.diagnostics])
        sizes[level] = result.listing.stats["asm_lines"]
        same_behaviour(source, module)
    assert sizes["Os"] < 0.8 * sizes["O0"]
    assert result.optimization.lines_saved == sizes["O0"] - sizes["Os"]
