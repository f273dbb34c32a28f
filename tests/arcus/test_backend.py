"""The Arcus backend's text, listing and cost model, the memory budget, and the command line."""

from __future__ import annotations

from pathlib import Path

import pytest

from conftest import ROOT
from mcc.compiler import catalog, driver, profiles

PROFILE = profiles.load("pmx-4ex-sa")


def compile_text(text: str, profile: str | None = None):
    return driver.compile_file("p.prg", "arcus", profile=profiles.load(profile) if profile else None, text=text)


def test_output_is_canonical_upper_case_one_statement_per_line_without_comments() -> None:
    text = ("; header\nhspdx = 1000 ;fast\nX1000 Y2000\nv1 = v2 + 1\nif v1=1\n  gosub 1\nendif\n"
            "while V1 != 2\nV1=SYNXS\nendwhile\nDelay=5\nend\nsub 1\n jogx+\nendsub\n")
    result = compile_text(text)
    assert not result.has_errors
    assert result.listing.text.splitlines() == [
        "HSPDX=1000", "X1000Y2000", "V1=V2+1", "IF V1=1", "GOSUB 1", "ENDIF", "WHILE V1!=2", "V1=SYNXS",
        "ENDWHILE", "DELAY=5", "END", "SUB 1", "JOGX+", "ENDSUB"]


def test_end_is_written_before_the_subroutines_even_when_the_source_has_none() -> None:
    result = compile_text("X0Y0\nX10Y10\n")
    assert result.listing.text.splitlines() == ["X0Y0", "X10Y10", "END"]


def test_listing_rows_follow_the_cost_model_and_map_back_to_source_lines() -> None:
    result = compile_text("HSPD=1000\nIF V1=1\nX1Y2\nELSEIF V1=2\nARCP0:0:90000\nENDIF\nV2=V1+1\nEND\n")
    listing = result.listing
    stats = listing.stats
    costs = [1, 2, 2, 3, 4, 1, 2, 1]  # HSPD, IF, 2-axis move, ELSEIF, ARC, ENDIF, V_OP, END
    assert stats["asm_lines"] == sum(costs) == len(listing.detail)
    assert stats["statements"] == 8 and stats["asm_budget"] == 3230
    lines = [sorted({s.line for s in spans}) for _, spans in listing.detail]
    expected = [[n] for n, cost in zip([1, 2, 3, 4, 5, 6, 7, 8], costs) for _ in range(cost)]
    assert lines == expected
    rows = [text for text, _ in listing.detail]
    assert rows[1].startswith("TEST") and rows[2] == "JF    0006"  # to the ELSEIF (line 4) test, after its JMP
    assert "h-estimate" in listing.header and "3230" in listing.header
    rendered = listing.render()
    assert "    0  SET   HSPD <- 1000" in rendered and "; src 1" in rendered


def test_calibrated_costs_in_the_profile_change_the_count(tmp_path: Path) -> None:
    custom = tmp_path / "calibrated.toml"
    custom.write_text('extends = "pmx-4ex-sa"\nname = "mine"\n[arcus.cost]\nmodel = "bench-2024"\n'
                      "calibrated = true\n[arcus.cost.statements]\nIF = 3\nX = 2\n", encoding="utf-8")
    result = driver.compile_file("p.prg", "arcus", profile=profiles.load(str(custom)),
                                 text="IF V1=1\nX1\nENDIF\nEND\n")
    assert result.listing.stats["asm_lines"] == 3 + 2 + 1 + 1
    assert len(result.listing.detail) == 7
    assert "bench-2024, calibrated" in result.listing.header


def program_of(moves: int) -> str:
    return "".join(f"X{i}\n" for i in range(moves)) + "END\n"


def test_program_over_the_budget_is_an_error_naming_budget_count_and_lines() -> None:
    result = compile_text(program_of(3230))  # 3230 moves + END = 3231 assembly lines
    errors = [d for d in result.diagnostics if d.code == "A201"]
    assert len(errors) == 1 and result.has_errors
    message = errors[0].message
    assert "3231" in message and "3230" in message and "h-estimate" in message and "line 1 (1)" in message
    assert result.listing.stats["asm_lines"] == 3231


def test_program_just_under_the_budget_compiles() -> None:
    result = compile_text(program_of(3229))  # 3230 assembly lines: exactly the budget
    assert not result.has_errors
    assert result.listing.stats["asm_lines"] == 3230
    # near the budget, and over the Windows software's 1785 lines: warnings only
    assert sorted(d.code for d in result.diagnostics) == ["A204", "A240"]


def test_the_gui_profile_has_the_1785_line_budget() -> None:
    assert not compile_text(program_of(1784), "pmx-4ex-sa-gui").has_errors
    result = compile_text(program_of(1785), "pmx-4ex-sa-gui")
    assert [d.code for d in result.diagnostics if d.severity.value == "error"] == ["A201"]
    assert "1785" in result.diagnostics[0].message


def test_costliest_source_lines_are_named() -> None:
    text = "".join("ARCP0:0:90000\n" if i % 100 == 0 else f"X{i}\n" for i in range(3300)) + "END\n"
    error = next(d for d in compile_text(text).diagnostics if d.code == "A201")
    assert "line 1 (4), line 101 (4)" in error.message
    assert len(error.notes) == 6  # the five costliest lines, then whether a higher -O level fits
    assert "optimization level" in error.notes[-1]


def test_profile_costs_cover_the_catalog_and_start_from_its_estimates() -> None:
    table = PROFILE.get("arcus.cost.statements")
    for entry in catalog.load("arcus").entries:
        cost = entry.get("cost")
        if not cost:
            continue
        assert table.get(entry.name) == cost, entry.name
    assert table["V_OP"] == next(e for e in catalog.load("arcus").entries if e.name == "V").get("cost_op")
    assert profiles.load("pmx-4ex-sa-gui").get("arcus.cost.budget") == 1785


def test_compile_listing_on_the_command_line(mcc, tmp_path: Path) -> None:
    source = tmp_path / "prog.prg"
    source.write_text("HSPD=1000\nWHILE V1<3\nV1=V1+1\nENDWHILE\nEND\n", encoding="utf-8")
    out, lst = tmp_path / "out.prg", tmp_path / "out.lst"
    run = mcc("compile", str(source), "-o", str(out), "--listing", str(lst))
    assert run.returncode == 0, run.stdout + run.stderr
    assert out.read_text() == "HSPD=1000\nWHILE V1<3\nV1=V1+1\nENDWHILE\nEND\n"
    listing = lst.read_text().splitlines()
    assert listing[0].startswith("; mcc arcus listing")
    rows = [line for line in listing if line[:5].strip().isdigit()]
    assert len(rows) == 1 + 2 + 2 + 1 + 1
    assert rows[0].split()[0] == "0" and rows[-1].split()[0] == "6"


def test_check_and_explain_on_the_command_line(mcc) -> None:
    run = mcc("check", str(ROOT / "samples" / "arcus" / "sorting_station.prg"))
    assert run.returncode == 0, run.stdout
    run = mcc("explain", "A201")
    assert run.returncode == 0 and "3230" in run.stdout


@pytest.mark.parametrize("code", ["A001"] + [f"A1{n:02d}" for n in range(1, 28)] + [f"A20{n}" for n in range(1, 9)])
def test_every_code_is_documented(code: str) -> None:
    from mcc.compiler.codes import registry

    info = registry().get(code)
    assert info is not None and info.summary and info.explanation
    assert "arcus" in info.dialects
    if code < "A200":
        assert info.bad and info.good


CROSS = [p for d in ("mcode", "x150") for p in sorted((ROOT / "samples" / d).glob("*.*"))]


@pytest.mark.parametrize("path", CROSS, ids=lambda p: p.name)
def test_other_dialects_compile_to_arcus_with_diagnostics_not_crashes(path: Path) -> None:
    dialect = "mcode" if path.suffix == ".mxt" else "x150"
    result = driver.compile_file(str(path), dialect, target="arcus")
    assert not [d.message for d in result.diagnostics if d.kind.value == "internal"]
    if result.listing is not None and not result.has_errors:
        again = driver.compile_file("again.prg", "arcus", text=result.listing.text)
        assert not again.has_errors, [(d.code, d.message) for d in again.diagnostics]


def test_mutated_programs_of_other_dialects_never_crash_the_arcus_backend() -> None:
    import random

    from test_fuzz import mutate  # the shared fuzz harness's mutation

    class Draw:  # mutate() draws from hypothesis; a seeded stand-in keeps this test fast and repeatable
        def __init__(self, seed):
            self.rnd = random.Random(seed)

        def draw(self, _strategy):
            return [(self.rnd.randint(0, 3), self.rnd.randint(0, 400), "".join(self.rnd.choice("X1;=()\n-") for _ in range(3)))
                    for _ in range(self.rnd.randint(0, 6))]

    from mcc.backends import arcus as backend

    samples = CROSS + sorted((ROOT / "samples" / "arcus").glob("*.prg"))
    for seed, path in enumerate(samples * 8):
        dialect = {".mxt": "mcode", ".x150": "x150"}.get(path.suffix, "arcus")
        text = mutate(path.read_text(encoding="utf-8"), Draw(seed))
        result = driver.check_file(path.name, dialect, text=text)
        if result.analysis is None or result.analysis.module is None:
            continue
        backend.emit(result.analysis.module, PROFILE)  # even a module with errors must not crash it


@pytest.mark.parametrize("level", ["O0", "O1", "O2", "Os"])
def test_an_explicit_leading_abs_survives_every_optimization_level(level: str) -> None:
    """A program that starts with ABS does not rely on the power-up mode: a host or an earlier run
    may have left INC in force (arcus-pmx-4ex-sa.txt L1569, "INC Turns on incremental move mode";
    the mode stays until ABS, L1503). The output keeps the statement at every -O level."""
    result = driver.compile_file("p.prg", "arcus", text="ABS\nHSPD=1000\nX1000\nWAITX\nEND\n", opt_level=level)
    assert not result.has_errors
    lines = result.listing.text.splitlines()
    assert lines.count("ABS") == 1 and lines[0] == "ABS"
    again = driver.compile_file("p.prg", "arcus", text=result.listing.text, opt_level=level)
    assert again.listing.text == result.listing.text  # the output compiles to itself


def test_a_mode_stated_on_every_path_is_kept_there() -> None:
    """ABS or INC before each path's first move (L1503, L1569) states the mode without opening the
    program with it: the output writes the switch before those moves, and compiles to itself."""
    text = "HSPD=1000\nIF DI1=1\nINC\nX10\nELSE\nABS\nX20\nENDIF\nWAITX\nEND\n"
    result = driver.compile_file("p.prg", "arcus", text=text)
    lines = result.listing.text.splitlines()
    assert lines[lines.index("X10") - 1] == "INC" and lines[lines.index("X20") - 1] == "ABS"
    assert driver.compile_file("p.prg", "arcus", text=result.listing.text).listing.text == result.listing.text


def test_a_leading_inc_is_kept_and_a_program_without_a_mode_still_relies_on_the_profile() -> None:
    """INC first (L1569) is written before the first move; a program that states no mode runs in
    the mode the profile says the controller powers up in (boot_move_mode, L974) and gets none."""
    stated = driver.compile_file("p.prg", "arcus", text="INC\nX1000\nWAITX\nEND\n")
    assert stated.listing.text.splitlines()[:2] == ["INC", "X1000"]
    unstated = driver.compile_file("p.prg", "arcus", text="HSPD=1000\nX1000\nWAITX\nEND\n")
    assert "ABS" not in unstated.listing.text.splitlines()
