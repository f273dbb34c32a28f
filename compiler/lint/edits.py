"""Building text edits for fixes: whole lines, insertions after a line, replacements.

Offsets are those of `SourceFile.text` (line ends folded to "\\n"), like every span.
"""

from __future__ import annotations

from mcc.compiler.diagnostics import Edit
from mcc.compiler.span import SourceFile, Span


def replace(span: Span, text: str) -> Edit:
    return Edit(span, text)


def line_bounds(source: SourceFile, line: int) -> tuple[int, int]:
    """Offsets of the start of `line` and of the start of the next line (or the end of the text)."""
    start = source.line_starts[line - 1]
    end = source.text.find("\n", start)
    return start, len(source.text) if end < 0 else end + 1


def delete_line(source: SourceFile, line: int) -> Edit:
    """Delete a whole line, its line end included."""
    start, end = line_bounds(source, line)
    return Edit(source.span(start, end), "")


def insert_after_line(source: SourceFile, line: int, text: str) -> Edit:
    """Insert `text` (whole lines, ending in "\\n") after `line`."""
    start, end = line_bounds(source, line)
    if end == len(source.text) and not source.text.endswith("\n"):
        return Edit(source.span(end, end), "\n" + text.rstrip("\n"))
    return Edit(source.span(end, end), text)
