"""The lint engine: checks + rules + configuration + suppression + fixes, for files and trees.

For one file: the frontend's diagnostics (`driver.check_file`, the work of `mcc check`), then the
selected lint rules of its dialect over the same analysis, then the configuration (selection,
per-file ignores, severities), then `noqa` comments. With `--fix` the fixes are applied round
after round until the text settles (compiler/lint/fixes.py proves each safe fix first).

Many files are linted in parallel with a process pool (Lark parsing is CPU-bound, so threads would
not help). Work is sent in batches to keep the pickling overhead small, and each worker returns
only what the report needs: diagnostics and the final text.
"""

from __future__ import annotations

import multiprocessing
import os
from concurrent.futures import ProcessPoolExecutor, as_completed
from dataclasses import dataclass, field
from typing import Callable, Iterable

from mcc.compiler import dialects, driver
from mcc.compiler.config import CONFIG_FILES, Resolver, Settings, load_profile
from mcc.compiler.diagnostics import Diagnostic, Diagnostics, Kind
from mcc.compiler.lint import files, fixes, flow, ignore, suppress
from mcc.compiler.lint.rules import Context, rules_for
from mcc.compiler.span import SourceFile

SKIP_DIRS = {"__pycache__", "node_modules", "venv"}


@dataclass(frozen=True)
class Options:
    fix: bool = False
    diff: bool = False
    unsafe_fixes: bool = False
    dialect: str | None = None
    verify: bool = False  # simulate before and after the fixes; write nothing if they differ
    # `mcc lint --fix` validates by default: then an original with errors of its own (nothing the
    # device would run, so no behaviour to keep) is fixed unvalidated; an explicit --verify refuses
    verify_required: bool = True


@dataclass
class Outcome:
    """What linting one file produced (sent back from a worker process, so kept small)."""

    path: str
    dialect: str
    diagnostics: list[Diagnostic] = field(default_factory=list)
    text: str | None = None  # the text the diagnostics refer to (after fixes)
    fixed: int = 0  # fixes applied (or that --diff would apply)
    diff: str = ""
    written: bool = False
    write_error: bool = False  # the fixed text could not be written (G006)

    @property
    def source(self) -> SourceFile | None:
        return SourceFile(self.path, self.text) if self.text is not None else None


# one file ------------------------------------------------------------------------------------------

def lint_text(path: str, text: str, settings: Settings, dialect: str | None = None) -> tuple[str, list[Diagnostic]]:
    """Lint one text: (dialect, diagnostics in file order)."""
    checked = check_text(path, text, settings, dialect)
    return checked.dialect, settle(checked, settings)


@dataclass
class Checked:
    """One text through the frontend (the work of `mcc check`), before the lint rules and the
    configuration are applied by `settle`. The editor server publishes the checks first and the
    rules when they finish, from the same analysis."""

    path: str
    dialect: str
    result: driver.FileResult
    profile: object | None  # the Profile the text was checked against

    @property
    def analysis(self):
        return self.result.analysis


def check_text(path: str, text: str, settings: Settings, dialect: str | None = None) -> Checked:
    """`mcc check` of one text, with the profile `selection.choose` gives it (the command line's,
    a `mcc: profile=` line, per-file-profiles, target, or the dialect's default)."""
    result = driver.check_file(path, dialect, None, text, settings=settings)
    return Checked(path, result.dialect, result, result.profile)


def settle(checked: Checked, settings: Settings, rules: bool = True,
           stop: Callable[[], bool] | None = None) -> list[Diagnostic]:
    """The checked text's diagnostics with the lint rules (unless `rules` is False), the selection,
    severities and `noqa` applied, in file order. `stop` is asked between rules: when it answers
    True the remaining rules are skipped (the editor server abandons stale work this way)."""
    path, result = checked.path, checked.result
    diags = Diagnostics(list(result.diagnostics))
    analysis = result.analysis
    syntax_ok = not any(d.kind is Kind.SYNTAX for d in result.diagnostics)
    if rules and analysis is not None and analysis.module is not None and syntax_ok \
            and result.dialect in dialects.DIALECTS:
        with driver.fewer_collections():
            run_rules(analysis, checked.profile, result.dialect, settings, path, diags, stop)
    kept = []
    for diag in diags.items:
        if not settings.enabled(diag.code, path):
            continue
        diag.severity = settings.severity_of(diag.code, diag.severity) if diag.kind is not Kind.SYNTAX \
            and diag.kind is not Kind.INTERNAL else diag.severity
        kept.append(diag)
    source = analysis.source if analysis is not None else SourceFile(path, result.source.text if result.source
                                                                     else "")
    kept = suppress.apply(kept, source, result.dialect, lambda code: settings.enabled(code, path))
    for diag in kept:
        if diag.code in ("G101", "G104"):
            diag.severity = settings.severity_of(diag.code, diag.severity)
    return sorted(kept, key=Diagnostic.sort_key)


def run_rules(analysis, profile, dialect: str, settings: Settings, path: str, diags: Diagnostics,
              stop: Callable[[], bool] | None = None) -> None:
    ctx = Context(analysis, profile or load_profile(dialects.get(dialect).default_profile), dialect, diags,
                  settings=settings)
    with flow.shared_shapes():  # the rules read the module, never change it: one graph walk per routine
        for rule in rules_for(dialect):
            if not settings.enabled(rule.code, path):
                continue
            if stop is not None and stop():
                return
            ctx.code = rule.code
            try:
                rule.check(ctx)
            except Exception as exc:  # noqa: BLE001 - a broken rule must not hide the others
                driver.internal_error(diags, path, exc, f"running lint rule {rule.code}")


def lint_source(path: str, text: str, settings: Settings, options: Options = Options()) -> Outcome:
    """Lint a text (a file's or standard input's) and, with --fix or --diff, apply the fixes in
    memory: the outcome's text is the fixed text, its diagnostics what remains."""
    dialect, diags = lint_text(path, text, settings, options.dialect)
    fixed = 0
    if (options.fix or options.diff) and not driver.has_long_lines(diags):  # G007: offsets shifted, no fixes
        run = fix_text(path, text, diags, settings, options)
        text, diags, fixed = run.text, run.diagnostics, run.fixed
        if run.error:
            extra = Diagnostics()
            extra.add("G008", driver.file_span(path), f"{run.error}; the file was left unchanged. This is a bug in "
                                                      "mcc: please report it with this file")
            diags = sorted(diags + extra.items, key=Diagnostic.sort_key)
    return Outcome(path, dialect, diags, text, fixed)


def lint_file(path: str, settings: Settings, options: Options = Options()) -> Outcome:
    try:
        original = files.read(path)
    except OSError as exc:
        diags = Diagnostics()
        diags.add("G002", driver.file_span(path), f"cannot read {path}: {exc.strerror or exc}")
        found = driver.resolve_dialect(path, options.dialect, settings)
        return Outcome(path, found.name if found else "unknown", diags.items)
    outcome = lint_source(path, original.text, settings, options)
    text = outcome.text
    if text != original.text:
        if options.diff:
            outcome.diff = fixes.unified_diff(path, original.text, text)
        elif options.fix and options.verify and _diverges(outcome, original.text, options):
            pass  # S010 is reported; the file is left as it was
        elif options.fix:
            try:
                files.write_atomic(path, text, original)
                outcome.written = True
            except OSError as exc:
                dialect, diags = lint_text(path, original.text, settings, options.dialect)
                extra = Diagnostics()
                extra.add("G006", driver.file_span(path), f"cannot write {path}: {exc.strerror or exc}; the fixes "
                                                          "were not applied")
                outcome = Outcome(path, dialect, sorted(diags + extra.items, key=Diagnostic.sort_key),
                                  original.text, 0, write_error=True)
    return outcome


def fix_text(path: str, text: str, diags: list[Diagnostic], settings: Settings, options: Options) -> fixes.FixRun:
    """Apply the fixes to one text until it settles (safe ones proved by fixes.fix_is_safe)."""
    found = driver.resolve_dialect(path, options.dialect, settings)
    profile = None
    if found is not None:
        from mcc.compiler import selection

        profile = selection.choose(path, found.name, SourceFile(path, text), settings).profile

    def relint(new_text: str) -> list[Diagnostic]:
        return lint_text(path, new_text, settings, options.dialect)[1]

    def make(new_text: str) -> fixes.Version:
        return fixes.Version(path, new_text, options.dialect, profile)

    return fixes.fix_until_stable(text, diags, relint, make, options.unsafe_fixes)


def _diverges(outcome: Outcome, before: str, options: Options) -> bool:
    """--verify: add S010 and answer True when the fixed text does not behave like the original."""
    from mcc.sim.verify import check_translation, explain

    problem = check_translation(outcome.path, outcome.dialect, before, outcome.text or "")
    if problem.startswith("the source has errors") and not options.verify_required:
        return False
    if problem:
        diags = Diagnostics(outcome.diagnostics)
        diags.add("S010", driver.file_span(outcome.path), f"--verify: {explain(problem)}; nothing was written")
        outcome.diagnostics = diags.items
    return bool(problem)


# many files ----------------------------------------------------------------------------------------

def expand(paths: Iterable[str], resolver: Resolver | None = None, skipped: list[str] | None = None,
           force_exclude: bool = False, respect_gitignore: bool = True,
           unknown: list[str] | None = None) -> list[str]:
    """Files to lint: the files given, and the files with a known extension under the directories
    given. Hidden directories, the configuration's `exclude` patterns and what `.gitignore` ignores
    (compiler/lint/ignore.py) are skipped in directories; with `force_exclude` also among the paths
    given (pre-commit names each staged file). Only regular files are taken from a directory: a
    FIFO, device or socket (or a broken link) with a dialect's extension is left out, with a note
    appended to `skipped`. A file in a directory whose extension no dialect has (neither built in
    nor mapped by the configuration's `extensions`) is left out and appended to `unknown`."""
    from mcc.compiler import files as files_mod

    extensions = dialects.all_extensions()
    found: list[str] = []
    seen: set = set()

    def known(full: str, name: str) -> bool:
        if name.lower().endswith(extensions):
            return True
        return resolver is not None and resolver.for_path(full).dialect_for(full) is not None

    def left_out(path: str, within: str | None = None) -> bool:
        return excluded(path, resolver) or (respect_gitignore and ignore.gitignored(path, within=within))

    for path in paths:
        if force_exclude and left_out(path):
            continue
        if os.path.isdir(path):
            for folder, subdirs, names in os.walk(path):
                subdirs[:] = sorted(d for d in subdirs if not d.startswith(".") and d not in SKIP_DIRS
                                    and not left_out(os.path.join(folder, d), path))
                for name in sorted(names):
                    full = os.path.join(folder, name)
                    if not known(full, name):
                        if unknown is not None and not name.startswith(".") and name not in CONFIG_FILES \
                                and not left_out(full, path):
                            unknown.append(os.path.normpath(full))
                        continue
                    if not left_out(full, path):
                        problem = files_mod.unreadable(full)
                        if problem is None:
                            add(found, seen, full)
                        elif skipped is not None:
                            skipped.append(f"skipped {os.path.normpath(full)}: {problem}")
        else:
            add(found, seen, path)
    return found


def add(found: list[str], seen: set, path: str) -> None:
    """Add a file once, however it is named: the same file reached through a link or a second
    path is worked on once (with --fix, two workers would otherwise write it at the same time)."""
    path = os.path.normpath(path)
    try:
        info = os.stat(path)
        identity: object = (info.st_dev, info.st_ino)
    except OSError:
        identity = path
    if path not in seen and identity not in seen:
        seen.update((path, identity))
        found.append(path)


def excluded(path: str, resolver: Resolver | None) -> bool:
    return resolver is not None and resolver.for_path(path).excluded(path)


def _batch(func: Callable, work: list[tuple[str, Settings]], options) -> list:
    return [func(path, settings, options) for path, settings in work]


def warm_up(work: list[tuple[str, Settings]], options) -> None:
    """Build each needed parser once before forking, so the workers inherit it."""
    done = set()
    for path, settings in work:
        found = driver.resolve_dialect(path, options.dialect, settings)
        if found is not None and found.name not in done:
            done.add(found.name)
            driver.check_file(f"warm-up{found.extensions[0]}", found.name, text="")
            rules_for(found.name)


def run(work: list[tuple[str, Settings]], options, jobs: int,
        start_progress: Callable[[], Callable[[int], None]] | None = None,
        func: Callable = lint_file) -> list:
    """Run `func(path, settings, options)` (default: lint) over (path, settings) pairs: sequential
    for one file or one job, else in a process pool. `func` must be a module-level function.

    `start_progress` is called once the work is under way (after the workers are forked, so no
    progress-bar thread exists at fork time) and returns the function that advances the bar.
    """
    if jobs <= 1 or len(work) <= 1:
        progress = start_progress() if start_progress else None
        outcomes = []
        for item in work:
            outcomes.append(_batch(func, [item], options)[0])
            if progress:
                progress(1)
        return outcomes
    jobs = min(jobs, len(work))
    size = max(1, min(64, len(work) // (jobs * 4)))
    batches = [work[i:i + size] for i in range(0, len(work), size)]
    methods = multiprocessing.get_all_start_methods()
    context = multiprocessing.get_context("fork" if "fork" in methods else None)
    if context.get_start_method() == "fork":
        warm_up(work, options)
    outcomes = []
    with ProcessPoolExecutor(max_workers=jobs, mp_context=context) as pool:
        futures = [pool.submit(_batch, func, batch, options) for batch in batches]  # all workers fork here
        progress = start_progress() if start_progress else None
        for future in as_completed(futures):
            done = future.result()
            outcomes.extend(done)
            if progress:
                progress(len(done))
    return outcomes
