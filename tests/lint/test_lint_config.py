"""Configuration: discovery, ruff-style selection, per-file ignores, severities, and mistakes in
the configuration reported with the file and line of the key."""

from __future__ import annotations

import json
import textwrap
from pathlib import Path

import pytest

from conftest import run_mcc
from helpers import codes
from mcc.compiler import config
from mcc.compiler.config import Layer, Selection, Settings

BAD = "VA Q1\nPG 1\nLB G1\n  R1=R2+R3*2\n  E\nPG\n"  # M306 (Q1 unused), M311 (mixed), M309 (no S)


def write(path: Path, text: str) -> Path:
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(textwrap.dedent(text).lstrip("\n"), encoding="utf-8")
    return path


# selection -------------------------------------------------------------------------------------

@pytest.mark.parametrize("layers,code,expected", [
    ((Layer(select=("ALL",)),), "M301", True),
    ((Layer(select=("M3",)),), "G101", False),
    ((Layer(select=("M3",), ignore=("M301",)),), "M301", False),
    ((Layer(select=("M3",), ignore=("M301",)),), "M302", True),
    ((Layer(select=("M301",), ignore=("M3",)),), "M301", True),  # the more specific prefix wins
    ((Layer(select=("M3",), ignore=("M3",)),), "M305", False),  # a tie goes to ignore
    ((Layer(select=("ALL",)), Layer(ignore=("M3",))), "M305", False),
    ((Layer(select=("ALL",), ignore=("M3",)), Layer(extend_select=("M305",))), "M305", True),
    ((Layer(select=("ALL",), ignore=("M3",)), Layer(select=("M30",))), "M305", True),  # a select starts afresh
    ((Layer(select=("ALL",)), Layer(select=("M31",))), "M305", False),
])
def test_selection_follows_ruff(layers, code: str, expected: bool) -> None:
    assert Selection(layers).enabled(code) is expected


def test_syntax_and_internal_errors_cannot_be_deselected() -> None:
    selection = Selection((Layer(select=("M3",), ignore=("M0", "G0")),))
    assert selection.enabled("M001") and selection.enabled("G001")
    assert not selection.enabled("M101")  # a semantic check can be


def test_ignore_in_settings_removes_findings() -> None:
    settings = Settings(selection=Selection((Layer(select=("ALL",), ignore=("M306", "M309")),)))
    assert codes(BAD, settings=settings) == ["M311"]


def test_severity_override_by_code_and_prefix() -> None:
    from helpers import lint

    settings = Settings(severity=(("M3", "info"), ("M311", "error")))
    found = {d.code: d.severity.value for d in lint(BAD, settings=settings)}
    assert found == {"M306": "info", "M311": "error", "M309": "info"}


# discovery and files --------------------------------------------------------------------------

def test_nearest_configuration_wins(tmp_path: Path) -> None:
    write(tmp_path / "pyproject.toml", """
        [tool.mcc]
        ignore = ["M311"]
    """)
    write(tmp_path / "sub" / "mcc.toml", """
        ignore = ["M306"]
    """)
    write(tmp_path / "sub" / "deeper" / "pyproject.toml", "[project]\nname = 'x'\n")  # no [tool.mcc]: skipped
    top = config.Resolver().for_path(str(tmp_path / "a.mxt"))
    deep = config.Resolver().for_path(str(tmp_path / "sub" / "deeper" / "b.mxt"))
    assert not top.enabled("M311", "a.mxt") and top.enabled("M306", "a.mxt")
    assert deep.enabled("M311", "b.mxt") and not deep.enabled("M306", "b.mxt")


def test_mcc_toml_wins_over_pyproject_in_the_same_directory(tmp_path: Path) -> None:
    write(tmp_path / "pyproject.toml", '[tool.mcc]\nignore = ["M311"]\n')
    write(tmp_path / "mcc.toml", 'ignore = ["M306"]\n')
    assert config.find(str(tmp_path)) == str(tmp_path / "mcc.toml")


def test_per_file_ignores_with_globs(tmp_path: Path) -> None:
    write(tmp_path / "mcc.toml", """
        [per-file-ignores]
        "legacy/*" = ["M3"]
        "*.ixt" = ["M311"]
    """)
    settings = config.Resolver().for_path(str(tmp_path / "x.mxt"))
    legacy = str(tmp_path / "legacy" / "old.mxt")
    assert not settings.enabled("M305", legacy) and settings.enabled("M101", legacy)
    assert not settings.enabled("M311", str(tmp_path / "deep" / "prog.ixt"))
    assert settings.enabled("M311", str(tmp_path / "prog.mxt"))


def test_target_profile_relative_to_the_config_file(tmp_path: Path) -> None:
    write(tmp_path / "profiles" / "mine.toml", 'extends = "lmd-e"\nname = "mine"\n')
    write(tmp_path / "mcc.toml", 'target = "profiles/mine.toml"\n')
    settings = config.Resolver().for_path(str(tmp_path / "p.mxt"))
    assert settings.profile("mcode").name == "mine"
    assert settings.profile("arcus") is None  # other dialects keep their default


def test_target_changes_what_is_checked(tmp_path: Path) -> None:
    prog = write(tmp_path / "p.mxt", "PY=1\n")  # serial-only command (M114 on Ethernet, L1178)
    assert run_mcc("lint", str(prog)).returncode == 0
    write(tmp_path / "mcc.toml", 'target = "lmd-e"\n')
    result = run_mcc("lint", str(prog))
    assert result.returncode == 1 and "M114" in result.stdout


# mistakes in the configuration ----------------------------------------------------------------

def config_diags(tmp_path: Path, text: str, name: str = "pyproject.toml"):
    path = write(tmp_path / name, text)
    return config.parse(path.read_text(), str(path), name).diagnostics


def test_unknown_key_is_reported_at_its_line(tmp_path: Path) -> None:
    diags = config_diags(tmp_path, """
        [project]
        name = "demo"

        [tool.mcc]
        select = ["M3"]
        per_file_ignores = {}
    """)
    assert [(d.code, d.span.line, d.span.column) for d in diags] == [("G102", 6, 1)]
    assert "per-file-ignores" in diags[0].message  # the near miss is named


def test_unknown_codes_are_reported_where_they_are_written(tmp_path: Path) -> None:
    diags = config_diags(tmp_path, """
        [tool.mcc]
        select = [
            "M3",
            "M999",
        ]
        ignore = ["Q1"]

        [tool.mcc.severity]
        M301 = "error"
        M998 = "warning"
        M302 = "fatal"

        [tool.mcc.per-file-ignores]
        "old/*" = ["M3", "XYZ1"]
    """)
    found = [(d.code, d.span.line, d.span.column) for d in diags]
    assert found == [("G103", 4, 5), ("G103", 6, 11), ("G103", 10, 1), ("G103", 11, 1), ("G103", 14, 18)]


def test_inline_tables_and_mcc_toml_positions(tmp_path: Path) -> None:
    diags = config_diags(tmp_path, """
        # mcc.toml keys are at the top level
        severity = { M301 = "error", M997 = "info" }
        fail-on = "sometimes"
        target = "no-such-profile"
    """, name="mcc.toml")
    found = [(d.code, d.span.line) for d in diags]
    assert found == [("G103", 2), ("G103", 3), ("G103", 4)]
    inline = next(d for d in diags if d.span.line == 2)
    assert inline.span.column == 30  # at M997, inside the inline table


def test_invalid_toml_is_reported_at_its_line(tmp_path: Path) -> None:
    diags = config_diags(tmp_path, '[tool.mcc]\nselect = ["M3"\n', name="mcc.toml")
    assert [d.code for d in diags] == ["G103"] and diags[0].span.line in (2, 3)


def test_lint_reports_configuration_errors_with_file_and_line(tmp_path: Path) -> None:
    write(tmp_path / "pyproject.toml", '[tool.mcc]\nselekt = ["M3"]\nignore = ["M306"]\n')
    write(tmp_path / "p.mxt", BAD)
    result = run_mcc("lint", "--format", "json", ".", cwd=tmp_path)
    assert result.returncode == 1
    files = {f["path"]: f for f in json.loads(result.stdout)["files"]}
    [diag] = files["pyproject.toml"]["diagnostics"]
    assert (diag["code"], diag["line"]) == ("G102", 2)
    assert files["pyproject.toml"]["dialect"] == "config"
    assert "M306" not in [d["code"] for d in files["p.mxt"]["diagnostics"]]  # the rest still applies
    text = run_mcc("lint", ".", cwd=tmp_path).stdout
    assert "pyproject.toml:2:1: error[G102] unknown configuration key 'selekt'; did you mean 'select'?" in text


# command-line overrides -----------------------------------------------------------------------

def test_command_line_select_replaces_and_ignore_extends(tmp_path: Path) -> None:
    write(tmp_path / "mcc.toml", 'ignore = ["M311"]\n')
    write(tmp_path / "p.mxt", BAD)

    def found(*args: str) -> set[str]:
        out = json.loads(run_mcc("lint", "--format", "json", *args, "p.mxt", cwd=tmp_path).stdout)
        return {d["code"] for f in out["files"] for d in f["diagnostics"]}

    assert found() == {"M306", "M309"}
    assert found("--ignore", "M309") == {"M306"}
    assert found("--select", "M311,M306") == {"M306", "M311"}
    assert found("--extend-select", "M311") == {"M306", "M309", "M311"}
    assert found("--isolated") == {"M306", "M309", "M311"}


def test_config_option_uses_one_file(tmp_path: Path) -> None:
    other = write(tmp_path / "elsewhere" / "strict.toml", 'select = ["M311"]\n')
    write(tmp_path / "p.mxt", BAD)
    out = json.loads(run_mcc("lint", "--format", "json", "--config", str(other), "p.mxt", cwd=tmp_path).stdout)
    assert [d["code"] for f in out["files"] for d in f["diagnostics"]] == ["M311"]


def test_unknown_code_on_the_command_line_is_a_usage_error(tmp_path: Path) -> None:
    write(tmp_path / "p.mxt", BAD)
    result = run_mcc("lint", "--select", "M999", "p.mxt", cwd=tmp_path)
    assert result.returncode == 2 and "M999" in result.stderr


def test_fail_on_warning(tmp_path: Path) -> None:
    """Warnings fail `mcc lint` by default (as any finding fails ruff, so the pre-commit hook blocks
    them); `fail-on = "error"` or `--fail-on error` lets them pass, `--exit-zero` passes all."""
    write(tmp_path / "p.mxt", BAD)
    assert run_mcc("lint", "p.mxt", cwd=tmp_path).returncode == 1
    assert run_mcc("lint", "--fail-on", "error", "p.mxt", cwd=tmp_path).returncode == 0
    write(tmp_path / "mcc.toml", 'fail-on = "error"\n')
    assert run_mcc("lint", "p.mxt", cwd=tmp_path).returncode == 0
    assert run_mcc("lint", "--fail-on", "warning", "p.mxt", cwd=tmp_path).returncode == 1
    write(tmp_path / "mcc.toml", 'fail-on = "warning"\n')
    assert run_mcc("lint", "p.mxt", cwd=tmp_path).returncode == 1
    assert run_mcc("lint", "--exit-zero", "p.mxt", cwd=tmp_path).returncode == 0


def test_exclude_skips_directories_but_not_explicit_files(tmp_path: Path) -> None:
    write(tmp_path / "mcc.toml", 'exclude = ["build"]\n')
    write(tmp_path / "build" / "out.mxt", "MX 1\n")
    write(tmp_path / "src" / "ok.mxt", "VA Q1\nPR Q1\n")
    assert run_mcc("lint", ".", cwd=tmp_path).returncode == 0
    assert run_mcc("lint", "build/out.mxt", cwd=tmp_path).returncode == 1
