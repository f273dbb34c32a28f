"""Completion in a real editor: headless Neovim (Debian's package, 0.7; `.ci/run` installs it)
with its built-in LSP client and omni completion, typing as a user does (`A`, then CTRL-X CTRL-O,
CTRL-N, CTRL-Y: tests/editors/nvim/complete.lua). After a device address (`1D`), an axis letter
(`XV2`) or a branch's comma (`BR G1,I`) the popup must hold the items, each replacing only the
word being typed (its textEdit range), and the chosen item must leave the address, the axis letter
and the branch in front of it. Without Neovim the tests are skipped, except under CI=true, where
they fail."""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

SCRIPT = Path(__file__).resolve().parent / "nvim" / "complete.lua"


@pytest.fixture(scope="module")
def nvim() -> str:
    found = shutil.which("nvim")
    if found is None:
        message = "Neovim (nvim) is not installed: apt-get install neovim"
        if os.environ.get("CI"):
            pytest.fail(message + " (.ci/run must install it)", pytrace=False)
        pytest.skip(message)
    return found


def complete(nvim: str, tmp_path: Path, name: str, text: str, line: int, pick: str) -> dict:
    """Type CTRL-X CTRL-O at the end of 1-based `line` of a file holding `text` and accept the
    item labelled `pick`: the popup's items (word, label, range) and the line after it."""
    program = tmp_path / name
    program.write_text(text, encoding="utf-8")
    out = tmp_path / "result.json"
    env = {**os.environ, "MCC_NVIM_OUT": str(out), "MCC_PYTHON": sys.executable, "MCC_LINE": str(line),
           "MCC_PICK": pick, "XDG_STATE_HOME": str(tmp_path), "XDG_DATA_HOME": str(tmp_path),
           "XDG_CONFIG_HOME": str(tmp_path)}
    subprocess.run([nvim, "--headless", "--clean", "-n", "-c", f"luafile {SCRIPT}", str(program)],
                   cwd=tmp_path, env=env, timeout=180, capture_output=True, check=False)
    result = json.loads(out.read_text(encoding="utf-8"))
    assert result.get("error") is None, result
    return result


def ranges(result: dict) -> set[tuple[int, int, int, int]]:
    return {(r["start"]["line"], r["start"]["character"], r["end"]["line"], r["end"]["character"])
            for r in (item["range"] for item in result["items"])}


def test_x150_command_after_a_device_address(nvim, tmp_path):
    """parker-x150.md L179: a command is made device specific by its device address (`1D`). The
    popup offers the commands starting with D, each replacing the `D` only (line 2, characters
    1-2); accepting D (distance, `D±n` as its snippet reads in Neovim 0.7) keeps the address."""
    result = complete(nvim, tmp_path, "addressed.x150", "1CUR4000\n1D\n", 2, "D")
    labels = [item["abbr"] for item in result["items"]]
    assert "D" in labels and all(label.startswith("D") for label in labels)
    assert ranges(result) == {(1, 1, 1, 2)}
    word = next(item["word"] for item in result["items"] if item["abbr"] == "D")
    assert result["line"] == "1" + word and result["line"].startswith("1D")


def test_arcus_variable_after_an_axis_letter(nvim, tmp_path):
    """arcus-pmx-4ex-sa.txt L2759: `XV10` moves X to the value of V10. After `XV2` the variables
    starting with V2 are offered, replacing `V2` (line 3, characters 1-3); V21 gives `XV21`."""
    result = complete(nvim, tmp_path, "target.prg", "V21=1200\nV3=5\nXV2\nEND\n", 3, "V21")
    labels = [item["abbr"] for item in result["items"]]
    assert "V21" in labels and not {"HSPD", "ABS", "END"} & set(labels)  # a move target: a variable
    assert ranges(result) == {(2, 1, 2, 3)}
    assert result["line"] == "XV21"


@pytest.mark.parametrize("typed,pick", [("  BR G1,I", "IN"), ("  BR G1,N", "Np")])
def test_mcode_condition_after_a_branch(nvim, tmp_path, typed, pick):
    """lexium-mcode.txt L1807 (BR <label>, [VAR/FLG/IN]<condition>): after the comma the variables,
    flags and inputs are offered, replacing only what follows the comma; the label stays."""
    text = f"VA Np=0\nPG 1\nLB G1\n{typed}\n  E\nPG\n"
    result = complete(nvim, tmp_path, "branch.mxt", text, 4, pick)
    labels = [item["abbr"] for item in result["items"]]
    assert pick in labels and "G1" not in labels  # a condition, not a label
    assert ranges(result) == {(3, 8, 3, 9)}
    assert result["line"] == typed[:8] + pick
