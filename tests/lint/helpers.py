"""Helpers for the linter's tests: lint a text without touching the disk."""

from __future__ import annotations

import textwrap

from mcc.compiler.config import Settings
from mcc.compiler.lint import engine


def every_rule() -> Settings:
    """Settings that run every rule, the opt-in ones (A315) too: the rules' own tests check them all."""
    from mcc.compiler import config
    from mcc.compiler.codes import registry

    chosen = tuple(info.code for info in registry() if info.opt_in)
    return Settings(selection=config.Selection((config.DEFAULT_LAYER, config.Layer(extend_select=chosen))))


def lint(text: str, path: str = "program.mxt", settings: Settings | None = None):
    """The diagnostics of `text` (dedented) as `mcc lint --extend-select <the opt-in rules>` would
    report them."""
    _, diags = engine.lint_text(path, textwrap.dedent(text).lstrip("\n"), settings or every_rule())
    return diags


def codes(text: str, path: str = "program.mxt", settings: Settings | None = None) -> list[str]:
    return [d.code for d in lint(text, path, settings)]


def lines_of(code: str, text: str, path: str = "program.mxt") -> list[int]:
    return [d.span.line for d in lint(text, path) if d.code == code]
