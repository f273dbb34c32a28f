"""End-to-end: odd files and paths through every command that reads or writes files (check, lint,
lint --fix, fmt, compile -o, compile --listing). No traceback, no hang, nothing half-written, and
never the user's source replaced by accident."""

from __future__ import annotations

import os
import stat
from pathlib import Path

import pytest

from conftest import run_mcc

PROGRAM = "PG 1\nLB G1\n  MA 1000\n  H\n  E\nPG\n"  # a clean MCode program
SOURCES = {  # per dialect: a program, and a statement to repeat into a line far past any limit
    "mcode": ("p.mxt", PROGRAM, "MA 1000+"),
    "x150": ("p.x150", "1A10 1V5 1D4000 1G\n", "1G "),
    "arcus": ("p.prg", "X1000\nEND\n", "X1000 "),
}
READERS = {
    "check": ["check"],
    "lint": ["lint"],
    "lint --fix": ["lint", "--fix"],
    "fmt": ["fmt"],
    "fmt --check": ["fmt", "--check"],
    "compile -o": ["compile", "-o", "{out}"],
    "compile --listing": ["compile", "--listing", "{out}"],
}


def command(name: str, path: Path, out: Path) -> list[str]:
    args = [a.format(out=out) for a in READERS[name]]
    return args[:1] + [str(path)] + args[1:]


def no_temporaries(folder: Path) -> None:
    assert not [p.name for p in folder.iterdir() if p.name.endswith(".tmp")]


# reading ---------------------------------------------------------------------------------------------

@pytest.mark.parametrize("name", READERS)
def test_a_fifo_on_the_command_line_is_an_error_not_a_hang(tmp_path: Path, name: str) -> None:
    fifo = tmp_path / "pipe.mxt"
    os.mkfifo(fifo)
    result = run_mcc(*command(name, fifo, tmp_path / "out.mxt"))
    assert result.returncode == 2, result
    assert "FIFO" in result.stderr and "pipe.mxt" in result.stderr and "Traceback" not in result.stderr
    assert stat.S_ISFIFO(os.stat(fifo).st_mode)


@pytest.mark.parametrize("args", [["lint"], ["lint", "--fix"], ["fmt"], ["fmt", "--check"]])
def test_a_fifo_in_a_tree_is_skipped_with_a_note(tmp_path: Path, args: list[str]) -> None:
    (tmp_path / "ok.mxt").write_text(PROGRAM + "S\n' saved\n")  # no warning (M309), which would fail lint
    os.mkfifo(tmp_path / "pipe.mxt")
    result = run_mcc(*args, str(tmp_path))
    assert result.returncode == 0, result
    assert f"note: skipped {tmp_path / 'pipe.mxt'}: it is a FIFO" in result.stderr
    assert "Traceback" not in result.stdout + result.stderr


# writing the compiled program ------------------------------------------------------------------------

@pytest.mark.parametrize("option", ["-o", "--listing"])
def test_compile_never_replaces_its_source_unless_asked(tmp_path: Path, option: str) -> None:
    source = tmp_path / "p.mxt"
    source.write_text(PROGRAM + "' a comment the listing would lose\n")
    before = source.read_text()
    refused = run_mcc("compile", str(source), option, str(source))
    assert refused.returncode == 2 and "--overwrite-input" in refused.stderr and "source file" in refused.stderr
    assert source.read_text() == before
    link = tmp_path / "link.mxt"
    link.symlink_to(source)
    assert run_mcc("compile", str(source), option, str(link)).returncode == 2
    assert source.read_text() == before
    allowed = run_mcc("compile", str(source), option, str(source), "--overwrite-input")
    assert allowed.returncode == 0, allowed.stderr
    assert source.read_text() != before


def test_compile_refuses_the_same_file_for_program_and_listing(tmp_path: Path) -> None:
    source = tmp_path / "p.mxt"
    source.write_text(PROGRAM)
    out = tmp_path / "out.mxt"
    result = run_mcc("compile", str(source), "-o", str(out), "--listing", str(out))
    assert result.returncode == 2 and "--listing" in result.stderr and not out.exists()


def target(tmp_path: Path, case: str) -> Path:
    if case == "fifo":
        os.mkfifo(tmp_path / "pipe.mxt")
        return tmp_path / "pipe.mxt"
    if case == "missing parent":
        return tmp_path / "build" / "out.mxt"
    if case == "parent is a file":
        (tmp_path / "build").write_text("")
        return tmp_path / "build" / "out.mxt"
    if case == "read-only":
        (tmp_path / "out.mxt").write_text("keep\n")
        (tmp_path / "out.mxt").chmod(0o444)
        return tmp_path / "out.mxt"
    if case == "/proc":
        if not os.path.isdir("/proc/self"):
            pytest.skip("no /proc on this system")
        return Path("/proc/mcc-test-output.mxt")
    if case == "/dev/null":
        if not stat.S_ISCHR(os.stat("/dev/null").st_mode):
            pytest.skip("/dev/null is not a character device here")
        return Path("/dev/null")
    raise ValueError(case)


WHY = {"fifo": "FIFO", "missing parent": "does not exist", "parent is a file": "not a directory",
       "read-only": "read-only", "/proc": "/proc", "/dev/null": "character device"}


@pytest.mark.parametrize("option", ["-o", "--listing"])
@pytest.mark.parametrize("case", list(WHY))
def test_write_errors_are_diagnostics_with_exit_two(tmp_path: Path, case: str, option: str) -> None:
    source = tmp_path / "p.mxt"
    source.write_text(PROGRAM)
    out = target(tmp_path, case)
    before = os.stat(out) if os.path.lexists(out) else None
    result = run_mcc("compile", str(source), option, str(out))
    assert result.returncode == 2, result
    assert f"{out}:1:1: error[G006] cannot write {out}" in result.stderr and WHY[case] in result.stderr
    assert "Traceback" not in result.stderr and result.stdout == ""
    if before is not None:
        after = os.stat(out)
        assert (after.st_ino, after.st_mode, after.st_size) == (before.st_ino, before.st_mode, before.st_size)
    else:
        assert not os.path.lexists(out)
    no_temporaries(tmp_path)


@pytest.mark.parametrize("option", ["-o", "--listing"])
def test_a_directory_as_output_is_refused(tmp_path: Path, option: str) -> None:
    source = tmp_path / "p.mxt"
    source.write_text(PROGRAM)
    (tmp_path / "build").mkdir()
    result = run_mcc("compile", str(source), option, str(tmp_path / "build"))
    assert result.returncode == 2 and "directory" in result.stderr and not list((tmp_path / "build").iterdir())


def test_write_errors_in_json(tmp_path: Path) -> None:
    source = tmp_path / "p.mxt"
    source.write_text(PROGRAM)
    result = run_mcc("compile", str(source), "-o", str(tmp_path / "no" / "out.mxt"), "--format", "json")
    assert result.returncode == 2 and '"code": "G006"' in result.stdout and '"text"' not in result.stdout


def test_a_failing_listing_writes_no_program_either(tmp_path: Path) -> None:
    source = tmp_path / "p.mxt"
    source.write_text(PROGRAM)
    out = tmp_path / "out.mxt"
    result = run_mcc("compile", str(source), "-o", str(out), "--listing", str(tmp_path / "no" / "p.lst"))
    assert result.returncode == 2 and not out.exists()


# writing a source back (lint --fix, fmt) ---------------------------------------------------------------

FIXABLE = "PG1\nLB G1\n  E\nPG\n"  # lint --fix: PG1 -> PG 1 (M124); fmt: E unindented


@pytest.mark.parametrize("args", [["lint", "--fix"], ["fmt"]])
def test_a_read_only_source_is_reported_and_left(tmp_path: Path, args: list[str]) -> None:
    path = tmp_path / "p.mxt"
    path.write_text(FIXABLE)
    path.chmod(0o444)
    result = run_mcc(*args, str(path))
    assert result.returncode == 2, result
    assert "read-only" in result.stdout + result.stderr and path.read_text() == FIXABLE
    no_temporaries(tmp_path)


# FIXABLE keeps a warning --fix does not remove (M309, unsafe): --fail-on error lets it pass
@pytest.mark.parametrize("args", [["lint", "--fix", "--fail-on", "error"], ["fmt"]])
def test_a_symlinked_source_is_written_through(tmp_path: Path, args: list[str]) -> None:
    real = tmp_path / "real.mxt"
    real.write_text(FIXABLE)
    real.chmod(0o640)
    link = tmp_path / "link.mxt"
    link.symlink_to(real.name)
    result = run_mcc(*args, str(link))
    assert result.returncode == 0, result
    assert link.is_symlink() and os.readlink(link) == real.name
    assert real.read_text() != FIXABLE and real.read_text().startswith("PG")
    assert stat.S_IMODE(real.stat().st_mode) == 0o640


# lines far past the device's limit -------------------------------------------------------------------

@pytest.mark.parametrize("dialect", list(SOURCES))
@pytest.mark.parametrize("name", READERS)
def test_a_megabyte_line_is_reported_once_and_not_analysed(tmp_path: Path, dialect: str, name: str) -> None:
    filename, program, piece = SOURCES[dialect]
    path = tmp_path / filename
    text = program + piece * (1_000_000 // len(piece)) + "\n" + program
    path.write_text(text)
    out = tmp_path / ("out" + path.suffix)
    result = run_mcc(*command(name, path, out))
    shown = result.stdout + result.stderr
    assert result.returncode == 1, shown[:2000]
    assert "Traceback" not in shown and "G001" not in shown
    assert shown.count("G007") == 1, shown[:2000]
    assert len(shown) < 20_000  # the line is shown as a window, not a megabyte of text
    assert path.read_text() == text and not out.exists()


def test_a_million_digit_x150_number(tmp_path: Path) -> None:
    path = tmp_path / "n.x150"
    path.write_text("1" * 1_000_000 + "\n")
    result = run_mcc("check", str(path))
    assert result.returncode == 1 and result.stdout.count("G007") == 1 and "G001" not in result.stdout
    path.write_text("1" * 5000 + "G\n1V" + "9" * 5000 + "\n")  # long numbers on lines the checks still read
    result = run_mcc("check", str(path))
    assert result.returncode == 1 and "G001" not in result.stdout and "Traceback" not in result.stderr


@pytest.mark.parametrize("args", [["check", "--profile"], ["compile", "--profile"], ["lint", "--config"],
                                  ["fmt", "--config"]])
def test_a_fifo_as_profile_or_configuration_is_an_error_not_a_hang(tmp_path: Path, args: list[str]) -> None:
    source = tmp_path / "p.mxt"
    source.write_text(PROGRAM)
    fifo = tmp_path / "settings.toml"
    os.mkfifo(fifo)
    result = run_mcc(*args, str(fifo), str(source))
    assert result.returncode == 2 and "FIFO" in result.stderr, result


def test_one_file_named_twice_is_fixed_once(tmp_path: Path) -> None:
    real = tmp_path / "p.mxt"
    real.write_text(FIXABLE)
    (tmp_path / "link.mxt").symlink_to(real.name)
    result = run_mcc("lint", "--fix", str(real), str(tmp_path / "link.mxt"), str(tmp_path))
    assert "in 1 file." in result.stdout and real.read_text().startswith("PG 1\n")
