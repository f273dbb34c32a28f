"""Runs files through the pipeline: read → frontend (parse, lower, check) → backend.

This is where "no input produces a traceback" is enforced: an unexpected exception while
processing one file becomes a G001 internal diagnostic on that file, and the run goes on.
"""

from __future__ import annotations

import gc
import traceback
from contextlib import contextmanager
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


@contextmanager
def fewer_collections():
    """Collect garbage less often while a file is analysed: a syntax tree and its IR are hundreds of
    thousands of live objects that the cyclic collector would walk again and again (it made
    `check` on 16,000 lines take three times as long as on 8,000). Restored on the way out."""
    old = gc.get_threshold()
    gc.set_threshold(max(old[0], 50_000), max(old[1], 20), max(old[2], 20))
    try:
        yield
    finally:
        gc.set_threshold(*old)


def analyze_source(source: SourceFile, dialect: dialects.Dialect, profile: Profile | None,
                   diags: Diagnostics) -> Analysis | None:
    try:
        frontend = dialect.load_frontend()
        with fewer_collections():
            analysis = frontend.analyze(source, profile_for(dialect, profile))
    except Exception as exc:  # noqa: BLE001 - the no-traceback guarantee
        internal_error(diags, source.path, exc, "checking")
        return None
    diags.extend(analysis.diagnostics)
    return analysis


def check_file(path: str, dialect: str | None = None, profile: Profile | None = None,
               text: str | None = None) -> FileResult:
    """Parse, lower and check one file (the work of `mcc check`)."""
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
    result.diagnostics = diags.items
    return result


def compile_file(path: str, dialect: str | None = None, target: str | None = None,
                 profile: Profile | None = None, text: str | None = None) -> FileResult:
    """Check one file and, when it has no errors, generate code for the target dialect."""
    result = check_file(path, dialect, profile, text)
    result.target = target or result.dialect
    analysis = result.analysis
    if analysis is None or analysis.module is None or result.has_errors:
        return result
    diags = Diagnostics(result.diagnostics)
    try:
        target_dialect = dialects.get(result.target)
        backend = target_dialect.load_backend()
        with fewer_collections():
            listing = backend.emit(analysis.module, profile_for(target_dialect, profile))
        diags.extend(listing.diagnostics)
        result.listing = listing
    except Exception as exc:  # noqa: BLE001 - the no-traceback guarantee
        internal_error(diags, path, exc, f"generating {result.target} code")
    result.diagnostics = diags.items
    return result
