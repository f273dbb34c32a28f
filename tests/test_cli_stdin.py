"""`mcc check -`, `mcc lint -` and `mcc fmt -`: a program read from standard input, as editor
plugins (conform.nvim, ALE, ruff-style integrations) call mcc, named by --stdin-filename."""

from __future__ import annotations

import json

from conftest import run_mcc

GOOD = "VA Np=0\nPG 100\n  Np=Np+1\n  E\nPG\nS\n"
UNFORMATTED = "VA Np=0\nPG 100\nNp=Np+1\n      E\nPG\nS\n"
FIXABLE = "PG 100\n  BR G1,I5=<100\n  LB G1\nE\nPG\nS\n"
SYNTAX = "PG 100\n  MA 1000,,\nE\nPG\n"


def test_check_reads_standard_input_named_by_stdin_filename():
    done = run_mcc("check", "-", "--stdin-filename", "cell/feeder.mxt", "--format", "json", input=SYNTAX)
    assert done.returncode == 1
    [entry] = json.loads(done.stdout)["files"]
    assert entry["path"] == "cell/feeder.mxt"
    assert [d["code"] for d in entry["diagnostics"]] == ["M001"] and entry["diagnostics"][0]["line"] == 2
    assert run_mcc("check", "-", "--stdin-filename", "feeder.mxt", input=GOOD).returncode == 0


def test_the_dialect_of_standard_input_comes_from_its_name_or_dialect():
    done = run_mcc("check", "-", input=GOOD)
    assert done.returncode == 2 and "--stdin-filename" in done.stderr
    assert run_mcc("check", "-", "--dialect", "mcode", input=GOOD).returncode == 0
    assert run_mcc("check", "-", "other.mxt", "--stdin-filename", "a.mxt", input=GOOD).returncode == 2


def test_fmt_writes_the_formatted_program_to_standard_output():
    done = run_mcc("fmt", "-", "--stdin-filename", "a.mxt", input=UNFORMATTED)
    assert done.returncode == 0
    assert done.stdout == GOOD
    again = run_mcc("fmt", "-", "--stdin-filename", "a.mxt", input=done.stdout)
    assert again.stdout == done.stdout  # idempotent
    check = run_mcc("fmt", "--check", "-", "--stdin-filename", "a.mxt", input=UNFORMATTED)
    assert check.returncode == 1 and "Would reformat: a.mxt" in check.stdout


def test_fmt_refuses_a_program_with_a_syntax_error():
    """Reformatting around a line that does not parse would guess at its meaning: mcc fmt, like
    black and ruff, leaves such a program alone and says where the error is."""
    done = run_mcc("fmt", "-", "--stdin-filename", "a.mxt", input=SYNTAX)
    assert done.returncode == 1 and done.stdout == ""
    assert "syntax error at 2:" in done.stderr and "M001" in done.stderr


def test_fmt_refuses_a_file_with_a_syntax_error(tmp_path):
    path = tmp_path / "a.mxt"
    path.write_text(SYNTAX.replace("PG 100\n", "PG   100\n"))
    done = run_mcc("fmt", str(path))
    assert done.returncode == 1 and "syntax error at 2:" in done.stderr
    assert path.read_text() == SYNTAX.replace("PG 100\n", "PG   100\n")


def test_lint_fix_on_standard_input_prints_the_fixed_program_and_reports_on_stderr():
    done = run_mcc("lint", "--fix", "-", "--stdin-filename", "a.mxt", input=FIXABLE)
    assert done.stdout.startswith(FIXABLE.replace("=<", "<="))
    assert "Fixed 2 problems in 1 file." in done.stderr and "No problems found" in done.stderr
    plain = run_mcc("lint", "-", "--stdin-filename", "a.mxt", input=FIXABLE)
    assert plain.returncode == 1 and "M321" in plain.stdout and "a.mxt:2:" in plain.stdout  # warnings fail lint


def test_lint_on_standard_input_reads_the_configuration_next_to_its_name(tmp_path):
    (tmp_path / "mcc.toml").write_text('ignore = ["M321"]\n')
    done = run_mcc("lint", "-", "--stdin-filename", str(tmp_path / "a.mxt"), input=FIXABLE)
    assert "M321" not in done.stdout


def test_bytes_that_are_not_utf8_are_read_as_a_files_are():
    """Standard input is decoded as a file is (UTF-8, else Latin-1): a diagnostic, no traceback."""
    import os
    import subprocess
    import sys
    from pathlib import Path

    exe = Path(sys.executable).parent / "mcc"
    done = subprocess.run([str(exe), "check", "-", "--stdin-filename", "a.mxt"], input=b"PG 100\n\xff\xfe E\nPG\n",
                          capture_output=True, timeout=120, env={**os.environ, "NO_COLOR": "1"})
    assert done.returncode == 1 and b"Traceback" not in done.stderr
    assert b"a.mxt:2:1: error" in done.stdout
