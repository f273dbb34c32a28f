"""Program memory and cycle time in the editor: a code lens above each routine (and the whole
program) with what it costs on the device against the budget, and the same as an inlay hint at the
end of the routine's first line for editors that show hints rather than lenses; a code lens with
the cycle time on the main loop and each called subroutine (cycles.py)."""

from __future__ import annotations

from lsprotocol import types as t


def code_lenses(snap) -> list[t.CodeLens]:
    return memory_lenses(snap) + cycle_lenses(snap)


def cycle_lenses(snap) -> list[t.CodeLens]:
    """The cycle time on the main loop's line and each called subroutine's first line (cycles.py)."""
    found = snap.cycles
    if found is None:
        return []
    return [t.CodeLens(range=t.Range(t.Position(lens.line - 1, 0), t.Position(lens.line - 1, 0)),
                       command=t.Command(title=found.title(lens), command="")) for lens in found.lenses]


def memory_lenses(snap) -> list[t.CodeLens]:
    usage = snap.memory
    if usage is None:
        return []
    out = []
    where = "program memory" if usage.unit == "assembly lines" else "sequence memory"
    out.append(t.CodeLens(range=t.Range(t.Position(0, 0), t.Position(0, 0)),
                          command=t.Command(title=f"{where}: {usage.describe(usage.total, usage.error_lines)}",
                                            command="")))
    for routine in usage.routines:
        line = routine.line - 1
        title = f"{routine.name}: {usage.describe(routine.used, routine.error_lines)}"
        out.append(t.CodeLens(range=t.Range(t.Position(line, 0), t.Position(line, 0)),
                              command=t.Command(title=title, command="")))
    return out


def inlay_hints(snap, first_line: int, last_line: int) -> list[t.InlayHint]:
    usage = snap.memory
    if usage is None:
        return []
    out = []
    for routine in usage.routines:
        line = routine.line - 1
        if not first_line <= line <= last_line:
            continue
        length = len(snap.source.line_text(routine.line))
        out.append(t.InlayHint(position=t.Position(line, length),
                               label=f"  {usage.describe(routine.used, routine.error_lines)}",
                               kind=t.InlayHintKind.Type, padding_left=True))
    return out
