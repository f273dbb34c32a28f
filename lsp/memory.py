"""Program memory as the user edits: what each routine costs on the device.

Arcus stores the compiled program in assembly lines (the backend's cost model, the profile's
budget); an X150 device stores each sequence as bytes (one per character and delimiter, L241)
in an 8,000-byte store. The numbers come from the dialect's own backend (`Listing.detail` for
Arcus, the listing's lines for X150), attributed to the routines of the editor model by the
source lines they came from. Whether and how a dialect is priced is its editor's (lsp/editor.py:
`prices_memory`, `memory`); MCode has no memory model in mcc, so it shows nothing.
"""

from __future__ import annotations

import bisect
from dataclasses import dataclass, field

from mcc.compiler import dialects, driver
from mcc.lsp.editor import editor_of


@dataclass
class RoutineUsage:
    name: str
    line: int  # 1-based line of the routine's head
    used: int
    error_lines: tuple[int, ...] = ()  # lines of the routine with errors (priced without them)


@dataclass
class Usage:
    unit: str  # "assembly lines" | "bytes"
    total: int
    budget: int
    routines: list[RoutineUsage] = field(default_factory=list)
    # priced from the lines that analyse: the lines with errors (what the IR may lack), else ()
    error_lines: tuple[int, ...] = ()

    def describe(self, used: int, error_lines: tuple[int, ...] = ()) -> str:
        share = f" ({100.0 * used / self.budget:.1f}% of {self.budget})" if self.budget else ""
        return f"{used} {self.unit}{share}{with_errors(error_lines)}"


def with_errors(lines: tuple[int, ...]) -> str:
    """What a figure computed from the lines that analyse adds: which lines it lacks."""
    if not lines:
        return ""
    if len(lines) == 1:
        return f", without line {lines[0]} (error)"
    if len(lines) <= 3:
        return f", without lines {', '.join(map(str, lines))} (errors)"
    return f", without {len(lines)} lines with errors"


def priced(snap) -> bool:
    """Whether `usage` has anything to compute for the snapshot (the backend's work). A program
    with errors is priced too, from the lines that analyse (the lowering leaves a statement with
    an error out): analysis.figures_wanted decides when that is shown."""
    return editor_of(snap.dialect).prices_memory and snap.module is not None


def carried(previous: Usage | None, snap) -> Usage | None:
    """The previous version's figures placed on this version's routines (matched by name), shown
    until this version is priced, and while it has errors (the figures of the last version without
    errors: analysis.figures_wanted), so that the code lenses and inlay hints do not vanish or
    change while the user types. Figures that were already priced without some lines say so with
    this version's lines with errors."""
    if previous is None or not editor_of(snap.dialect).prices_memory:
        return None
    lines = {routine.name: routine.span.line for routine in snap.index.routines}
    errors = snap.error_lines if previous.error_lines else ()
    return Usage(previous.unit, previous.total, previous.budget,
                 [RoutineUsage(r.name, lines[r.name], r.used, routine_errors(snap, r.name, errors))
                  for r in previous.routines if r.name in lines], errors)


def routine_errors(snap, name: str, errors: tuple[int, ...]) -> tuple[int, ...]:
    """The lines of `errors` within the routine of the editor model named `name`."""
    for routine in snap.index.routines:
        if routine.name == name:
            return tuple(line for line in errors if routine.span.line <= line <= routine.span.end_line)
    return ()


def usage(snap) -> Usage | None:
    if not priced(snap):
        return None
    try:
        dialect = dialects.get(snap.dialect)
        listing = dialect.load_backend().emit(snap.module, driver.profile_for(dialect, snap.profile))
    except Exception:  # noqa: BLE001 - no memory figures is better than no editor
        return None
    return editor_of(snap.dialect).memory(snap, listing, tuple(snap.error_lines))


def by_source_lines(snap, listing, unit: str, total_key: str, budget_key: str, errors: tuple[int, ...]) -> Usage:
    """Usage from a listing whose `detail` rows each cost one `unit` (an assembly line) and name
    the source lines they came from: each row is counted to the routine of its first source line;
    the total and the budget are the listing's `stats[total_key]` and `stats[budget_key]`."""
    rows = [(sources, 1) for _, sources in (listing.detail or [])]
    result = Usage(unit, int(listing.stats.get(total_key, len(rows))),
                   int(listing.stats.get(budget_key, 0)), error_lines=errors)
    routines = sorted(snap.index.routines, key=lambda r: r.span.line)
    starts = [r.span.line for r in routines]
    counts = [0] * len(routines)
    for sources, cost in rows:
        if not sources:
            continue
        line = sources[0].line
        i = bisect.bisect_right(starts, line) - 1
        if i >= 0 and routines[i].span.line <= line <= routines[i].span.end_line:
            counts[i] += cost
    for routine, count in zip(routines, counts, strict=True):
        result.routines.append(RoutineUsage(routine.name, routine.span.line, count,
                                            routine_errors(snap, routine.name, errors)))
    return result
