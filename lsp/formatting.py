"""Document and range formatting with `mcc fmt`'s rules (`mcc.compiler.lint.formatting`).

The whole text is formatted and verified by `mcc fmt`'s own step (`formatting.format_source`: the
IR must not change, a text with a syntax error is not formatted), and written with the document's
own line ends as `mcc fmt` writes a file (`files.encode`: the first of CRLF, CR, LF the text uses),
so the document after the edits equals, byte for byte, what `mcc fmt` makes of the same file
(tests/lsp/test_formatting_equals_fmt.py compares them over the samples). The result is sent as
the smallest edits of whole lines (edits.py); range formatting keeps only the edits that touch the
range's lines.
"""

from __future__ import annotations

from lsprotocol import types as t

from mcc.compiler.lint import formatting
from mcc.compiler.span import normalise_newlines
from mcc.lsp.edits import line_edits, with_newlines_of


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
    return with_newlines_of(document, formatted)


def edits(snap, document: str, first_line: int | None = None, last_line: int | None = None) -> list[t.TextEdit]:
    """The edits that turn the editor's `document` (its text as the editor holds it, line ends
    included) into what `mcc fmt` writes; positions in characters."""
    wanted = target(snap, document)
    return [] if wanted is None else line_edits(document, wanted, first_line, last_line)
