"""Document and range formatting with `mcc fmt`'s rules (`mcc.compiler.lint.formatting`).

The whole text is formatted and verified by `mcc fmt`'s own step (`formatting.format_source`: the
IR must not change, a text with a syntax error is not formatted), and written with the document's
own line ends as `mcc fmt` writes a file (`files.encode`: the first of CRLF, CR, LF the text uses),
so the document after the edits equals, byte for byte, what `mcc fmt` makes of the same file
(tests/lsp/test_formatting_equals_fmt.py compares them over the samples). The result is sent as
the smallest edits of whole lines, each line with its own line end; range formatting keeps only
the edits that touch the range's lines.
"""

from __future__ import annotations

import difflib
import re

from lsprotocol import types as t

from mcc.compiler.lint import formatting
from mcc.compiler.span import normalise_newlines

LINE = re.compile(r"[^\r\n]*(?:\r\n|\r|\n)|[^\r\n]+\Z")  # a line with its end, as LSP counts lines


def newline_of(text: str) -> str:
    """The line end `mcc fmt` writes the file back with (compiler/files.py: decode, encode)."""
    return "\r\n" if "\r\n" in text else "\r" if "\r" in text else "\n"


def target(snap, document: str) -> str | None:
    """What `mcc fmt` would write for the document's text; None when it formats nothing."""
    if formatting.formatter(snap.dialect) is None:
        return None
    formatted, problem = formatting.format_source(snap.path, normalise_newlines(document), snap.dialect,
                                                  snap.settings)
    if problem.startswith("not formatted:"):
        return None  # the program's own errors, which the editor already shows: nothing to format
    if problem:
        raise RuntimeError(problem)
    newline = newline_of(document)
    return formatted if newline == "\n" else formatted.replace("\n", newline)


def edits(snap, document: str, first_line: int | None = None, last_line: int | None = None) -> list[t.TextEdit]:
    """The edits that turn the editor's `document` (its text as the editor holds it, line ends
    included) into what `mcc fmt` writes; positions in characters."""
    wanted = target(snap, document)
    if wanted is None or wanted == document:
        return []
    before = LINE.findall(document)
    after = LINE.findall(wanted)
    out = []
    matcher = difflib.SequenceMatcher(a=before, b=after, autojunk=False)
    for op, a1, a2, b1, b2 in matcher.get_opcodes():
        if op == "equal":
            continue
        if first_line is not None and (a2 - 1 < first_line or a1 > last_line):
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
