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
    matcher = difflib.SequenceMatcher(a=before, b=after, autojunk=False)
    for op, a1, a2, b1, b2 in matcher.get_opcodes():
        if op == "equal":
            continue
        if first_line is not None and last_line is not None and (a2 - 1 < first_line or a1 > last_line):
            if not (a1 == a2 and first_line <= a1 <= last_line):
                continue
        out.append(t.TextEdit(range=t.Range(position(before, a1), position(before, a2)),
                              new_text="".join(after[b1:b2])))
    return out


def position(lines: list[str], index: int) -> t.Position:
    """The start of line `index`; past the last line, the end of the text (after a last line
    without a line end, that is on the last line itself)."""
    if index >= len(lines) and lines and not lines[-1].endswith(("\n", "\r")):
        return t.Position(len(lines) - 1, len(lines[-1]))
    return t.Position(index, 0)
