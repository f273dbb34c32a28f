"""A real editor: headless Neovim (the Debian package; .ci/run installs it) runs `mcc lsp` with its
built-in client, opens a program with a planted error and reads back the diagnostics and a hover;
formats a file with CRLF line ends and writes it, which must give the bytes `mcc fmt` writes; and
saves a file with the fix-on-save autocommand of docs/EDITORS.md, which must write what
`mcc lint --fix` writes."""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

NVIM = shutil.which("nvim")
SCRIPT = Path(__file__).resolve().parent / "nvim" / "check.lua"
PROGRAM = """' planted error on line 3: MA takes a position, not a parenthesised expression
VM=400000
MA (100)
MR 51200
"""



@pytest.fixture(autouse=True)
def neovim_installed() -> None:
    """Without Neovim the tests are skipped, except under CI=true, where they fail: `.ci/run`
    installs Debian's package, so a CI run without it has lost the editor test."""
    if NVIM is None:
        message = "Neovim (nvim) is not installed; `.ci/run` installs the Debian package so this test runs in CI"
        if os.environ.get("CI"):
            pytest.fail(message, pytrace=False)
        pytest.skip(message)


def test_neovim_shows_the_diagnostics_and_a_hover(tmp_path):
    program = tmp_path / "planted.mxt"
    program.write_text(PROGRAM, encoding="utf-8")
    out = tmp_path / "result.json"
    env = {**os.environ, "MCC_NVIM_OUT": str(out), "MCC_PYTHON": sys.executable,
           "MCC_HOVER_LINE": "3", "MCC_HOVER_COL": "0", "XDG_STATE_HOME": str(tmp_path),
           "XDG_DATA_HOME": str(tmp_path), "XDG_CONFIG_HOME": str(tmp_path)}
    subprocess.run([NVIM, "--headless", "--clean", "-n", "-c", f"luafile {SCRIPT}", str(program)],
                   cwd=tmp_path, env=env, timeout=120, capture_output=True, check=False)
    result = json.loads(out.read_text(encoding="utf-8"))
    assert result.get("error") is None, result["error"]
    planted = [d for d in result["diagnostics"] if d["lnum"] == 2]
    assert planted, result["diagnostics"]
    assert planted[0]["source"] == "mcc" and planted[0]["severity"] == 1  # an error
    assert planted[0]["code"] == "M001"
    assert "**MR**" in result.get("hover", "") and "Move relative" in result["hover"]


MESSY = "; cell   \r\nABS\r\nHSPD=30000   \r\nLSPD=500\r\nACC=250\r\nEO=1\r\nX1000\r\nWAITX\r\nEND\r\n\r\n\r\n"


def test_neovim_formatting_writes_what_mcc_fmt_writes(tmp_path):
    program = tmp_path / "messy.prg"
    program.write_bytes(MESSY.encode())
    expected_path = tmp_path / "expected" / "messy.prg"
    expected_path.parent.mkdir()
    expected_path.write_bytes(MESSY.encode())
    subprocess.run([sys.executable, "-m", "mcc", "fmt", str(expected_path)], cwd=tmp_path, check=True,
                   capture_output=True, timeout=120)
    expected = expected_path.read_bytes()
    assert expected != MESSY.encode() and b"\r\n" in expected  # there is something to format, CRLF kept
    out = tmp_path / "result.json"
    env = {**os.environ, "MCC_NVIM_OUT": str(out), "MCC_PYTHON": sys.executable, "MCC_FORMAT": "1",
           "XDG_STATE_HOME": str(tmp_path), "XDG_DATA_HOME": str(tmp_path), "XDG_CONFIG_HOME": str(tmp_path)}
    subprocess.run([NVIM, "--headless", "--clean", "-n", "-c", f"luafile {SCRIPT}", str(program)],
                   cwd=tmp_path, env=env, timeout=120, capture_output=True, check=False)
    result = json.loads(out.read_text(encoding="utf-8"))
    assert result.get("error") is None, result["error"]
    assert result["formatted"] > 0
    assert program.read_bytes() == expected


EDITORS = Path(__file__).resolve().parents[2] / "docs" / "EDITORS.md"
FIXTURE = Path(__file__).resolve().parent / "fixtures" / "feeder.mxt"


def documented_autocommand() -> str:
    """The Lua block of docs/EDITORS.md's "Fix on save" section, as a user copies it."""
    section = EDITORS.read_text(encoding="utf-8").split("## Fix on save", 1)[1]
    return section.split("```lua\n", 1)[1].split("```", 1)[0]


def test_neovim_fix_on_save_writes_what_mcc_lint_fix_writes(tmp_path):
    text = FIXTURE.read_bytes()
    program = tmp_path / "feeder.mxt"
    program.write_bytes(text)
    expected_path = tmp_path / "expected" / "feeder.mxt"
    expected_path.parent.mkdir()
    expected_path.write_bytes(text)
    subprocess.run([sys.executable, "-m", "mcc", "lint", "--fix", "--exit-zero", str(expected_path)], cwd=tmp_path,
                   capture_output=True, timeout=120, check=False)
    expected = expected_path.read_bytes()
    assert expected != text  # the fixture has a safe fix (M321)
    autocmd = tmp_path / "fix_on_save.lua"
    autocmd.write_text(documented_autocommand(), encoding="utf-8")
    out = tmp_path / "result.json"
    env = {**os.environ, "MCC_NVIM_OUT": str(out), "MCC_PYTHON": sys.executable, "MCC_SAVE_WITH": str(autocmd),
           "XDG_STATE_HOME": str(tmp_path), "XDG_DATA_HOME": str(tmp_path), "XDG_CONFIG_HOME": str(tmp_path)}
    subprocess.run([NVIM, "--headless", "--clean", "-n", "-c", f"luafile {SCRIPT}", str(program)],
                   cwd=tmp_path, env=env, timeout=120, capture_output=True, check=False)
    result = json.loads(out.read_text(encoding="utf-8"))
    assert result.get("error") is None, result["error"]
    assert result["saved"] and program.read_bytes() == expected
