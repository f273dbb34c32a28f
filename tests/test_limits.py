"""Inputs at and past mcc's bounds: huge numbers (G030), statements nested too deep (G031), deeply
nested blocks and long call chains. Each gives the file's own diagnostics, never an internal error
(G001), for check, lint, fmt and compile to every target."""

from __future__ import annotations

import pytest

from conftest import EXTENSIONS
from mcc.compiler import driver
from mcc.compiler.config import Settings
from mcc.compiler.lint import engine, formatting
from test_fuzz import LONG_EXPRESSION, nested

TARGETS = ("mcode", "arcus", "x150")
HUGE = "7" * 5000
# A line that assigns a number, in each dialect, inside a minimal program.
ASSIGN = {
    "arcus": ("{}\nEND\n", "V1={}"),
    "mcode": ("PG 1\n{}\nE\nPG\n", "R1={}"),
    "x150": ("1XE1\n1XD1\n{}\n1XT\n", "1VAR1={}"),
}


def codes(dialect: str, text: str) -> dict[str, list]:
    """Diagnostics of check, lint and compile to every target; asserts none is internal."""
    path = f"f{EXTENSIONS[dialect]}"
    found = {"check": driver.check_file(path, text=text).diagnostics,
             "lint": engine.lint_text(path, text, Settings())[1]}
    for target in TARGETS:
        found[target] = driver.compile_file(path, target=target, text=text).diagnostics
    for stage, diags in found.items():
        internal = [d.message for d in diags if d.code == "G001"]
        assert not internal, (stage, internal)
    return found


def program(dialect: str, line: str) -> str:
    template, _ = ASSIGN[dialect]
    return template.format(line)


@pytest.mark.parametrize("dialect", sorted(ASSIGN))
@pytest.mark.parametrize("digits", [41, 400, 3000])  # longer lines are G007 (not analysed)
def test_a_number_too_long_is_g006_at_its_place(dialect: str, digits: int) -> None:
    line = ASSIGN[dialect][1].format("7" * digits)
    found = codes(dialect, program(dialect, line))
    g006 = [d for d in found["check"] if d.code == "G030"]
    assert len(g006) == 1
    assert g006[0].span.column == line.index("7") + 1 and g006[0].span.end_column - g006[0].span.column == digits
    assert all(any(d.code == "G030" for d in diags) for diags in found.values())


@pytest.mark.parametrize("dialect", sorted(ASSIGN))
def test_forty_digits_and_digits_in_comments_are_not_refused(dialect: str) -> None:
    comment = {"arcus": ";", "mcode": "`", "x150": ";"}[dialect]
    text = program(dialect, ASSIGN[dialect][1].format("1" + "0" * 39)) + f"{comment} serial {HUGE}\n"
    assert not any(d.code == "G030" for d in codes(dialect, text)["check"])


@pytest.mark.parametrize("dialect", sorted(ASSIGN))
def test_a_statement_nested_too_deep_is_g007(dialect: str) -> None:
    found = codes(dialect, program(dialect, LONG_EXPRESSION[dialect](600)))
    assert [d.code for d in found["check"] if d.code == "G031"] == ["G031"]
    shallow = codes(dialect, program(dialect, LONG_EXPRESSION[dialect](20)))
    assert not any(d.code == "G031" for d in shallow["check"])


@pytest.mark.parametrize("dialect", sorted(ASSIGN))
def test_fmt_keeps_refused_lines_as_written(dialect: str, tmp_path) -> None:
    deep = LONG_EXPRESSION[dialect](600)
    text = program(dialect, ASSIGN[dialect][1].format(HUGE)) + deep + "\n"
    path = tmp_path / f"f{EXTENSIONS[dialect]}"
    path.write_text(text, encoding="utf-8")
    outcome = formatting.format_file(str(path), Settings())
    assert "internal" not in outcome.error
    after = path.read_text(encoding="utf-8")
    assert HUGE in after and deep in after


@pytest.mark.parametrize("kind", ["if", "while", "ifelse"])
def test_arcus_blocks_500_deep(kind: str) -> None:
    found = codes("arcus", nested("arcus", kind, 500))
    # only the program memory (A201: `mcc check` prices the program since issue 12) may be over
    assert not [d for d in found["check"] if d.severity.value == "error" and d.code != "A201"]
    fallback = [d for d in found["arcus"] if d.code == "A202"]
    assert fallback and "nest more than 64 deep" in fallback[0].message  # written as a flat dispatch loop
    assert not any(d.code == "A202" for d in codes("arcus", nested("arcus", kind, 60))["arcus"])


@pytest.mark.parametrize("kind", ["if", "while"])
def test_x150_blocks_500_deep_are_x110(kind: str) -> None:
    found = codes("x150", nested("x150", kind, 500))
    assert any(d.code == "X110" for d in found["check"])  # the manual's limit: 16 levels


@pytest.mark.parametrize("kind", ["if", "while"])  # CL chain, BR chain
def test_mcode_500_calls_or_branches_deep(kind: str) -> None:
    found = codes("mcode", nested("mcode", kind, 500))
    assert any(d.code == "M116" for d in found["check"])  # more labels than the name table holds


def test_mcode_deep_call_chain_within_the_name_table_is_linted() -> None:
    found = codes("mcode", nested("mcode", "if", 150))
    assert not [d for d in found["check"] if d.severity.value == "error"]


def test_fmt_of_a_file_it_cannot_format_reports_the_files_own_errors(tmp_path, monkeypatch) -> None:
    path = tmp_path / "bad.prg"
    path.write_text("V1=(2)\nX1000\nEND\n", encoding="utf-8")
    monkeypatch.setattr(formatting, "verify", lambda *args: "an instruction differs")
    monkeypatch.setattr(formatting, "format_text", lambda text, *args: text + "\n")
    outcome = formatting.format_file(str(path), Settings())
    assert outcome.error.startswith("not formatted: the file has errors (1:")
    assert "A001" in outcome.error and "internal" not in outcome.error


@pytest.mark.parametrize("command", [["check"], ["lint"], ["fmt", "--check"], ["compile", "--target", "mcode"]])
def test_the_mcc_command_on_a_deep_nest_and_a_huge_number(command: list[str], tmp_path, mcc) -> None:
    deep = tmp_path / "deep.prg"
    deep.write_text(nested("arcus", "ifelse", 500), encoding="utf-8")
    huge = tmp_path / "huge.x150"
    huge.write_text(program("x150", ASSIGN["x150"][1].format(HUGE)), encoding="utf-8")
    for path in (deep, huge):
        run = mcc(*command, str(path))
        assert run.returncode in (0, 1), run.stderr
        assert "Traceback" not in run.stderr and "G001" not in run.stdout + run.stderr
    assert "G030" in mcc("check", str(huge)).stdout
