"""The programs the IR contract is checked on: every sample and every golden input of a dialect."""

from __future__ import annotations

from pathlib import Path

from conftest import EXTENSIONS, GOLDEN, sample_files


def program_files(dialect: str) -> list[Path]:
    golden = sorted(GOLDEN.joinpath(dialect).glob(f"*/*{EXTENSIONS[dialect]}"))
    return sample_files(dialect) + golden


def lowered(path: Path, dialect: str):
    """The IR module of `path`, or None when the file has errors (only a program that checks
    clean reaches a backend; an undefined subroutine is the user's error, not a broken IR)."""
    from mcc.compiler import driver

    result = driver.check_file(str(path), dialect)
    if result.has_errors or result.analysis is None:
        return None
    return result.analysis.module


def modules_of(dialect: str):
    """(path, module) for every sample and golden program of `dialect` that lowers, errors or not
    (the printer and the reader work on any module `mcc ir` prints)."""
    from mcc.compiler import driver

    for path in program_files(dialect):
        result = driver.check_file(str(path), dialect)
        if result.analysis is not None and result.analysis.module is not None:
            yield path, result.analysis.module
