"""A file in a neighbouring controller's language gets one diagnostic naming it (G020), not a
cascade; a program of the right dialect with many mistakes keeps its own diagnostics."""

from __future__ import annotations

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from conftest import EXTENSIONS, GOLDEN, run_mcc, sample_files
from mcc.compiler import driver

SIX_K = (GOLDEN / "x150" / "neighbour-6k" / "input.x150").read_text(encoding="utf-8")


def codes(path: str, text: str) -> list[str]:
    return [d.code for d in driver.check_file(path, text=text).diagnostics]


def test_a_6k_program_is_one_diagnostic_in_every_reader() -> None:
    assert len(SIX_K.splitlines()) >= 35
    for path in ("cell.x150", "cell.mxt", "cell.prg"):
        assert codes(path, SIX_K) == ["G020"], path


def test_the_diagnostic_names_the_language_and_the_lines() -> None:
    diag = driver.check_file("cell.x150", text=SIX_K).diagnostics[0]
    assert "Parker 6K" in diag.message and diag.span.line == 2 and len(diag.notes) >= 3


def test_a_broken_x150_program_keeps_its_own_diagnostics() -> None:
    text = "1XD1\n1A10\n1FOO5\n1BAR\n1QQQ\n1D4000\n1G\n1ZZZ2\n1XT\n"
    found = codes("p.x150", text)
    assert "G020" not in found and len([c for c in found if c.startswith("X")]) >= 6


def test_two_prg_blocks_are_a_sibling_program_not_a_neighbour() -> None:
    """Two PRG blocks are a PMX-2ED-SA program (its manual p.61-62, p.66: PRG n ... END, axes X and
    Y): no G020, but G021 naming the profile it fits (issue 24: the siblings are profiles of the
    arcus dialect now, docs/dialects/arcus.md "Family")."""
    found = driver.check_file("p.prg", text="PRG 0\nX1000\nEND\nPRG 1\nY1000\nEND\n")
    assert [d.code for d in found.diagnostics] == ["G021"] and "'pmx-2ed-sa'" in found.diagnostics[0].message


def test_nothing_is_compiled_and_the_exit_code_is_1(tmp_path) -> None:
    path = tmp_path / "cell.x150"
    path.write_text(SIX_K, encoding="utf-8")
    result = run_mcc("compile", str(path))
    assert result.returncode == 1 and "G020" in result.stdout + result.stderr
    assert result.stdout.count("error[") + result.stderr.count("error[") == 1


@pytest.mark.parametrize("dialect", sorted(EXTENSIONS))
@settings(max_examples=25, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(data=st.data())
def test_mutated_samples_of_the_right_dialect_are_never_another_language(dialect: str, data) -> None:
    """Deleting, duplicating and truncating lines of a real sample makes errors, never a G020."""
    lines = data.draw(st.sampled_from(sample_files(dialect))).read_text(encoding="utf-8").splitlines()
    for _ in range(data.draw(st.integers(0, 6))):
        if not lines:
            break
        i = data.draw(st.integers(0, len(lines) - 1))
        action = data.draw(st.sampled_from(["delete", "duplicate", "truncate"]))
        if action == "delete":
            del lines[i]
        elif action == "duplicate":
            lines.insert(i, lines[i])
        else:
            lines[i] = lines[i][: data.draw(st.integers(0, len(lines[i])))]
    assert "G020" not in codes("p" + EXTENSIONS[dialect], "\n".join(lines) + "\n")


@pytest.mark.parametrize("sample,reader", [
    ("mcode/pick_and_place.mxt", "p.x150"), ("mcode/trip_on_input.mxt", "p.prg"),
    ("arcus/sorting_station.prg", "p.mxt"), ("arcus/pick_and_place.prg", "p.x150"),
    ("x150/03_part_sorter.x150", "p.mxt"), ("x150/06_rp240_menu.x150", "p.prg"),
])
def test_a_file_of_another_mcc_dialect_names_the_option(sample: str, reader: str) -> None:
    from conftest import SAMPLES

    text = (SAMPLES / sample).read_text(encoding="utf-8")
    diags = driver.check_file(reader, text=text).diagnostics
    dialect = sample.split("/")[0]
    assert [d.code for d in diags] == ["G020"]
    assert f"--dialect {dialect}" in diags[0].message
