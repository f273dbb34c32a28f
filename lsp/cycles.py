"""Cycle time in the editor (issue 27): a code lens on the line of the loop that forms the main
cycle ("cycle 1.600 s, 1 moves") and on each subroutine's first line ("call 0.250 s").

The figures come from the same bounded run `mcc compile` prints its cycle from
(`sim.cycles.bounded_timing`: 30 virtual seconds, every input low, at most 200,000 steps), run in
the analysis worker after the pause in the typing that prices the program memory, and stopped at
the simulator's next checkpoint when a newer edit arrives. A main loop entered but not closed
within the run says "cycle > N s" (N the virtual seconds the loop ran); a loop that only polls an
input the run keeps low says so; a main loop the program leaves, and a subroutine the run never
called, have no lens. While a file has errors the last figures of a version without any stay,
moved to the lines that now hold the same text (like the memory lenses, so they do not flicker
while the user types); a file that has had none since it was opened is simulated as far as it
analyses (the lowering leaves a statement with an error out), and each lens says which lines it
was run without (analysis.figures_wanted).
"""

from __future__ import annotations

from dataclasses import dataclass, field

from mcc.sim.cycles import cycle_title  # the lens says what `mcc compile` prints


@dataclass
class Lens:
    line: int  # 1-based
    text: str  # the source line's text (stripped): where a carried lens goes in a later version
    title: str


@dataclass
class Cycles:
    lenses: list[Lens] = field(default_factory=list)
    error_lines: tuple[int, ...] = ()  # run without the statements of these lines (errors), else ()

    def title(self, lens: Lens) -> str:
        from mcc.lsp.memory import with_errors

        return lens.title + with_errors(self.error_lines)


def timed(snap) -> bool:
    """Whether there is a program to simulate (a module: with errors, the lines that analyse)."""
    return snap.module is not None


def cycles(snap) -> Cycles | None:
    """The lenses of a bounded run of the snapshot's program (None when it cannot run)."""
    if not timed(snap):
        return None
    from mcc.compiler import dialects, driver
    from mcc.sim.cycles import bounded_timing

    try:
        profile = driver.profile_for(dialects.get(snap.dialect), snap.profile)
    except Exception:  # noqa: BLE001 - the simulator runs without a profile
        profile = None
    try:
        found = bounded_timing(snap.module, profile)
    except Exception:  # noqa: BLE001 - no cycle figures is better than no editor
        return None
    if found is None:
        return None
    out = Cycles(error_lines=tuple(snap.error_lines))
    line = loop_line(snap.module, found.loop)
    title = cycle_title(found)
    if line is not None and title:
        out.lenses.append(Lens(line, snap.source.line_text(line).strip(), title))
    lines = {routine.name: first_line(snap, routine.span) for routine in snap.module.routines
             if routine.span is not None}
    for name, times in sorted(found.calls.items()):
        if name in lines:
            first = lines[name]
            out.lenses.append(Lens(first, snap.source.line_text(first).strip(), f"call {max(times):.3f} s"))
    return out


def first_line(snap, span) -> int:
    """A subroutine's first line as the editor model (and the memory lens) has it: the routine of
    the outline that starts within the IR routine's span (an X150 sequence's XD line, where the IR
    routine starts at the XE that erases it first), else the IR routine's own first line."""
    for routine in snap.index.routines:
        if span.line <= routine.span.line <= span.end_line:
            return routine.span.line
    return span.line


def loop_line(module, label: str) -> int | None:
    """The source line of the main loop's header block."""
    if not label:
        return None
    for routine in module.routines:
        for block in routine.blocks:
            if block.label == label and block.span is not None:
                return block.span.line
    return None


def carried(previous: Cycles | None, snap) -> Cycles | None:
    """The previous version's lenses on the lines of this version that hold the same text (the
    nearest such line to where it was); a lens whose line is gone is dropped."""
    if previous is None:
        return None
    lines = snap.text.split("\n")
    where: dict[str, list[int]] = {}
    for number, text in enumerate(lines, 1):
        where.setdefault(text.strip(), []).append(number)
    out = Cycles(error_lines=tuple(snap.error_lines) if previous.error_lines else ())
    for lens in previous.lenses:
        candidates = where.get(lens.text)
        if candidates:
            line = min(candidates, key=lambda n: abs(n - lens.line))
            out.lenses.append(Lens(line, lens.text, lens.title))
    return out
