"""`mcc fmt` for any dialect: find the dialect's formatter, format, verify, write.

Each dialect's formatter is `mcc.compiler.<dialect>.format.format_text(text, path, profile)`. As a
safety net (black and ruff do the same) the IR of the formatted text is compared with the IR of
the original, ignoring positions: when they differ, or the formatter fails, the file is left
alone and the failure is reported as an internal error (a bug in mcc).
"""

from __future__ import annotations

import importlib
from dataclasses import dataclass
from types import ModuleType

from mcc.compiler import driver
from mcc.compiler.config import Settings
from mcc.compiler.diagnostics import SyntaxErrors
from mcc.compiler.ir_compare import differences
from mcc.compiler.lint import files
from mcc.compiler.lint.fixes import unified_diff


@dataclass(frozen=True)
class Options:
    check: bool = False  # report files that would change, write nothing
    diff: bool = False  # print the change, write nothing
    dialect: str | None = None
    verify: bool = False  # also simulate before and after; write nothing if they behave differently


@dataclass
class Outcome:
    path: str
    dialect: str
    changed: bool = False
    written: bool = False
    diff: str = ""
    error: str = ""  # why the file was not formatted
    skipped: bool = False  # no formatter for this dialect (yet)
    write_error: bool = False  # the formatted text could not be written


def formatter(dialect: str) -> ModuleType | None:
    try:
        return importlib.import_module(f"mcc.compiler.{dialect}.format")
    except ModuleNotFoundError as exc:
        if exc.name in (f"mcc.compiler.{dialect}.format", f"mcc.compiler.{dialect}"):
            return None
        raise


def chosen_profile(path: str, dialect: str, text: str, settings: Settings):
    """The file's profile as every command chooses it (compiler/selection.py)."""
    from mcc.compiler import selection
    from mcc.compiler.span import SourceFile

    return selection.choose(path, dialect, SourceFile(path, text), settings).profile


def format_text(text: str, path: str, dialect: str, settings: Settings = Settings(), strict: bool = False) -> str:
    module = formatter(dialect)
    if module is None:
        return text
    return module.format_text(text, path, chosen_profile(path, dialect, text, settings), strict=strict)


def verify(path: str, dialect: str, before: str, after: str, settings: Settings) -> str:
    """Empty when `after` means the same as `before`; otherwise the first differences."""
    profile = chosen_profile(path, dialect, before, settings)
    old = module_of(driver.check_file(path, dialect, profile, before))  # only the IR stays alive,
    new = module_of(driver.check_file(path, dialect, profile, after))  # not both syntax trees
    if old is None or new is None:
        return "the file could not be analysed"
    return "; ".join(differences(old, new, limit=3))


def module_of(result: driver.FileResult):
    return result.analysis.module if result.analysis is not None else None


def own_errors(path: str, dialect: str, text: str, settings: Settings, limit: int = 3) -> str:
    """The file's own errors (syntax first), as `line:column CODE message`: when a file that cannot
    be formatted has some, they are the reason to show, not an internal error of mcc."""
    try:
        result = driver.check_file(path, dialect, chosen_profile(path, dialect, text, settings), text)
    except Exception:  # noqa: BLE001 - the caller falls back to its own message
        return ""
    errors = [d for d in result.diagnostics if d.severity.value == "error" and d.kind.value != "internal"]
    errors.sort(key=lambda d: (d.kind.value != "syntax", d.span.line, d.span.column))
    shown = "; ".join(f"{d.span.line}:{d.span.column} {d.code} {d.message}" for d in errors[:limit])
    more = f"; and {len(errors) - limit} more" if len(errors) > limit else ""
    return shown + more


def long_line(text: str, limit: int) -> str:
    """Why a text cannot be formatted because of a line far past the device's limit, or ""."""
    if len(text) <= limit:
        return ""
    for number, line in enumerate(text.split("\n"), 1):
        if len(line) > limit:
            return f"line {number} is {len(line):,} characters long; mcc does not format lines over {limit:,} characters"
    return ""


def format_source(path: str, text: str, dialect: str, settings: Settings) -> tuple[str, str]:
    """(formatted text, "") or (text, why it was not formatted): the one formatting step of
    `mcc fmt` for a file and for standard input. A text with a syntax error is not formatted."""
    found = driver.resolve_dialect(path, dialect, settings)
    too_long = long_line(text, found.longest_line)
    if too_long:
        return text, f"{too_long}; the file was left unchanged (G007)"
    preprocessor = found.load_preprocessor()
    if preprocessor is not None:
        from mcc.compiler.span import SourceFile

        directives = preprocessor.directive_lines(SourceFile(path, text))
        if directives:
            return text, (f"not formatted: mcontrol preprocessor source (#{directives[0][1]} on line "
                          f"{directives[0][0]}, M142); format the preprocessor's output instead")
    try:
        formatted = format_text(text, path, found.name, settings, strict=True)
    except SyntaxErrors as exc:
        return text, f"not formatted: {exc}; fix it first"
    except Exception as exc:  # noqa: BLE001 - the no-traceback guarantee
        own = own_errors(path, found.name, text, settings)
        return text, f"not formatted: the file has errors ({own}); fix them first" if own else (
            f"internal error while formatting: {type(exc).__name__}: {exc}. This is a bug in mcc; "
            "please report it with this file")
    if formatted != text:
        problem = verify(path, found.name, text, formatted, settings)
        if problem:
            own = own_errors(path, found.name, text, settings)
            return text, f"not formatted: the file has errors ({own}); fix them first" if own else (
                f"internal error: formatting would change the program ({problem}). This is a bug "
                "in mcc; the file was left unchanged, please report it")
    return formatted, ""


def format_file(path: str, settings: Settings, options: Options = Options()) -> Outcome:
    found = driver.resolve_dialect(path, options.dialect, settings)
    if found is None:
        return Outcome(path, "unknown", error="cannot tell the dialect from the extension; pass --dialect")
    outcome = Outcome(path, found.name)
    if formatter(found.name) is None:
        outcome.skipped = True
        return outcome
    try:
        original = files.read(path)
    except OSError as exc:
        outcome.error = f"cannot read {path}: {exc.strerror or exc}"
        return outcome
    text, outcome.error = format_source(path, original.text, found.name, settings)
    if outcome.error:
        return outcome
    outcome.changed = text != original.text
    if outcome.changed:
        if options.diff:
            outcome.diff = unified_diff(path, original.text, text)
        elif options.verify and (problem := _simulated_difference(path, found.name, original.text, text)):
            outcome.error = f"--verify: {problem}; the file was left unchanged"
        elif not options.check:
            try:
                files.write_atomic(path, text, original)
                outcome.written = True
            except OSError as exc:
                outcome.error = f"cannot write {path}: {exc.strerror or exc}; the file was left unchanged"
                outcome.write_error = True
    return outcome


def _simulated_difference(path: str, dialect: str, before: str, after: str) -> str:
    from mcc.sim.verify import check_translation, explain

    problem = check_translation(path, dialect, before, after)
    return explain(problem) if problem else ""
