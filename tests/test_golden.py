"""Golden cases: tests/golden/<dialect>/<case>/ holds an input file and what mcc must say about it.

- `input.<ext>`: the program;
- `expected.diag`: one diagnostic per line, `LINE:COLUMN CODE` (empty file: no diagnostics);
- `expected.out` (optional): the compiled program, when the input compiles;
- `expected.lst` (optional): the listing, source map included;
- `profile.toml` (optional): the target profile to check against (default: the dialect's).

Regenerate after an intended change with `MCC_UPDATE_GOLDEN=1 pytest tests/test_golden.py` and
review the diff before committing it.
"""

from __future__ import annotations

import os
from pathlib import Path

import pytest

from conftest import EXTENSIONS, GOLDEN, dialects_with
from mcc.compiler import driver, profiles

UPDATE = os.environ.get("MCC_UPDATE_GOLDEN") == "1"


def cases() -> list[Path]:
    return sorted(p for p in GOLDEN.glob("*/*") if p.is_dir() and p.parent.name in dialects_with("backend"))


def render_diags(result) -> str:
    rows = sorted((d.span.line, d.span.column, d.code) for d in result.diagnostics)
    return "".join(f"{line}:{col} {code}\n" for line, col, code in rows)


def check_or_update(path: Path, actual: str) -> None:
    if UPDATE:
        path.write_text(actual, encoding="utf-8")
        return
    assert path.exists(), f"{path} is missing (run with MCC_UPDATE_GOLDEN=1 to create it)"
    expected = path.read_text(encoding="utf-8")
    assert actual.splitlines() == expected.splitlines(), f"{path} differs"


@pytest.mark.parametrize("case", cases(), ids=lambda p: f"{p.parent.name}/{p.name}")
def test_golden(case: Path) -> None:
    dialect = case.parent.name
    source = case / f"input{EXTENSIONS[dialect]}"
    profile_path = case / "profile.toml"
    profile = profiles.load(str(profile_path)) if profile_path.exists() else None
    result = driver.compile_file(str(source), dialect, profile=profile)
    for diag in result.diagnostics:
        assert diag.kind.value != "internal", diag.message
    check_or_update(case / "expected.diag", render_diags(result))
    out = case / "expected.out"
    if result.listing is not None and not result.has_errors:
        check_or_update(out, result.listing.text)
        lst = case / "expected.lst"
        if lst.exists() or UPDATE:
            rendered = result.listing.render().replace(str(case) + "/", "")
            check_or_update(lst, rendered)
    else:
        assert not out.exists() or UPDATE, f"{case.name}: expected output, but the file did not compile"
