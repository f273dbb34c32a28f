"""One finished analysis of one document version: diagnostics, syntax tree, editor model, memory.

`analyze` runs in a worker thread (see documents.py) in steps, so that the diagnostics reach the
editor as soon as they are known and the rest follows: `check` (the frontend, parsing only the
lines an edit changed: incremental.py), `lint` (the lint rules, configuration and noqa: the
diagnostics are complete and published), `with_index` (the editor model hover, completion, ...
answer from) and `complete` (program memory for the code lenses). The checks and the rules reuse
the lint engine and the project configuration exactly as `mcc lint` does, so the editor and the
command line never disagree.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Callable

from mcc.compiler import dialects, driver
from mcc.compiler.config import Resolver, Settings
from mcc.compiler.diagnostics import Diagnostic
from mcc.compiler.lint import engine
from mcc.compiler.span import SourceFile
from mcc.lsp import incremental, model


@dataclass
class Snapshot:
    """What the features answer from: never mutated once published."""

    uri: str
    path: str
    version: int | None
    text: str
    dialect: str
    source: SourceFile
    settings: Settings
    profile: object | None = None
    tree: object | None = None
    module: object | None = None
    analysis: object | None = None  # the frontend's Analysis: its symbol table and def-use chains
    index: model.Index = field(default_factory=lambda: model.Index(""))
    diagnostics: list[Diagnostic] = field(default_factory=list)
    complete: bool = False  # every step has run (lint rules, editor model, program memory)
    check_errors: bool = False  # the frontend's checks found errors
    # the lines of the frontend's errors, the budget's own (A201, X203, M116) aside: the program
    # memory and the cycle time of a version with such lines are computed from the lines that do
    # analyse (the others left out of the IR), or carried from the last version without any
    error_lines: tuple[int, ...] = ()
    memory: object | None = None  # memory.Usage
    cycles: object | None = None  # cycles.Cycles: the cycle time lenses
    config_diagnostics: list[tuple[str, list[Diagnostic]]] = field(default_factory=list)
    # milliseconds the analysis took: wall clock from the edit's arrival to the diagnostics, and the
    # analysis thread's CPU time in the checks and the rules (mcc/status reports them: on a loaded
    # machine the wall clock is mostly waiting for a CPU)
    timings: dict[str, float] = field(default_factory=dict)

    @property
    def known(self) -> bool:
        return self.dialect in dialects.DIALECTS


def settings_for(path: str, resolver: Resolver) -> Settings:
    try:
        return resolver.for_path(path)
    except Exception:  # noqa: BLE001 - a broken configuration is reported on the TOML file, never fatal
        return Settings()


def check(uri: str, path: str, version: int | None, text: str, resolver: Resolver,
          dialect: str | None = None, cache: incremental.LineCache | None = None,
          stop: Callable[[], bool] | None = None):
    """The frontend's checks (first step), parsing through `cache` (the lines of the document's
    previous version): (snapshot, checked, cache to keep). The snapshot has the checks'
    diagnostics only and no editor model; snapshot and checked are None when `stop` answered
    True (a newer version arrived) before the checks were done."""
    settings = settings_for(path, resolver)
    checked, cache = incremental.check_text(path, text, settings, dialect, cache, stop)
    if checked is None:
        return None, None, cache
    result = checked.result
    analysis = result.analysis
    source = analysis.source if analysis is not None else SourceFile(path, text)
    snap = Snapshot(uri, path, version, text, result.dialect, source, settings, checked.profile)
    if analysis is not None:
        snap.tree, snap.module, snap.analysis = analysis.tree, analysis.module, analysis
    snap.diagnostics = engine.settle(checked, settings, rules=False)
    snap.check_errors = any(d.severity.value == "error" for d in snap.diagnostics)
    snap.error_lines = error_lines(snap.diagnostics, {path, source.path})
    snap.config_diagnostics = [(p, d) for p, d, _ in resolver.diagnostics()]
    return snap, checked, cache


def error_lines(diagnostics: list[Diagnostic], paths: set[str]) -> tuple[int, ...]:
    """The lines of the errors among the checks' diagnostics that may leave a statement out of the
    IR: every error but the program memory's budget (the whole program is priced for it)."""
    return tuple(sorted({d.span.line for d in diagnostics if d.severity.value == "error"
                         and d.code not in driver.BUDGET_CODES and d.span.file in paths}))


def lint(snap: Snapshot, checked: engine.Checked, stop: Callable[[], bool] | None = None) -> Snapshot | None:
    """The snapshot with all the diagnostics of `mcc check` and `mcc lint` (second step); None when
    `stop` says the work is stale."""
    diagnostics = engine.settle(checked, snap.settings, rules=True, stop=stop)
    if stop is not None and stop():
        return None
    return Snapshot(**{**snap.__dict__, "diagnostics": diagnostics})


def with_index(snap: Snapshot) -> Snapshot:
    """The snapshot with its editor model (what hover, completion, ... answer from)."""
    extra: list[Diagnostic] = []
    index = build_index(snap, extra)
    return Snapshot(**{**snap.__dict__, "index": index, "diagnostics": snap.diagnostics + extra})


def build_index(snap: Snapshot, diags: list[Diagnostic]) -> model.Index:
    import importlib

    from mcc.lsp.editor import editor_of

    indexer = editor_of(snap.dialect).indexer  # the dialect's own (lsp/<dialect>_index.py)
    if not indexer or snap.tree is None:
        return model.Index(snap.dialect)
    profile = snap.profile or driver.profile_for(dialects.get(snap.dialect), None)
    try:
        return importlib.import_module(indexer).build(snap.tree, snap.source, profile, snap.analysis)
    except Exception as exc:  # noqa: BLE001 - the editor model must never cost the diagnostics
        driver.internal_error(_Sink(diags), snap.path, exc, "building the editor model")
        return model.Index(snap.dialect)


class _Sink:
    def __init__(self, items: list[Diagnostic]):
        self.items = items

    def add(self, code, span, message):
        from mcc.compiler.diagnostics import Diagnostics

        collected = Diagnostics()
        collected.add(code, span, message)
        self.items.extend(collected.items)


def figures_wanted(snap: Snapshot) -> bool:
    """Whether the program memory and the cycle time are to be computed for this version (the
    backend's work and a bounded simulation). A version whose checks found errors (`error_lines`)
    keeps the figures of the last version without any, carried onto its lines (`snap.memory` and
    `snap.cycles` hold them then), so that the lenses stay as they were while the user types;
    only when there are none (a file opened with an error, or never without one since) are they
    computed from the lines that analyse, and say which lines have errors."""
    from mcc.lsp import cycles, memory

    if not (memory.priced(snap) or cycles.timed(snap)):
        return False
    if not snap.error_lines:
        return True
    carried = [figures for figures in (snap.memory, snap.cycles) if figures is not None]
    return not carried or any(figures.error_lines for figures in carried)


def complete(snap: Snapshot, compute: bool = True) -> Snapshot:
    """The snapshot with its program memory and cycle time (last step), computed when `compute`
    (else the figures it carries stay): every feature has what it needs."""
    from mcc.lsp import cycles, memory

    usage = memory.usage(snap) if compute else None  # None: the figures carried stay (documents.py)
    timed = cycles.cycles(snap) if compute else None
    return Snapshot(**{**snap.__dict__, "complete": True, "memory": usage if usage is not None else snap.memory,
                       "cycles": timed if timed is not None else snap.cycles})


def analyze(uri: str, path: str, version: int | None, text: str, resolver: Resolver | None = None,
            dialect: str | None = None) -> Snapshot:
    """All the steps at once (for tests, the benchmark and one-off requests)."""
    snap, checked, _ = check(uri, path, version, text, resolver or Resolver(), dialect)
    snap = lint(snap, checked) or snap
    snap = with_index(snap)
    return complete(snap, figures_wanted(snap))
