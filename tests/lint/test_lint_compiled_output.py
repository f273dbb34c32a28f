"""mcc's own lint must not flag what `mcc compile` writes.

What a backend writes is linted as a user would lint it; every diagnostic it gets must already be
reported on the source (the output keeps the source's own omissions, such as a program never saved,
but adds none). Cross-dialect outputs are held to the same standard whenever the compile succeeds.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from conftest import EXTENSIONS, dialects_with, sample_files
from mcc.compiler import driver
from mcc.compiler.config import Settings
from mcc.compiler.lint.engine import lint_text


def lint_codes(path: str, text: str) -> set[str]:
    _, diags = lint_text(path, text, Settings())
    return {d.code for d in diags}


def compiled_text(path: Path, target: str) -> str | None:
    result = driver.compile_file(str(path), target=target)
    if result.listing is None or result.has_errors:
        return None
    return result.listing.text


def added_codes(path: Path, target: str, output: str) -> set[str]:
    source_codes = lint_codes(str(path), path.read_text(encoding="utf-8"))
    return lint_codes("compiled" + EXTENSIONS[target], output) - source_codes


SAME = [(d, p) for d in dialects_with("backend") for p in sample_files(d)]


@pytest.mark.parametrize("dialect,path", SAME, ids=[f"{d}-{p.name}" for d, p in SAME])
def test_compiled_sample_is_lint_clean(dialect: str, path: Path) -> None:
    output = compiled_text(path, dialect)
    assert output is not None, f"{path.name} does not compile to {dialect}"
    assert added_codes(path, dialect, output) == set(), output


def test_mcode_output_ends_with_a_comment_after_save() -> None:
    text = "PG 1\nLB G1\n  MR 100\n  E\nPG\nS\n"
    result = driver.compile_file("save.mxt", text=text)
    lines = result.listing.text.splitlines()
    assert lines[-2] == "S" and lines[-1].startswith("'"), lines
    assert "M320" not in lint_codes("out.mxt", result.listing.text)

