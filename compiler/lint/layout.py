"""Line layout shared by the formatters: one output line, blank-line groups, comment alignment.

Each dialect's formatter decides what a statement looks like; how lines are laid out around it is
the same everywhere: runs of blank lines collapse to one (none at the end), and the trailing
comments of a block of lines (between blank lines) start in one common column.
"""

from __future__ import annotations

from dataclasses import dataclass

COMMENT_COLUMN = 24  # 0-based: trailing comments start in column 25, as in the manuals' samples


@dataclass
class Out:
    """One output line before comment alignment."""

    indent: str = ""
    code: str = ""
    comment: str = ""
    verbatim: str | None = None  # a line that did not parse: written back unchanged
    blank: bool = False


def collapse_blank_lines(lines: list[Out]) -> list[Out]:
    out: list[Out] = []
    for line in lines:
        if line.blank and (not out or out[-1].blank):
            continue
        out.append(line)
    while out and out[-1].blank:
        out.pop()
    return out


def align_comments(lines: list[Out], limit: int = 0, *, indent_counts: bool = True) -> None:
    """Give the trailing comments of each block one common column.

    With a `limit` (a device line buffer), alignment never pushes a line over it: such a line
    keeps a single space before its comment. `indent_counts=False` measures lines without their
    indentation, for dialects whose downloaders strip it (MCode, see M109/M110).
    """
    block: list[Out] = []
    for line in [*lines, Out(blank=True)]:
        if not line.blank:
            block.append(line)
            continue
        trailing = [item for item in block if item.code and item.comment]
        if trailing:
            column = max(COMMENT_COLUMN, *(len(item.indent + item.code) + 2 for item in trailing))
            for item in trailing:
                gap = column - len(item.indent + item.code)
                measured = len(item.indent) * indent_counts + len(item.code) + gap + len(item.comment)
                if limit and measured > limit:
                    gap = 1
                item.code += " " * gap
        block = []


def render(line: Out) -> str:
    if line.verbatim is not None:
        return line.verbatim
    if line.blank:
        return ""
    return line.indent + line.code + line.comment if line.code else line.indent + line.comment
