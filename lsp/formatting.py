"""Document and range formatting with `mcc fmt`'s rules (`mcc.compiler.lint.formatting`).

The whole text is formatted and verified by `mcc fmt`'s own step (`formatting.format_source`: the
IR must not change, a text with a syntax error is not formatted); the result is sent as the
smallest line edits. Range formatting keeps only the edits inside the range's lines.
"""

from __future__ import annotations

import difflib

from lsprotocol import types as t

from mcc.compiler.lint import formatting


def edits(snap, text: str, first_line: int | None = None, last_line: int | None = None) -> list[t.TextEdit]:
    if formatting.formatter(snap.dialect) is None:
        return []
    formatted, problem = formatting.format_source(snap.path, text, snap.dialect, snap.settings)
    if problem.startswith("not formatted:"):
        return []  # the program's own errors, which the editor already shows: nothing to format
    if problem:
        raise RuntimeError(problem)
    if formatted == text:
        return []
    before = text.split("\n")
    after = formatted.split("\n")
    out = []
    matcher = difflib.SequenceMatcher(a=before, b=after, autojunk=False)
    for op, a1, a2, b1, b2 in matcher.get_opcodes():
        if op == "equal":
            continue
        if first_line is not None and (a2 - 1 < first_line or a1 > last_line):
            if not (a1 == a2 and first_line <= a1 <= last_line):
                continue
        start = t.Position(a1, 0)
        new = "".join(line + "\n" for line in after[b1:b2])
        if a2 >= len(before):  # the edit runs to the end of the text: no newline after the last line
            new = "\n".join(after[b1:b2])
            end = t.Position(len(before) - 1, len(before[-1]))
            if a1 >= len(before):  # lines added after the last one
                start, new = end, "\n" + new
        else:
            end = t.Position(a2, 0)
        out.append(t.TextEdit(range=t.Range(start, end), new_text=new))
    return out
