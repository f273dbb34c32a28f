"""Between mcc's spans (1-based lines and columns, character offsets) and LSP positions
(0-based lines and characters); diagnostics into LSP diagnostics.

Columns here are counted in characters of the normalised text, as mcc's spans are; the server
converts every position to and from the client's position encoding at the protocol's edge
(`lsp/units.py`), since a UTF-8 or UTF-16 column differs from a character column after any
non-ASCII character on the line.
"""

from __future__ import annotations

import re
from functools import lru_cache
from pathlib import Path

from lsprotocol import types as t

from mcc.compiler.diagnostics import Diagnostic, Severity
from mcc.compiler.span import SourceFile, Span

SEVERITY = {Severity.ERROR: t.DiagnosticSeverity.Error, Severity.WARNING: t.DiagnosticSeverity.Warning,
            Severity.INFO: t.DiagnosticSeverity.Information}
RULES_DIR = Path(__file__).resolve().parent.parent / "docs" / "rules"
LINE_REFERENCE = re.compile(r"\b(?:at |on |from )?line (\d+)\b")


def range_of(span: Span) -> t.Range:
    return t.Range(t.Position(max(span.line - 1, 0), max(span.column - 1, 0)),
                   t.Position(max(span.end_line - 1, 0), max(span.end_column - 1, 0)))


def offset_of(source: SourceFile, position: t.Position) -> int:
    """The character offset of an LSP position (clamped into the text)."""
    starts = source.line_starts
    line = min(max(position.line, 0), len(starts) - 1)
    length = len(source.line_text(line + 1))
    return starts[line] + min(max(position.character, 0), length)


def line_range(source: SourceFile, line: int) -> t.Range:
    """The range of a whole 1-based line."""
    return range_of(source.line_span(min(max(line, 1), source.line_count)))


@lru_cache(maxsize=None)
def rule_page(code: str, base: str | None = None) -> str | None:
    """Where the rule's explanation page is: `base` with {code} filled in, or the page in mcc's
    own docs/rules/ when it is installed from a checkout."""
    if base:
        return base.replace("{code}", code)
    page = RULES_DIR / f"{code}.md"
    return page.as_uri() if page.is_file() else None


def diagnostic(diag: Diagnostic, source: SourceFile, uri: str, rules_url: str | None = None) -> t.Diagnostic:
    page = rule_page(diag.code, rules_url)
    message = diag.message
    if diag.notes:
        message += "\n" + "\n".join(f"note: {note}" for note in diag.notes)
    if diag.fix is not None:
        message += f"\nfix: {diag.fix.description}"
    return t.Diagnostic(
        range=range_of(diag.span),
        message=message,
        severity=SEVERITY.get(diag.severity, t.DiagnosticSeverity.Error),
        code=diag.code,
        code_description=t.CodeDescription(href=page) if page else None,
        source="mcc",
        related_information=related(diag, source, uri) or None,
        data={"code": diag.code, "fixable": diag.fix is not None},
    )


def related(diag: Diagnostic, source: SourceFile, uri: str) -> list[t.DiagnosticRelatedInformation]:
    """The other end of a finding: mcc's messages name it as "line N" (the move still running,
    the first definition, the label), so each line named in the message or its notes becomes a
    related location."""
    out = []
    seen = {diag.span.line}
    for text in (diag.message, *diag.notes):
        if "line " not in text:  # most messages name no line: skip the search (publishing is timed)
            continue
        for match in LINE_REFERENCE.finditer(text):
            line = int(match.group(1))
            if line in seen or not 1 <= line <= source.line_count:
                continue
            seen.add(line)
            what = source.line_text(line).strip() or f"line {line}"
            out.append(t.DiagnosticRelatedInformation(
                location=t.Location(uri, line_range(source, line)), message=f"line {line}: {what}"))
    return out
