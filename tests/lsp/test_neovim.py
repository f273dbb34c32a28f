"""A real editor: headless Neovim (the Debian package; .ci/run installs it) runs `mcc lsp` with its
built-in client, opens a program with a planted error and reads back the diagnostics and a hover."""

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

pytestmark = pytest.mark.skipif(NVIM is None, reason="Neovim (nvim) is not installed; `.ci/run` installs the "
                                                      "Debian package so this test runs in CI")


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
