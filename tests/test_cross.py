"""Cross-dialect compilation of every sample and golden program, for all six pairs.

Each compilation either writes a program that checks clean in the target dialect and compiles
again to the same text, or refuses with errors that name a line (never an internal error, never
exit 0 with output that does not check)."""

from __future__ import annotations

from pathlib import Path

import pytest

from conftest import EXTENSIONS, GOLDEN, sample_files
from mcc.compiler import driver

DIALECTS = ("mcode", "arcus", "x150")


def programs(dialect: str) -> list[Path]:
    """The samples and the golden programs that check clean (a golden case with an error exists to
    test that error: it is left out here rather than skipped for each target)."""
    golden = sorted(GOLDEN.joinpath(dialect).glob(f"*/*{EXTENSIONS[dialect]}"))
    return sample_files(dialect) + [p for p in golden if not driver.check_file(str(p), dialect).has_errors]


CASES = [(src, tgt, path) for src in DIALECTS for tgt in DIALECTS if tgt != src for path in programs(src)]


def case_id(value):
    return value.parent.name + "/" + value.name if isinstance(value, Path) else value


@pytest.mark.parametrize("source,target,path", CASES, ids=case_id)
def test_cross_compilation_is_right_or_refuses(source: str, target: str, path: Path) -> None:
    assert not driver.check_file(str(path), source).has_errors, "a sample must check clean"
    result = driver.compile_file(str(path), source, target)
    internal = [d.message for d in result.diagnostics if d.kind.value == "internal"]
    assert not internal
    if result.has_errors:
        errors = [d for d in result.diagnostics if d.severity.value == "error"]
        assert all(d.span is not None and d.span.line >= 1 for d in errors)
        return
    assert result.listing is not None
    text = result.listing.text
    again = driver.compile_file(f"out{EXTENSIONS[target]}", target, text=text)
    assert not again.has_errors, [(d.code, d.span.line, d.message) for d in again.diagnostics
                                  if d.severity.value == "error"]
    assert again.listing.text == strip_header(text, target)


def strip_header(text: str, target: str) -> str:
    """The conversion header (comment lines stating the assumptions) is not written again when the
    output is compiled in its own dialect."""
    comment = {"mcode": "'", "arcus": ";", "x150": ";"}[target]
    lines = text.splitlines(keepends=True)
    while lines and lines[0].startswith(comment):
        lines.pop(0)
    return "".join(lines)
