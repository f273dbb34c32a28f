"""`mcc lint` end to end: directories, parallel workers, every output format, exit codes."""

from __future__ import annotations

import json
import shutil
from pathlib import Path

import pytest

from conftest import SAMPLES, run_mcc

BAD = "VA Q1\nPG 1\nLB G1\n  MA 100\n  PR P\n  H\n  BR G9\nPG\nS\n' keep\n"  # M306, M301, M106 (error)
GOOD = "VA Q1\nPR Q1\n"


@pytest.fixture
def tree(tmp_path: Path) -> Path:
    (tmp_path / "a").mkdir()
    (tmp_path / "a" / "bad.mxt").write_text(BAD)
    (tmp_path / "a" / "good.ixt").write_text(GOOD)
    (tmp_path / "b").mkdir()
    (tmp_path / "b" / "also.mcode").write_text(BAD)
    (tmp_path / "b" / "notes.txt").write_text("not a program")
    (tmp_path / ".hidden").mkdir()
    (tmp_path / ".hidden" / "skip.mxt").write_text(BAD)
    return tmp_path


def lint_json(*args: str, cwd: Path) -> dict:
    result = run_mcc("lint", "--format", "json", *args, cwd=cwd)
    return json.loads(result.stdout)


def test_directories_are_searched_by_extension(tree: Path) -> None:
    out = lint_json(".", cwd=tree)
    assert [f["path"] for f in out["files"]] == ["a/bad.mxt", "a/good.ixt", "b/also.mcode"]


def test_json_has_the_shape_of_check(tree: Path) -> None:
    lint = lint_json("a/bad.mxt", cwd=tree)
    check = json.loads(run_mcc("check", "--format", "json", "a/bad.mxt", cwd=tree).stdout)
    assert lint.keys() == check.keys() == {"files"}
    [lfile], [cfile] = lint["files"], check["files"]
    assert lfile.keys() == cfile.keys() == {"path", "dialect", "diagnostics"}
    assert {tuple(d) for d in lfile["diagnostics"]} >= {tuple(d) for d in cfile["diagnostics"]}
    keys = {"code", "severity", "kind", "message", "line", "column", "end_line", "end_column"}
    assert all(keys <= set(d) for d in lfile["diagnostics"])
    assert [d["line"] for d in lfile["diagnostics"]] == sorted(d["line"] for d in lfile["diagnostics"])


def test_exit_codes(tree: Path) -> None:
    assert run_mcc("lint", "a/good.ixt", cwd=tree).returncode == 0
    assert run_mcc("lint", "a/bad.mxt", cwd=tree).returncode == 1
    assert run_mcc("lint", "no/such/file.mxt", cwd=tree).returncode == 2
    assert run_mcc("lint", "--format", "xml", "a", cwd=tree).returncode == 2


def test_parallel_and_sequential_runs_agree(tmp_path: Path) -> None:
    for i in range(30):
        shutil.copy(SAMPLES / "mcode" / "pick_and_place.mxt", tmp_path / f"p{i:02}.mxt")
        (tmp_path / f"q{i:02}.mxt").write_text(BAD)
    one = run_mcc("lint", "--jobs", "1", ".", cwd=tmp_path)
    two = run_mcc("lint", "--jobs", "2", ".", cwd=tmp_path)
    assert one.stdout == two.stdout and one.returncode == two.returncode == 1
    assert one.stderr == two.stderr == ""  # no progress bar when stderr is not a terminal
    files = [line.split(":")[0] for line in one.stdout.splitlines() if ": warning[" in line or ": error[" in line]
    assert files == sorted(files)


def test_text_output_shows_the_source_line_and_a_caret(tree: Path) -> None:
    out = run_mcc("lint", "a/bad.mxt", cwd=tree).stdout
    assert "a/bad.mxt:5:3: warning[M301] the position is read while the move at line 4" in out
    assert "    5 |   PR P\n      |   ^^^^\n" in out
    assert "\nFound 1 error, 2 warnings in 1 file.\n" in out


def test_statistics(tree: Path) -> None:
    out = run_mcc("lint", "--statistics", ".", cwd=tree).stdout.splitlines()
    assert out[0].split() == ["2", "M106", "undefined-label"]
    assert {tuple(line.split()[:2]) for line in out} == {("2", "M106"), ("2", "M301"), ("2", "M306")}
    rows = json.loads(run_mcc("lint", "--statistics", "--format", "json", ".", cwd=tree).stdout)["statistics"]
    assert {r["code"]: r["count"] for r in rows} == {"M106": 2, "M301": 2, "M306": 2}
    assert rows[0].keys() == {"code", "name", "severity", "count", "fixable"}


def test_sarif(tree: Path) -> None:
    out = json.loads(run_mcc("lint", "--format", "sarif", ".", cwd=tree).stdout)
    assert out["version"] == "2.1.0" and "sarif-2.1.0" in out["$schema"]
    [run] = out["runs"]
    rules = run["tool"]["driver"]["rules"]
    assert [r["id"] for r in rules] == ["M106", "M301", "M306"]  # one entry per code
    m301 = rules[1]
    assert m301["name"] == "position-read-while-moving"
    assert "## Bad" in m301["help"]["markdown"] and m301["defaultConfiguration"]["level"] == "warning"
    assert len(run["results"]) == 6
    result = next(r for r in run["results"] if r["ruleId"] == "M301")
    assert rules[result["ruleIndex"]]["id"] == "M301"
    location = result["locations"][0]["physicalLocation"]
    assert location["artifactLocation"]["uri"] == "a/bad.mxt"
    assert location["region"] == {"startLine": 5, "startColumn": 3, "endLine": 5, "endColumn": 7}
    assert {r["level"] for r in run["results"]} == {"error", "warning"}


def test_github_annotations(tree: Path) -> None:
    lines = run_mcc("lint", "--format", "github", "a/bad.mxt", cwd=tree).stdout.splitlines()
    assert lines[0] == ("::warning file=a/bad.mxt,line=1,col=4,endLine=1,endColumn=6,title=M306::"
                        "variable Q1 is never used (if a host reads it with PR, suppress this line)")
    assert any(line.startswith("::error file=a/bad.mxt,line=7,") and "title=M106::" in line for line in lines)


def test_unknown_extension_given_explicitly(tree: Path) -> None:
    result = run_mcc("lint", "b/notes.txt", cwd=tree)
    assert result.returncode == 1 and "G004" in result.stdout
    assert run_mcc("lint", "--dialect", "mcode", "--select", "M1", "a/good.ixt", cwd=tree).returncode == 0


def test_default_path_is_the_current_directory(tree: Path) -> None:
    out = lint_json(cwd=tree / "a")
    assert [f["path"] for f in out["files"]] == ["bad.mxt", "good.ixt"]
