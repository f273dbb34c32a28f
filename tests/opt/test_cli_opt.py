"""`mcc compile -O0/-O1/-O2/-Os --passes` as a user runs it: the listing header names the level,
the JSON stats carry the optimization, a bad --passes is a usage error."""

from __future__ import annotations

import json

import pytest

from conftest import run_mcc

# A machine-made program: the same gripper sequence at four places (what -Os outlines).
PROGRAM = "\n".join(["ABS", "HSPD=20000", "HSPD=20000", "LSPD=500", "ACC=200"]
                    + [line for x in (1000, 2000, 3000, 4000)
                       for line in (f"X{x}Y500", "WAITX", "WAITY", "Z-6000", "WAITZ", "DO1=1", "DELAY=250", "Z0",
                                    "WAITZ")]
                    + ["END"]) + "\n"


@pytest.fixture
def program(tmp_path):
    path = tmp_path / "cell.prg"
    path.write_text(PROGRAM)
    return path


@pytest.mark.parametrize("level", ["O0", "O1", "O2", "Os"])
def test_each_level_compiles_and_names_itself_in_the_listing(tmp_path, program, level):
    out, lst = tmp_path / "out.prg", tmp_path / "out.lst"
    result = run_mcc("compile", f"-{level}", str(program), "-o", str(out), "--listing", str(lst))
    assert result.returncode == 0, result.stderr
    assert f"; optimization: -{level}" in lst.read_text().splitlines()[:8]
    assert run_mcc("check", str(out)).returncode == 0
    if level != "O0":
        assert f"optimized -{level}:" in result.stderr


def test_os_is_smaller_and_reports_its_statistics_in_json(tmp_path, program):
    sizes = {}
    for level in ("O0", "Os"):
        result = run_mcc("compile", f"-{level}", "--format", "json", str(program), "-o", str(tmp_path / "o.prg"))
        assert result.returncode == 0, result.stderr
        stats = json.loads(result.stdout)["files"][0]["stats"]
        sizes[level] = stats["asm_lines"]
    opt = stats["optimization"]
    assert opt["level"] == "Os" and not opt["fallback_to_O0"]
    assert opt["target_lines_before"] == sizes["O0"] and opt["target_lines_after"] == sizes["Os"]
    assert opt["target_lines_saved"] == sizes["O0"] - sizes["Os"] > 0
    assert {p["name"] for p in opt["passes"]} >= {"fold", "settings", "outline"}
    assert next(p for p in opt["passes"] if p["name"] == "outline")["ops_removed"] > 0
    assert "GOSUB" in (tmp_path / "o.prg").read_text()


def test_passes_runs_exactly_the_named_passes(tmp_path, program):
    result = run_mcc("compile", "--passes", "settings", "--format", "json", str(program), "--listing",
                     str(tmp_path / "o.lst"), "-o", str(tmp_path / "o.prg"))
    assert result.returncode == 0, result.stderr
    opt = json.loads(result.stdout)["files"][0]["stats"]["optimization"]
    assert [p["name"] for p in opt["passes"]] == ["settings"]
    assert opt["passes"][0]["ops_removed"] == 1  # the repeated HSPD
    assert "; optimization: -O1 (passes settings)" in (tmp_path / "o.lst").read_text()


def test_a_bad_passes_value_is_a_usage_error(program):
    result = run_mcc("compile", "--passes", "fold,nope", str(program))
    assert result.returncode == 2
    assert "unknown pass nope" in result.stderr and "--passes" in result.stderr
    assert "Traceback" not in result.stderr


def test_help_lists_the_levels():
    result = run_mcc("compile", "--help")
    assert result.returncode == 0
    for option in ("-O0", "-O1", "-O2", "-Os", "--passes"):
        assert option in result.stdout
