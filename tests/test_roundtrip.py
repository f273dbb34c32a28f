"""Round trip and idempotence over every bundled sample, for every dialect with a backend:
what a backend writes, the frontend reads back without errors, and compiling that output again
gives byte-identical text."""

from __future__ import annotations

from pathlib import Path

import pytest

from conftest import EXTENSIONS, dialects_with, sample_files
from mcc.compiler import driver

SAMPLES = [(d, p) for d in dialects_with("backend") for p in sample_files(d)]


@pytest.mark.parametrize("dialect,path", SAMPLES, ids=lambda v: v.name if isinstance(v, Path) else v)
def test_sample_round_trip(dialect: str, path: Path) -> None:
    first = driver.compile_file(str(path), dialect)
    errors = [d for d in first.diagnostics if d.severity.value == "error"]
    assert not errors, f"sample {path.name} has errors: {[(d.code, d.span.line, d.message) for d in errors]}"
    assert first.listing is not None
    text = first.listing.text
    again = driver.compile_file(f"out{EXTENSIONS[dialect]}", dialect, text=text)
    assert not again.has_errors, [(d.code, d.span.line, d.message) for d in again.diagnostics]
    assert again.listing.text == text, "compiling the output again changed it"
