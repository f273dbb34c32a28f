"""The registry of semantic checks: every whole-program check is a small function over one program.

A check is one module, `compiler/checks/<dialect>/<code>_<name>.py` (`mcode/m106_undefined_label.py`),
whose docstring is the page of its code (what `mcc explain M106` prints), exactly as a lint rule's
is (docs/decisions/0021): the code registry (compiler/codes.py) reads the code's name, severity and
examples from that page, and `@check` takes the code from the module's name. A check reports its
own code; a few also report a code whose page lives with the stage that reports it first (X110,
nested too deep, is reported while lowering one sequence and, through the calls, by a check): they
name it in `also`, and the code's entry in compiler/codes/*.toml names the module in `emitted`.

A check declares what a program must have for it to apply (`needs`, names of the dialect's `FACTS`:
"label references", "sequence calls"...); the runner skips a check whose needs the program lacks, so
that no check starts with its own "is there anything to do" test. The frontend runs the checks
(`run`) after lowering, in the order of their codes; the diagnostics users see are sorted by
position (compiler/diagnostics.py `sort_key`), so that order only decides which of two checks'
findings on one character comes first, and no two checks report one code.

The per-statement diagnostics, found while a statement is read against the catalog (resolve.py,
the X150 command checks) and while the block structure is built (lower.py, x150/structure.py),
are not registered checks: docs/decisions/0021 says why. Every 1xx code still says where it is
reported (`emitted` in compiler/codes/*.toml, or the check module), and tests/checks/test_check_
registry.py fails on a code reported anywhere else.
"""

from __future__ import annotations

import importlib
import pkgutil
from dataclasses import dataclass, field
from typing import Any, Callable

from mcc.compiler.cancel import checkpoint
from mcc.compiler.codes import RULE_NAME
from mcc.compiler.diagnostics import Diagnostic, Diagnostics, Fix, Severity
from mcc.compiler.profiles import Profile
from mcc.compiler.span import SourceFile, Span


@dataclass
class Program:
    """What a check sees: one lowered file. `lowering` is the dialect's Lowering (its tables of
    labels, calls, sequences); `memory` is what a check measured of the program's memory, which the
    frontend returns in its Analysis (the X150 sequence store)."""

    dialect: str
    source: SourceFile
    tree: Any
    lowering: Any
    profile: Profile
    memory: dict = field(default_factory=dict)
    cache: dict[str, Any] = field(default_factory=dict)  # facts several checks share (per file)

    @property
    def module(self):
        return self.lowering.module

    def shared(self, key: str, compute: Callable[[], Any]) -> Any:
        """A per-file fact computed once for every check that needs it (the call-nesting walk)."""
        if key not in self.cache:
            self.cache[key] = compute()
        return self.cache[key]


@dataclass
class Context:
    """A check's view of the program and its way to report: `report` adds a diagnostic of the
    check's own code, or of one of the codes it names in `also`."""

    program: Program
    check: "Check"
    diagnostics: Diagnostics

    @property
    def lowering(self):
        return self.program.lowering

    @property
    def profile(self) -> Profile:
        return self.program.profile

    def report(self, span: Span, message: str, *, code: str | None = None, fix: Fix | None = None,
               notes: tuple[str, ...] | list[str] = (), severity: Severity | None = None) -> Diagnostic:
        code = code or self.check.code
        if code not in self.check.codes:  # caught by tests/checks/test_check_registry.py
            raise ValueError(f"check {self.check.code} reports {code}: name it in `also`")
        return self.diagnostics.add(code, span, message, fix=fix, notes=notes, severity=severity)


@dataclass(frozen=True)
class Check:
    code: str
    dialect: str
    run: Callable[[Context], None]
    needs: tuple[str, ...] = ()
    also: tuple[str, ...] = ()  # codes whose page is elsewhere that the check reports too

    @property
    def codes(self) -> tuple[str, ...]:
        return (self.code, *self.also)


CHECKS: dict[str, Check] = {}
FACTS: dict[str, dict[str, Callable[[Program], bool]]] = {}  # dialect -> need -> does the program have it
_LOADED: set[str] = set()


def code_of(module_name: str) -> str:
    """The code of the check a module holds, from its name (`...mcode.m106_undefined_label` -> M106)."""
    match = RULE_NAME.match(module_name.rpartition(".")[2])
    if match is None:
        raise ValueError(f"{module_name} is not a check module: name it <code>_<name>, e.g. m106_undefined_label")
    return match.group(1).upper()


def dialect_of(module_name: str) -> str:
    """The dialect of a check module: the package it is in (`mcc.compiler.checks.mcode.m106_...`)."""
    return module_name.rsplit(".", 2)[-2]


def check(*, needs: tuple[str, ...] = (), also: tuple[str, ...] = ()) -> Callable:
    """Register the function of a check module as the check of its code, for its package's dialect.
    `needs` are facts of the dialect's `FACTS` the program must have; `also` the other codes it
    reports (their pages stay in compiler/codes/)."""

    def register(func: Callable[[Context], None]) -> Callable[[Context], None]:
        code = code_of(func.__module__)
        dialect = dialect_of(func.__module__)
        if code in CHECKS:
            raise ValueError(f"two checks for {code}")
        unknown = [need for need in needs if need not in FACTS.get(dialect, {})]
        if unknown:
            raise ValueError(f"check {code} needs {unknown}, which are not facts of {dialect} "
                             f"(compiler/checks/{dialect}/__init__.py FACTS)")
        CHECKS[code] = Check(code, dialect, func, tuple(needs), tuple(also))
        return func

    return register


def facts(dialect: str, table: dict[str, Callable[[Program], bool]]) -> None:
    """The facts a dialect's checks may need (its package's `__init__` calls this before `discover`)."""
    FACTS[dialect] = table


def discover(package: str, path) -> None:
    """Import every check module of a package: a check is registered by adding its module."""
    for found in sorted(pkgutil.iter_modules(path), key=lambda m: m.name):
        if RULE_NAME.match(found.name):
            importlib.import_module(f"{package}.{found.name}")


def load(dialect: str) -> None:
    """Import the checks of a dialect (once). A dialect without a package has no checks."""
    if dialect in _LOADED:
        return
    _LOADED.add(dialect)
    try:
        importlib.import_module(f"{__name__}.{dialect}")
    except ModuleNotFoundError as exc:
        if exc.name != f"{__name__}.{dialect}":
            raise


def load_all() -> dict[str, Check]:
    from mcc.compiler import dialects

    for name in dialects.names():
        load(name)
    return CHECKS


def checks_for(dialect: str) -> list[Check]:
    load(dialect)
    return [c for code, c in sorted(CHECKS.items()) if c.dialect == dialect]


def applies(check_: Check, program: Program) -> bool:
    """Whether the program has everything the check needs (each fact found once per program)."""
    table = FACTS.get(check_.dialect, {})
    return all(program.shared(f"fact:{need}", lambda need=need: bool(table[need](program)))
               for need in check_.needs)


def run(program: Program, diags: Diagnostics) -> None:
    """Run every registered check of the program's dialect that applies to it, in code order."""
    for found in checks_for(program.dialect):
        checkpoint()  # the editor server abandons a stale analysis here (compiler/cancel.py)
        if applies(found, program):
            found.run(Context(program, found, diags))
