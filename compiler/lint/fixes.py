"""Applying fixes: the edits of several diagnostics at once, never two that touch the same text.

As in ruff, fixes are applied in passes: each pass takes the fixes whose edits do not overlap an
already accepted one, applies them, and the file is checked again (a fix may make another finding
appear or disappear). Only safe fixes are applied unless unsafe fixes are asked for.
"""

from __future__ import annotations

import difflib

from mcc.compiler.diagnostics import Diagnostic, Edit, Fix


def applicable(diagnostics: list[Diagnostic], unsafe: bool) -> list[Fix]:
    return [d.fix for d in diagnostics if d.fix is not None and d.fix.edits and (d.fix.safe or unsafe)]


def apply(text: str, fixes: list[Fix]) -> tuple[str, int]:
    """Apply the fixes that do not conflict; (new text, number of fixes applied)."""
    taken: list[tuple[int, int]] = []
    edits: list[Edit] = []
    count = 0
    for fix in sorted(fixes, key=lambda f: min(e.span.start for e in f.edits)):
        ranges = [(e.span.start, e.span.end) for e in fix.edits]
        if any(not 0 <= a <= b <= len(text) for a, b in ranges):
            continue  # a span that does not fit this text: never guess
        if any(overlaps(r, t) for r in ranges for t in taken):
            continue
        taken += ranges
        edits += fix.edits
        count += 1
    for edit in sorted(edits, key=lambda e: (e.span.start, e.span.end), reverse=True):
        text = text[:edit.span.start] + edit.text + text[edit.span.end:]
    return text, count


def overlaps(a: tuple[int, int], b: tuple[int, int]) -> bool:
    """Ranges overlap, or are the same insertion point (their order would be arbitrary)."""
    if a[0] == a[1] or b[0] == b[1]:
        return a[0] == b[0] or b[0] < a[0] < b[1] or a[0] < b[0] < a[1]
    return a[0] < b[1] and b[0] < a[1]


def unified_diff(path: str, before: str, after: str) -> str:
    lines = difflib.unified_diff(before.splitlines(keepends=True), after.splitlines(keepends=True),
                                 fromfile=f"a/{path}", tofile=f"b/{path}")
    out = []
    for line in lines:
        out.append(line if line.endswith("\n") else line + "\n\\ No newline at end of file\n")
    return "".join(out)
