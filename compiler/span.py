"""Source positions.

Every syntax node, IR operation and diagnostic carries a `Span` so that messages, the simulator's
trace and the backends' source maps all point back to the user's text. Lines and columns are
1-based; the end column is exclusive (the column just after the last character), as in Lark and LSP.
Offsets are 0-based character offsets into the normalised text (line ends folded to "\\n").
"""

from __future__ import annotations

import bisect
from itertools import accumulate
from dataclasses import dataclass


@dataclass(slots=True, unsafe_hash=True)
class Span:
    """A range of the source. A value: never changed once made (it is shared by the syntax tree,
    the IR and the diagnostics). It is not declared `frozen` only because a frozen dataclass sets
    each field through `object.__setattr__`, which made creating one six times as slow, and a
    parse creates one for every token it reads (docs/PERFORMANCE.md)."""

    file: str
    line: int
    column: int
    end_line: int
    end_column: int
    start: int = 0
    end: int = 0

    def to(self, other: "Span") -> "Span":
        """The span from the start of `self` to the end of `other`."""
        return Span(self.file, self.line, self.column, other.end_line, other.end_column,
                    self.start, other.end)

    @property
    def label(self) -> str:
        return f"{self.file}:{self.line}:{self.column}"


def normalise_newlines(text: str) -> str:
    """Fold CRLF and lone CR (the device terminator) to LF, so line numbers mean what editors show."""
    if "\r" in text:
        text = text.replace("\r\n", "\n").replace("\r", "\n")
    return text


class SourceFile:
    """A source text with a line index, for turning offsets into spans and spans into lines."""

    def __init__(self, path: str, text: str):
        self.path = path
        self.text = normalise_newlines(text)
        self._line_starts: list[int] | None = None

    @classmethod
    def read(cls, path: str, display: str | None = None) -> "SourceFile":
        """Read a file as UTF-8, falling back to Latin-1: manuals' listings carry µ and ± in comments.
        Only regular files are read (mcc.compiler.files); anything else raises FileError (an OSError)."""
        from mcc.compiler.files import read_bytes

        data = read_bytes(path)
        try:
            text = data.decode("utf-8-sig")
        except UnicodeDecodeError:
            text = data.decode("latin-1")
        return cls(display or path, text)

    @property
    def line_starts(self) -> list[int]:
        if self._line_starts is None:
            # Each line starts one past the end of the one before it: running sums of the line
            # lengths plus one, all in C (a loop of `find` costs a Python step per line). The sum
            # after the last line is not a line start.
            starts = list(accumulate(map((1).__add__, map(len, self.text.split("\n"))), initial=0))
            starts.pop()
            self._line_starts = starts
        return self._line_starts

    @property
    def line_count(self) -> int:
        return len(self.line_starts)

    def line_text(self, line: int) -> str:
        starts = self.line_starts
        if line < 1 or line > len(starts):
            return ""
        begin = starts[line - 1]
        end = self.text.find("\n", begin)
        return self.text[begin:] if end < 0 else self.text[begin:end]

    def position(self, offset: int) -> tuple[int, int]:
        """1-based (line, column) of a character offset."""
        index = bisect.bisect_right(self.line_starts, offset) - 1
        return index + 1, offset - self.line_starts[index] + 1

    def span(self, start: int, end: int) -> Span:
        line, col = self.position(start)
        end_line, end_col = self.position(end)
        return Span(self.path, line, col, end_line, end_col, start, end)

    def line_span(self, line: int) -> Span:
        """The span of a whole line (without its newline)."""
        begin = self.line_starts[line - 1]
        return self.span(begin, begin + len(self.line_text(line)))
