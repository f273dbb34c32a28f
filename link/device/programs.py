"""Compiling what a virtual device stores into the IR, with mcc's own frontends (public driver)."""

from __future__ import annotations

from mcc.compiler import driver, ir


def module_of(dialect: str, text: str, name: str = "<device>") -> ir.Module | None:
    """The IR of `text`, or None when it does not compile (the device then reports an error)."""
    result = driver.check_file(name, dialect, text=text)
    if result.has_errors or result.analysis is None:
        return None
    return result.analysis.module
