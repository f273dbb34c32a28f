"""The lint rule registry: every rule is a small function over one file's `Analysis`.

A rule is registered with `@rule("M301", "mcode")` and reports through `Context.report`. What a
rule is called, its default severity, its explanation page and whether it has a fix are *not* here:
they come from the code registry (`compiler/codes/*-lint.toml`), so `mcc explain`, SARIF and
docs/rules/ all read one source. A test checks that every lint code has exactly one rule and every
rule a registered code.

Rules of a dialect live in `compiler/lint/<dialect>_rules.py` and are imported on first use, so a
run over MCode files never imports the Arcus rules.
"""

from __future__ import annotations

import importlib
from dataclasses import dataclass, field
from typing import Any, Callable

from mcc.compiler import dialects
from mcc.compiler.codes import CodeInfo, registry
from mcc.compiler.diagnostics import Diagnostic, Diagnostics, Fix
from mcc.compiler.analysis import Analysis
from mcc.compiler.profiles import Profile
from mcc.compiler.span import Span


@dataclass
class Context:
    """What a rule sees: the analysis of one file, and a way to report findings."""

    analysis: Analysis
    profile: Profile
    dialect: str
    diagnostics: Diagnostics = field(default_factory=Diagnostics)
    code: str = ""  # the code of the rule being run; set by the engine
    cache: dict[str, Any] = field(default_factory=dict)  # facts several rules share (per file)
    settings: Any = None  # the file's config.Settings (the envelope rules read `axes`)

    @property
    def source(self):
        return self.analysis.source

    @property
    def tree(self):
        return self.analysis.tree

    @property
    def module(self):
        return self.analysis.module

    def report(self, span: Span, message: str, *, fix: Fix | None = None,
               notes: tuple[str, ...] | list[str] = ()) -> Diagnostic:
        return self.diagnostics.add(self.code, span, message, fix=fix, notes=notes)

    def shared(self, key: str, compute: Callable[[], Any]) -> Any:
        """A per-file fact computed once for all rules that need it (e.g. the call graph)."""
        if key not in self.cache:
            self.cache[key] = compute()
        return self.cache[key]


@dataclass(frozen=True)
class Rule:
    code: str
    dialects: tuple[str, ...]
    check: Callable[[Context], None]

    @property
    def info(self) -> CodeInfo:
        info = registry().get(self.code)
        if info is None:  # caught by tests/lint/test_registry.py
            raise KeyError(f"lint rule {self.code} has no entry in compiler/codes/")
        return info

    @property
    def name(self) -> str:
        return self.info.name


RULES: dict[str, Rule] = {}
_LOADED: set[str] = set()


def rule(code: str, *dialect_names: str) -> Callable[[Callable[[Context], None]], Callable[[Context], None]]:
    """Register a rule function under its diagnostic code."""

    def register(func: Callable[[Context], None]) -> Callable[[Context], None]:
        if code in RULES:
            raise ValueError(f"two lint rules for {code}")
        RULES[code] = Rule(code, tuple(dialect_names), func)
        return func

    return register


def load(dialect: str) -> None:
    """Import the rules of a dialect (once). A dialect without a rules module has no rules yet."""
    if dialect in _LOADED:
        return
    _LOADED.add(dialect)
    importlib.import_module("mcc.compiler.lint.envelope_rules")  # the machine's envelope: every dialect
    try:
        importlib.import_module(f"mcc.compiler.lint.{dialect}_rules")
    except ModuleNotFoundError as exc:
        if exc.name != f"mcc.compiler.lint.{dialect}_rules":
            raise


def load_all() -> dict[str, Rule]:
    for name in dialects.names():
        load(name)
    return RULES


def rules_for(dialect: str) -> list[Rule]:
    load(dialect)
    return [r for code, r in sorted(RULES.items()) if dialect in r.dialects]
