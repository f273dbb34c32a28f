"""The lint rule registry: every rule is a small function over one file's `Analysis`.

A rule is one module, `compiler/lint/rules/<package>/<code>_<name>.py` (`mcode/m302_branch_out_of_
subroutine.py`), whose docstring is the rule's page (what `mcc explain M302` prints: what it finds,
why it matters with the manual lines, a bad and a good example) and whose `@rule` function reports
through `Context.report`. The code registry (compiler/codes.py) reads the rule's name, severity,
dialects and whether it has a fix from that page, so `mcc explain`, SARIF and docs/rules/ have one
source; `@rule` takes the code from the module's name. A rule that means the same in every dialect
is written once in `rules/shared/` and each dialect's module gives it its code, page and words
(`shared.voice.speak`).

A package is a dialect's rules (`mcode`, `x150`, `arcus`) or rules of every dialect (`envelope`);
importing the package imports its rule modules (`discover`), and `load(dialect)` imports only that
dialect's package (and `envelope`), on first use: a run over MCode files never imports the Arcus
rules. Helpers several rules of a package share live in its `helpers.py`. Each rule has a fixture,
tests/lint/fixtures/<CODE>.<ext> (tests/lint/test_rule_fixtures.py).
"""

from __future__ import annotations

import importlib
import pkgutil
from dataclasses import dataclass, field
from typing import Any, Callable

from mcc.compiler import dialects
from mcc.compiler.codes import RULE_NAME, CodeInfo, registry
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
    voice: Any = None  # the shared.voice.Voice a rule written once for every dialect speaks with

    @property
    def info(self) -> CodeInfo:
        info = registry().get(self.code)
        if info is None:  # caught by tests/lint/test_rule_modules.py
            raise KeyError(f"lint rule {self.code} has no page (its module's docstring)")
        return info

    @property
    def name(self) -> str:
        return self.info.name


RULES: dict[str, Rule] = {}
_LOADED: set[str] = set()
EVERY_DIALECT = "envelope"  # the package of the rules every dialect has


def code_of(module_name: str) -> str:
    """The code of the rule a module holds, from its name (`...mcode.m302_branch_out_...` -> M302)."""
    match = RULE_NAME.match(module_name.rpartition(".")[2])
    if match is None:
        raise ValueError(f"{module_name} is not a rule module: name it <code>_<name>, e.g. m302_branch_out_of_"
                         "subroutine")
    return match.group(1).upper()


def add(code: str, check: Callable[[Context], None], voice: Any = None) -> Rule:
    """Register `check` as the rule of `code`, for the dialects its page names."""
    if code in RULES:
        raise ValueError(f"two lint rules for {code}")
    info = registry().get(code)
    if info is None:
        raise KeyError(f"lint rule {code} has no page: its module's docstring is its page (docs/LINT.md)")
    RULES[code] = Rule(code, info.dialects, check, voice)
    return RULES[code]


def rule(func: Callable[[Context], None]) -> Callable[[Context], None]:
    """Register a rule function: `@rule` over the one check of a rule module; its code is the
    module's (m302_branch_out_of_subroutine -> M302), its dialects those its page names."""
    add(code_of(func.__module__), func)
    return func


def discover(package: str, path) -> None:
    """Import every rule module of a package (its `__init__` calls this): a rule is registered by
    adding its module, and nothing lists it elsewhere."""
    for found in sorted(pkgutil.iter_modules(path), key=lambda m: m.name):
        if RULE_NAME.match(found.name):
            importlib.import_module(f"{package}.{found.name}")


def load(dialect: str) -> None:
    """Import the rules of a dialect (once): its package and the rules of every dialect. A dialect
    without a package has no rules yet."""
    if dialect in _LOADED:
        return
    _LOADED.add(dialect)
    importlib.import_module(f"{__name__}.{EVERY_DIALECT}")  # the machine's envelope
    try:
        importlib.import_module(f"{__name__}.{dialect}")
    except ModuleNotFoundError as exc:
        if exc.name != f"{__name__}.{dialect}":
            raise


def load_all() -> dict[str, Rule]:
    for name in dialects.names():
        load(name)
    return RULES


def rules_for(dialect: str) -> list[Rule]:
    load(dialect)
    return [r for code, r in sorted(RULES.items()) if dialect in r.dialects]
