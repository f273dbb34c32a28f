"""Converting a fixture program to another dialect as `mcc compile --target` does, for the
cross-compilation tests (tests/test_cross_*.py): one copy of what each of them needs. Every
conversion is validated by simulation (driver.compile_file verifies by default)."""

from __future__ import annotations

from mcc.compiler import dialects, driver


def extension(dialect: str) -> str:
    return dialects.get(dialect).extensions[0]


def convert(text: str, source: str, target: str):
    """The compile result and its errors as (code, line, message)."""
    result = driver.compile_file(f"fixture{extension(source)}", source, target, text=text)
    errors = [(d.code, d.span.line if d.span else None, d.message) for d in result.diagnostics
              if d.severity.value == "error"]
    return result, errors


def written(text: str, source: str, target: str) -> str:
    """The program written, after checking it converted without errors and checks clean itself."""
    result, errors = convert(text, source, target)
    assert not errors, errors
    out = result.listing.text
    again = driver.compile_file(f"out{extension(target)}", target, text=out)
    assert not again.has_errors, [d.message for d in again.diagnostics if d.severity.value == "error"]
    return out


def body(text: str, target: str) -> list[str]:
    """The statements written, without the conversion header's comments."""
    comment = dialects.get(target).comment
    return [line for line in text.splitlines() if line.strip() and not line.startswith(comment)]
