"""Runs files through the pipeline: read → frontend (parse, lower, check) → backend.

This is where "no input produces a traceback" is enforced: an unexpected exception while
processing one file becomes a G001 internal diagnostic on that file, and the run goes on.
"""

from __future__ import annotations

import gc
import os
import traceback
from contextlib import contextmanager
from dataclasses import dataclass, field
from typing import Any

from mcc.compiler import dialects
from mcc.compiler import ir
from mcc.compiler.analysis import Analysis
from mcc.compiler.diagnostics import Diagnostic, Diagnostics
from mcc.compiler.profiles import Profile
from mcc.compiler import profiles as profiles_mod
from mcc.compiler.span import SourceFile, Span


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
    optimization: Any = None  # opt.OptStats of the compilation
    profile: Profile | None = None  # the profile the file was checked with (compiler/selection.py)
    profile_source: str = ""  # why that one: "command line", "directive", "per-file-profiles", ...
    # the written program was validated against its source (`verify_translation` found no
    # difference): a caller that would validate it again with the same arguments need not
    validated: bool = False

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


def resolve_dialect(path: str, dialect: str | None, settings=None) -> dialects.Dialect | None:
    """--dialect, else the configuration's `extensions` (config.Settings), else the built-in extensions.
    A caller without settings (mcc sim, the validation) gets the nearest configuration's `extensions`
    for an extension that is no dialect's, so a mapped file is read the same by every command."""
    if dialect:
        return dialects.get(dialect)
    mapped = settings.dialect_for(path) if settings is not None else None
    if mapped is not None:
        return dialects.get(mapped)
    found = dialects.from_path(path)
    if found is None and settings is None and os.path.isfile(path):
        from mcc.compiler import config

        mapped = config.Resolver().for_path(path).dialect_for(path)
        return dialects.get(mapped) if mapped is not None else None
    return found


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


def without_long_lines(source: SourceFile, limit: int, diags: Diagnostics) -> SourceFile:
    """The source with the content of every line longer than `limit` removed (the line itself
    stays, empty, so every other line keeps its number and columns), each reported once as G007.
    Offsets after such a line shift; fixes are therefore never applied to a file with G007."""
    text = source.text
    if len(text) <= limit or max(map(len, text.split("\n"))) <= limit:  # the common case, at C speed
        return source
    pieces: list[str] = []
    start = 0
    changed = False
    for number, begin in enumerate(source.line_starts, 1):
        end = text.find("\n", begin)
        end = len(text) if end < 0 else end
        if end - begin > limit:
            diags.add("G007", Span(source.path, number, 1, number, 1, begin, begin),
                      f"line {number} is {end - begin:,} characters long, far past what the device reads; "
                      f"mcc does not analyse lines over {limit:,} characters: split it, or check that this file is "
                      "the program you meant")
            pieces.append(text[start:begin])
            start = end
            changed = True
    if not changed:
        return source
    pieces.append(text[start:])
    return SourceFile(source.path, "".join(pieces))


def has_long_lines(diagnostics) -> bool:
    return any(d.code == "G007" for d in diagnostics)


@contextmanager
def fewer_collections():
    """No cyclic garbage collection while a file is analysed: a syntax tree and its IR are hundreds
    of thousands of live objects, almost none of them garbage, that the collector would walk again
    and again (it made `check` on 16,000 lines take three times as long as on 8,000; with its
    threshold raised it still took 8 % of `check`). Reference counting still frees what is dropped;
    the few cycles made are collected after, when the collector is back on. Restored on the way out
    (nested uses leave it off until the outermost one ends). A check holds it over all of its steps
    (analysis, then memory): turned back on in between, the collector's first run would walk every
    object the analysis made, all of them still in use, before the memory pricing."""
    was_enabled = gc.isenabled()
    gc.disable()
    try:
        yield
    finally:
        if was_enabled:
            # The objects made meanwhile go to the oldest generation at once (freeze, then unfreeze:
            # two list splices), as they would after surviving two collections: back on with them
            # all young, the collector's first run would walk every one of them, in use by the
            # result, to find nothing (about 10 % of a check). A check and a compile make no
            # reference cycles (tests/test_no_cycles.py), so nothing waits there for a full
            # collection that the young generations would have freed.
            gc.freeze()
            gc.unfreeze()
            gc.enable()


def analyze_source(source: SourceFile, dialect: dialects.Dialect, profile: Profile | None,
                   diags: Diagnostics) -> Analysis | None:
    source = without_long_lines(source, dialect.longest_line, diags)
    try:
        frontend = dialect.load_frontend()
        with fewer_collections():
            analysis = frontend.analyze(source, profile_for(dialect, profile))
    except Exception as exc:  # noqa: BLE001 - the no-traceback guarantee
        internal_error(diags, source.path, exc, "checking")
        return None
    if analysis.diagnostics.has_errors:
        analysis = neighbour_language(analysis, dialect)
    diags.extend(analysis.diagnostics)
    return analysis


def verify_ir(result: FileResult) -> None:
    """Run the IR verifier on a checked file and add each violation as a G010 diagnostic."""
    from mcc.compiler import ir_verify

    module = result.analysis.module if result.analysis is not None else None
    if module is None:
        return
    diags = Diagnostics(result.diagnostics)
    for violation in ir_verify.verify(module):
        diags.add("G010", violation.span or file_span(result.path),
                  f"IR contract broken ({violation.group}) at {violation.where}: {violation.message}")
    result.diagnostics = diags.items


def ir_keeps_contract(result: FileResult) -> bool:
    """Another dialect's backend trusts the IR's meaning (units, modes, names): a module that
    breaks the contract is refused (G011, naming the first violation) rather than converted into
    a program that does something else."""
    from mcc.compiler import ir_verify

    violations = ir_verify.verify(result.analysis.module)
    if not violations:
        return True
    first = violations[0]
    diags = Diagnostics(result.diagnostics)
    diags.add("G011", first.span or file_span(result.path),
              f"cannot convert to {result.target}: {first.message} ({first.where}); "
              f"{len(violations)} construct(s) of this {result.dialect} program are not yet expressed in the "
              "IR's neutral terms")
    result.diagnostics = diags.items
    return False


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
        with fewer_collections():
            analysis.memory, found = measure(analysis.module, profile_for(dialect, profile))
    except Exception as exc:  # noqa: BLE001 - the no-traceback guarantee
        internal_error(diags, analysis.source.path, exc, "measuring program memory")
        return
    diags.extend(found)


def check_file(path: str, dialect: str | None = None, profile: Profile | None = None,
               text: str | None = None, memory: bool = True, settings=None) -> FileResult:
    """Parse, lower and check one file (the work of `mcc check`); with `memory`, also the program
    memory against the target's budget (compile measures it in the backend instead).

    The profile is chosen by `selection.choose`: `profile` (the command line's) if it is for the
    file's dialect, else a `mcc: profile=` line at the top of the file, else the configuration
    `settings` (per-file-profiles, target), else the dialect's default; with the default, a file
    that fails and fits another profile gets that profile named (G021)."""
    diags = Diagnostics()
    found = resolve_dialect(path, dialect, settings)
    if found is None:
        ext = os.path.splitext(path)[1].lstrip(".").lower() or "lxt"
        diags.add("G004", file_span(path),
                  f"cannot tell the dialect of '{path}' from its extension "
                  f"(known: {', '.join(dialects.all_extensions())}); pass --dialect, or map the extension in "
                  f"[tool.mcc]: extensions = {{{ext} = \"mcode\"}}")
        return FileResult(path, dialect or "unknown", diags.items)
    source = SourceFile(path, text) if text is not None else read_source(path, diags)
    result = FileResult(path, found.name, source=source)
    if source is not None:
        from mcc.compiler import selection

        choice = selection.choose(path, found.name, source, settings, profile)
        diags.extend(choice.diagnostics)
        profile = result.profile = choice.profile
        result.profile_source = choice.source
        with fewer_collections():  # one pause for the whole check: see `fewer_collections`
            result.analysis = analyze_source(source, found, profile, diags)
            if memory and result.analysis is not None and not diags.has_errors:
                measure_memory(result.analysis, found, profile, diags)
        if not choice.chosen and diags.has_errors:
            suggest_profile(result, found, diags)
    result.diagnostics = diags.items
    return result


def suggest_profile(result: FileResult, dialect: dialects.Dialect, diags: Diagnostics) -> None:
    """A failing file read with the dialect's default profile that fits another built-in profile
    of its dialect better: one G021 naming it replaces the errors (compiler/selection.py)."""
    from mcc.compiler import selection

    errors = sum(1 for d in diags.items if d.severity.value == "error")
    if any(d.code in ("G001", "G020") for d in diags.items):
        return  # an internal error, or a file in another language altogether

    def errors_with(profile: Profile) -> int:
        trial = Diagnostics()
        analysis = analyze_source(result.source, dialect, profile, trial)
        if analysis is not None and not trial.has_errors:
            measure_memory(analysis, dialect, profile, trial)
        return sum(1 for d in trial.items if d.severity.value == "error")

    try:
        found = selection.suggest(result.source, dialect.name, result.profile, errors, errors_with)
    except Exception as exc:  # noqa: BLE001 - the no-traceback guarantee
        internal_error(diags, result.path, exc, "looking for the profile the file fits")
        return
    if found is not None:
        diags.items[:] = [d for d in diags.items if d.code == "G022"] + [found]


BUDGET_CODES = frozenset({"A201", "X203", "M116"})  # the program does not fit the target's memory


def compile_file(path: str, dialect: str | None = None, target: str | None = None,
                 profile: Profile | None = None, text: str | None = None, opt_level: str = "O1",
                 passes: str | None = None, verify: bool = True, scenarios: list | None = None,
                 always_verify: bool = False, source_profile: Profile | None = None, settings=None) -> FileResult:
    """Check one file and, when it has no errors, optimize its IR at `opt_level` (or run the
    comma-separated `passes`) and generate code for the target dialect.

    With `verify` (the default) the program written is validated against its source in the
    simulator whenever it is not a plain re-spelling of it: another target, or a pass that changed
    something (`needs_validation`); `always_verify` validates in every case. A difference is S010
    on the source line and the listing is not to be written. `scenarios` replace the default ones
    (docs/SIMULATOR.md, "Verification").

    `source_profile` is the product the program was written for when it is not `profile`'s: the
    file is checked with it, and an MCode program moved to another MCode family (MDrivePlus ->
    Lexium) is converted on the way (the dialect's `migration` module, compiler/mcode/migrate.py) and always validated."""
    result = check_file(path, dialect, source_profile or profile, text, memory=False, settings=settings)
    result.target = target or result.dialect
    analysis = result.analysis
    if analysis is None or analysis.module is None or result.has_errors:
        return result
    diags = Diagnostics(result.diagnostics)
    programs = [r for r in analysis.module.routines if r.kind is ir.RoutineKind.PROGRAM]
    if programs and result.target != result.dialect:
        for routine in programs:  # a conversion of several programs at once would be another program
            diags.add("G003", routine.span or file_span(path),
                      f"program {routine.number} runs at the same time as program 0: a {result.target} program runs "
                      f"one program at a time, so the file cannot be converted as it is; compile it to {result.dialect}, "
                      "or convert each program in a file of its own")
        result.diagnostics = diags.items
        return result
    if result.target != result.dialect and not ir_keeps_contract(result):
        return result
    if programs:  # the optimizer does not know that the programs share variables and the machine
        opt_level, passes = "O0", None
    try:
        target_dialect = dialects.get(result.target)
        # the file's own profile for its own dialect (compiler/selection.py), the command line's for
        # another, and always the command line's when the source names its own (a migration)
        own = result.target == result.dialect and result.profile is not None and source_profile is None
        target_profile = result.profile if own else profile_for(target_dialect, profile)
        module = analysis.module
        migrating = False
        migrate = target_dialect.load_migration() if source_profile is not None else None
        if migrate is not None:
            migrating = migrate.differs(source_profile, target_profile)
        if migrating:
            module = migrate.migrate(module, source_profile, target_profile, diags)
            if diags.has_errors:
                result.diagnostics = diags.items
                return result
        dropped = []
        if result.target != result.dialect and (settings is None or settings.drop_drive_setup):
            from mcc.backends import drive_setup  # a conversion only: docs/decisions/0016

            module, dropped = drive_setup.drop(module, result.target)
            for item in dropped:
                diags.add(drive_setup.CODE, item.span or file_span(path),
                          drive_setup.message(item, target_dialect.title))
        listing, stats = generate(module, target_dialect, target_profile, opt_level, passes)
        result.optimization = stats
        if any(p.changed for p in stats.passes):
            baseline, _ = generate(module, target_dialect, target_profile, "O0", None)
            if new_errors(listing, baseline):
                # The optimized graph is one the target's structurer cannot write although the
                # program as written can be: keep the program as written rather than fail.
                listing, stats.fallback = baseline, True
            stats.lines_before = target_lines(baseline)
        elif stats.passes:  # nothing changed: the listing is the program as written
            stats.lines_before = target_lines(listing)
        stats.lines_after = target_lines(listing)
        budget = [d for d in listing.diagnostics if d.code in BUDGET_CODES and d.severity.value == "error"]
        if budget and not passes:
            # one note for every budget diagnostic: whether a higher level fits does not depend on
            # the diagnostic (asked once per diagnostic, a program over its memory by many sequences
            # was compiled twice per sequence: minutes for a 150-deep call chain, issue 26)
            note = fits_at(module, target_dialect, target_profile, opt_level)
            listing.diagnostics.items[:] = [d for d in listing.diagnostics
                                            if d not in budget] + [with_level_note(d, note) for d in budget]
        level = f"; optimization: -{stats.level}" + (f" (passes {passes})" if passes else "")
        listing.header = "\n".join(filter(None, [listing.header.rstrip("\n"), level]))
        diags.extend(listing.diagnostics)
        if dropped:
            drive_setup.with_comments(listing, dropped, target_dialect.comment)
        refuse_divisions(module, result, target_profile, diags)
        result.listing = listing
        if verify and not diags.has_errors and (always_verify or migrating or needs_validation(result, stats)):
            verify_translation(result, target_profile, diags, scenarios,
                               source_profile if migrating else None)
    except Exception as exc:  # noqa: BLE001 - the no-traceback guarantee
        internal_error(diags, path, exc, f"generating {result.target} code")
    result.diagnostics = diags.items
    return result


def refuse_divisions(module: ir.Module, result: FileResult, target_profile: Profile, diags: Diagnostics) -> bool:
    """Refuse upfront (G040) each division the target product would round otherwise than the
    source's (backends/division.py): the backends write a division as it is, and the validation
    would only stop it late, when a scenario reaches a negative quotient."""
    from mcc.backends.division import CODE, refusals

    if result.target == result.dialect and module.profile == target_profile.name:
        return False
    source_profile = result.profile if result.profile is not None else profile_for(
        dialects.get(result.dialect), None)
    found = refusals(module, source_profile, target_profile, result.target)
    for refusal in found:
        diags.add(CODE, refusal.span or file_span(result.path), refusal.message)
    return bool(found)


def needs_validation(result: FileResult, stats) -> bool:
    """Whether the program written may behave otherwise than its source: it is in another dialect,
    or a pass of the optimizer changed something (`PassStat.changed`); a same-dialect compile whose
    passes changed nothing writes the program as it was written, re-spelled."""
    return result.target != result.dialect or stats is None or stats.fallback or stats.changed


def verify_translation(result: FileResult, target_profile: Profile, diags: Diagnostics,
                       scenarios: list | None = None, source_profile: Profile | None = None) -> None:
    """The written program is simulated against its source (docs/SIMULATOR.md): one that the
    simulator finds behaving differently is an error (S010) on the source line of the first
    divergence, so nothing is written; a compile never exits 0 with a program that does something
    else."""
    import re

    from mcc.sim.verify import check_translation, explain

    problem = check_translation(result.path, result.dialect, result.analysis.module, result.listing.text,
                                result.target, target_profile, scenarios, source_profile)
    if not problem:
        result.validated = True
        return
    found = re.match(r"line (\d+), ", problem)
    line = int(found.group(1)) if found else 1
    text = result.source.line_text(line) if result.source is not None and found else ""
    advice = "compile to the source dialect, or set what the output needs explicitly in the source" \
        if result.target != result.dialect else "compile with -O0, or report the optimizer's mistake"
    diags.add("S010", Span(result.path, line, 1, line, max(2, len(text) + 1)),
              f"the {result.target} program does not behave like the source: {explain(problem)}; nothing was "
              f"written ({advice})")


def generate(module: ir.Module, target: dialects.Dialect, profile: Profile, level: str, passes: str | None):
    """The listing of `module` optimized at `level`; the analysis's own module is left untouched."""
    from mcc.compiler import opt

    work = ir.copy_module(module) if level != "O0" or passes else module
    with fewer_collections():
        stats = opt.optimize(work, level, profile, passes)
        return target.load_backend().emit(work, profile), stats


def target_lines(listing) -> int:
    """The size the target's memory sees: Arcus assembly lines under the cost model, else lines."""
    return int(listing.stats.get("asm_lines", len(listing.lines)))


def new_errors(listing, baseline) -> bool:
    """Whether `listing` has an error code `baseline` (the same program at -O0) does not."""
    before = {d.code for d in baseline.diagnostics if d.severity.value == "error"}
    return any(d.severity.value == "error" and d.code not in before for d in listing.diagnostics)


def fits_at(module: ir.Module, target: dialects.Dialect, profile: Profile, level: str) -> str:
    """A note on whether a higher optimization level makes the program fit the target's memory."""
    from mcc.compiler.opt import LEVELS

    order = list(LEVELS)
    for higher in order[order.index(level) + 1 if level in order else 1:]:
        listing, _ = generate(module, target, profile, higher, None)
        if not any(d.code in BUDGET_CODES and d.severity.value == "error" for d in listing.diagnostics):
            return f"at -{higher} the program fits ({listing.stats.get('asm_lines', len(listing.lines))} lines)"
    return "no optimization level makes it fit: shorten the program"


def with_level_note(diag: Diagnostic, note: str) -> Diagnostic:
    import dataclasses

    return dataclasses.replace(diag, notes=diag.notes + (note,))
