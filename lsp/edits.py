"""Whole-line text edits from one text to another, as an editor applies them.

Both formatting and "fix all" compute the new text of the whole document the way the command line
does (`mcc fmt`, `mcc lint --fix`) and send the smallest edits of whole lines. Lines are cut as LSP
counts them (after CRLF, CR or LF) and keep their own line ends, so the document after the edits
is the new text byte for byte.
"""

from __future__ import annotations

import difflib
import re

from lsprotocol import types as t

LINE = re.compile(r"[^\r\n]*(?:\r\n|\r|\n)|[^\r\n]+\Z")  # a line with its end, as LSP counts lines


def newline_of(text: str) -> str:
    """The line end the command line writes a file back with (compiler/files.py: decode, encode)."""
    return "\r\n" if "\r\n" in text else "\r" if "\r" in text else "\n"


def with_newlines_of(document: str, text: str) -> str:
    """`text` (with LF line ends, as mcc works on it) with the line ends of `document`."""
    newline = newline_of(document)
    return text if newline == "\n" else text.replace("\n", newline)


def line_edits(before_text: str, after_text: str, first_line: int | None = None,
               last_line: int | None = None) -> list[t.TextEdit]:
    """The edits turning `before_text` into `after_text` (positions in characters); with a line
    range, only those that touch it."""
    if before_text == after_text:
        return []
    before = LINE.findall(before_text)
    after = LINE.findall(after_text)
    out = []
    for a1, a2, b1, b2 in changes(before, after):
        if first_line is not None and last_line is not None and (a2 - 1 < first_line or a1 > last_line):
            if not (a1 == a2 and first_line <= a1 <= last_line):
                continue
        out.append(t.TextEdit(range=t.Range(position(before, a1), position(before, a2)),
                              new_text="".join(after[b1:b2])))
    return out


def changes(before: list[str], after: list[str]) -> list[tuple[int, int, int, int]]:
    """(a1, a2, b1, b2): before[a1:a2] becomes after[b1:b2], in order. The lines both texts begin
    and end with are left out first; when as many lines stay in between on each side (formatting
    and most fixes change lines in place), they are compared line by line. Otherwise difflib
    matches them, treating lines that recur very often as junk on a long stretch: without that a
    program of many identical lines (`WAITX`, `H`) took seconds to diff, the edits being no
    less right, only larger."""
    start, limit = 0, min(len(before), len(after))
    while start < limit and before[start] == after[start]:
        start += 1
    end_a, end_b = len(before), len(after)
    while end_a > start and end_b > start and before[end_a - 1] == after[end_b - 1]:
        end_a, end_b = end_a - 1, end_b - 1
    if end_a - start == end_b - start:
        found, run = [], None
        for index in range(start, end_a):
            if before[index] != after[index]:
                run = (run[0] if run else index, index + 1)
            elif run:
                found.append((run[0], run[1], run[0], run[1]))
                run = None
        if run:
            found.append((run[0], run[1], run[0], run[1]))
        return found
    matcher = difflib.SequenceMatcher(a=before[start:end_a], b=after[start:end_b], autojunk=end_a - start > 200)
    return [(start + a1, start + a2, start + b1, start + b2)
            for op, a1, a2, b1, b2 in matcher.get_opcodes() if op != "equal"]


def position(lines: list[str], index: int) -> t.Position:
    """The start of line `index`; past the last line, the end of the text (after a last line
    without a line end, that is on the last line itself)."""
    if index >= len(lines) and lines and not lines[-1].endswith(("\n", "\r")):
        return t.Position(len(lines) - 1, len(lines[-1]))
    return t.Position(index, 0)
