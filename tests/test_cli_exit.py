"""At exit the `mcc` process moves its objects to the collector's permanent generation, so that the
interpreter's finalisation does not walk them again (cli/main.py, decision 0024, issue 26); what a
command writes is complete all the same."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

from click.testing import CliRunner

from mcc.cli.commands import cli

PROGRAM = "; a small program\nHSPD=20000\nLSPD=1000\nACC=300\nABS\nX1000\nWAITX\nX0\nWAITX\nEND\n"


def test_the_objects_are_frozen_at_exit(tmp_path: Path) -> None:
    """An exit handler registered before `main` runs after main's own (they run last registered
    first) and sees every object frozen."""
    program = tmp_path / "small.prg"
    program.write_text(PROGRAM, encoding="utf-8")
    probe = ("import atexit, gc, sys\n"
             "atexit.register(lambda: print('frozen', gc.get_freeze_count() > 1000, file=sys.stderr))\n"
             "from mcc.cli.main import main\n"
             f"main(['check', {str(program)!r}])\n")
    done = subprocess.run([sys.executable, "-c", probe], capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    assert done.stderr.strip().splitlines()[-1] == "frozen True"


def test_what_a_process_writes_is_complete(tmp_path: Path) -> None:
    """`mcc compile -o --listing` in its own process writes the files that the same command run in
    this process writes, and its report reaches standard error in full."""
    program = tmp_path / "small.prg"
    program.write_text(PROGRAM, encoding="utf-8")
    here = CliRunner().invoke(cli, ["compile", str(program), "-o", str(tmp_path / "a.prg"),
                                    "--listing", str(tmp_path / "a.lst")])
    assert here.exit_code == 0, here.output
    done = subprocess.run([sys.executable, "-m", "mcc", "compile", str(program), "-o", str(tmp_path / "b.prg"),
                           "--listing", str(tmp_path / "b.lst")], capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    for suffix in (".prg", ".lst"):
        assert (tmp_path / f"b{suffix}").read_bytes() == (tmp_path / f"a{suffix}").read_bytes()
    assert done.stderr.replace("b.prg", "a.prg") == here.output
