"""Runs files through the pipeline: read → frontend (parse, lower, check) → backend.

This is where "no input produces a traceback" is enforced: an unexpected exception while
processing one file becomes a G001 internal diagnostic on that file, and the run goes on.
"""

from __future__ import annotations

import traceback
from dataclasses import dataclass, field
from typing import Any

from mcc.compiler import dialects
from mcc.compiler import ir
from mcc.compiler.diagnostics import Diagnostic, Diagnostics
from mcc.compiler.profiles import Profile
from mcc.compiler import profiles as profiles_mod
from mcc.compiler.span import SourceFile, Span


@dataclass
class Analysis:
    """What a frontend returns for one source file."""

    source: SourceFile
    tree: Any
    module: ir.Module | None
    diagnostics: Diagnostics
    # program memory against the target's budget, from the same model as the backend's listing
    # (X150 sequence bytes, Arcus assembly lines); filled by the frontend or by `measure_memory`
    memory: dict = field(default_factory=dict)


@dataclass
class FileResult:
    path: str
    dialect: str
    diagnostics: list[Diagnostic] = field(default_factory=list)
    source: SourceFile | None = None
    analysis: Analysis | None = None
    listing: Any = None  # backends.listing.Listing
    output: str | None = None
    target: str = ""

    @property
    def has_errors(self) -> bool:
        return any(d.severity.value == "error" for d in self.diagnostics)

    def to_json(self) -> dict:
        data: dict = {
            "path": self.path,
            "dialect": self.dialect,
            "diagnostics": [d.to_json() for d in sorted(self.diagnostics, key=Diagnostic.sort_key)],
        }
        if self.analysis is not None and self.analysis.memory:
            data["memory"] = self.analysis.memory
        return data


def file_span(path: str) -> Span:
    return Span(path, 1, 1, 1, 1, 0, 0)


def internal_error(diags: Diagnostics, path: str, exc: BaseException, stage: str) -> None:
    frames = traceback.extract_tb(exc.__traceback__)
    where = f" at {frames[-1].filename.rsplit('/', 1)[-1]}:{frames[-1].lineno}" if frames else ""
    diags.add("G001", file_span(path),
              f"internal error while {stage}: {type(exc).__name__}: {exc}{where}. "
              "This is a bug in mcc, not in your program; please report it with this file.")


def resolve_dialect(path: str, dialect: str | None) -> dialects.Dialect | None:
    if dialect:
        return dialects.get(dialect)
    return dialects.from_path(path)


def profile_for(dialect: dialects.Dialect, profile: Profile | None) -> Profile:
    if profile is not None and profile.dialect == dialect.name:
        return profile
    return profiles_mod.load(dialect.default_profile)


def read_source(path: str, diags: Diagnostics) -> SourceFile | None:
    try:
        return SourceFile.read(path)
    except OSError as exc:
        diags.add("G002", file_span(path), f"cannot read {path}: {exc.strerror or exc}")
        return None


def analyze_source(source: SourceFile, dialect: dialects.Dialect, profile: Profile | None,
                   diags: Diagnostics) -> Analysis | None:
    try:
        frontend = dialect.load_frontend()
        analysis = frontend.analyze(source, profile_for(dialect, profile))
    except Exception as exc:  # noqa: BLE001 - the no-traceback guarantee
        internal_error(diags, source.path, exc, "checking")
        return None
    if analysis.diagnostics.has_errors:
        analysis = neighbour_language(analysis, dialect)
    diags.extend(analysis.diagnostics)
    return analysis


def neighbour_language(analysis: Analysis, dialect: dialects.Dialect) -> Analysis:
    """A file in a neighbouring controller's language (6K, another indexer's X-code, an Arcus DMX
    program) gets one diagnostic naming it instead of an error per line (compiler/neighbours.py)."""
    from mcc.compiler import neighbours

    items = list(analysis.diagnostics)
    found = neighbours.recognise(analysis.source, dialect.name, items)
    if found is None:
        return analysis
    errors = sum(1 for d in items if d.severity.value == "error")
    diags = neighbours.report(analysis.source, dialect.name, dialect.title, found, errors)
    return Analysis(analysis.source, analysis.tree, None, diags)


def measure_memory(analysis: Analysis, dialect: dialects.Dialect, profile: Profile | None,
                   diags: Diagnostics) -> None:
    """Program memory for `mcc check`, `lint` and the editor, when the frontend has not measured it:
    the dialect's backend prices the program with the cost model of `mcc compile` (its `memory`
    function) and reports only what concerns memory (over or near a budget)."""
    if analysis.memory or analysis.module is None:
        return
    try:
        backend = dialect.load_backend()
        measure = getattr(backend, "memory", None)
        if measure is None:
            return
        analysis.memory, found = measure(analysis.module, profile_for(dialect, profile))
    except Exception as exc:  # noqa: BLE001 - the no-traceback guarantee
        internal_error(diags, analysis.source.path, exc, "measuring program memory")
        return
    diags.extend(found)


def check_file(path: str, dialect: str | None = None, profile: Profile | None = None,
               text: str | None = None, memory: bool = True) -> FileResult:
    """Parse, lower and check one file (the work of `mcc check`); with `memory`, also the program
    memory against the target's budget (compile measures it in the backend instead)."""
    diags = Diagnostics()
    found = resolve_dialect(path, dialect)
    if found is None:
        diags.add("G004", file_span(path),
                  f"cannot tell the dialect of '{path}' from its extension "
                  f"(known: {', '.join(dialects.all_extensions())}); pass --dialect")
        return FileResult(path, dialect or "unknown", diags.items)
    source = SourceFile(path, text) if text is not None else read_source(path, diags)
    result = FileResult(path, found.name, source=source)
    if source is not None:
        result.analysis = analyze_source(source, found, profile, diags)
        if memory and result.analysis is not None and not diags.has_errors:
            measure_memory(result.analysis, found, profile, diags)
    result.diagnostics = diags.items
    return result


def compile_file(path: str, dialect: str | None = None, target: str | None = None,
                 profile: Profile | None = None, text: str | None = None) -> FileResult:
    """Check one file and, when it has no errors, generate code for the target dialect."""
    result = check_file(path, dialect, profile, text, memory=False)
    result.target = target or result.dialect
    analysis = result.analysis
    if analysis is None or analysis.module is None or result.has_errors:
        return result
    diags = Diagnostics(result.diagnostics)
    try:
        target_dialect = dialects.get(result.target)
        backend = target_dialect.load_backend()
        listing = backend.emit(analysis.module, profile_for(target_dialect, profile))
        diags.extend(listing.diagnostics)
        result.listing = listing
    except Exception as exc:  # noqa: BLE001 - the no-traceback guarantee
        internal_error(diags, path, exc, f"generating {result.target} code")
    result.diagnostics = diags.items
    return result
