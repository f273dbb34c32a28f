"""Inline suppression: `noqa` in the dialect's own comment syntax, as ruff users know it.

    MA 2000      ' noqa: M301          MCode (backtick or apostrophe comments)
    X1000        ; noqa: A301          Arcus
    1G           ; noqa: X301, X305    X150
    MA 2000      ' noqa                every code on the line

A directive suppresses diagnostics that start on its own line. Syntax and internal errors cannot
be suppressed. A directive (or one of its codes) that suppresses nothing is reported as G101 with
a fix that removes it; a code that does not exist is reported as G104.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field

from mcc.compiler import dialects
from mcc.compiler.codes import registry
from mcc.compiler.config import deselectable
from mcc.compiler.diagnostics import Diagnostic, Diagnostics, Edit, Fix
from mcc.compiler.span import SourceFile, Span

DIRECTIVE = re.compile(r"(?i)(?<![A-Za-z0-9_])noqa(?![A-Za-z0-9_])"
                       r"(?:\s*:\s*(?P<codes>[A-Za-z]+[0-9]+(?:[\s,]+[A-Za-z]+[0-9]+)*))?")
CODE = re.compile(r"[A-Za-z]+[0-9]+")


def markers(dialect: str) -> str:
    """The markers a comment that may hold `noqa` starts with (the dialect's `noqa_comment_markers`)."""
    return dialects.get(dialect).noqa_comment_markers() if dialect in dialects.DIALECTS else ""


def comment_start(line: str, marks: str) -> int | None:
    """Index of the comment marker that starts the line's comment (outside double-quoted text)."""
    quoted = False
    for i, ch in enumerate(line):
        if ch == '"':
            quoted = not quoted
        elif ch in marks and not quoted:
            return i
    return None


@dataclass
class Directive:
    line: int
    span: Span  # "noqa: M301, M302"
    comment: Span  # the whole comment, marker included, with the spaces before it
    only: bool  # the comment holds nothing but the directive
    codes: dict[str, Span] = field(default_factory=dict)  # empty: a bare noqa
    used: set[str] = field(default_factory=set)
    used_bare: bool = False

    @property
    def bare(self) -> bool:
        return not self.codes


def find_directives(source: SourceFile, dialect: str) -> dict[int, Directive]:
    marks = markers(dialect)
    found: dict[int, Directive] = {}
    if not marks or "noqa" not in source.text.lower():
        return found
    for number in range(1, source.line_count + 1):
        text = source.line_text(number)
        if "noqa" not in text.lower():
            continue
        at = comment_start(text, marks)
        if at is None:
            continue
        match = DIRECTIVE.search(text, at + 1)
        if match is None:
            continue
        base = source.line_starts[number - 1]
        codes = {}
        if match.group("codes"):
            for code in CODE.finditer(text, match.start("codes"), match.end("codes")):
                codes.setdefault(code.group().upper(), source.span(base + code.start(), base + code.end()))
        rest = (text[at + 1:match.start()] + text[match.end():]).strip()
        lead = len(text[:at]) - len(text[:at].rstrip())
        found[number] = Directive(number, source.span(base + match.start(), base + match.end()),
                                  source.span(base + at - lead, base + len(text)), not rest, codes)
    return found


def apply(diagnostics: list[Diagnostic], source: SourceFile | None, dialect: str,
          enabled) -> list[Diagnostic]:
    """Drop suppressed diagnostics; add G101/G104 for directives that suppress nothing.

    `enabled(code)` says whether a code is selected for this file (for G101 and G104 themselves).
    """
    if source is None:
        return diagnostics
    directives = find_directives(source, dialect)
    if not directives:
        return diagnostics
    kept = []
    for diag in diagnostics:
        directive = directives.get(diag.span.line) if diag.span.file == source.path else None
        if directive is None or not deselectable(diag.code):
            kept.append(diag)
        elif directive.bare:
            directive.used_bare = True
        elif diag.code in directive.codes:
            directive.used.add(diag.code)
        else:
            kept.append(diag)
    extra = Diagnostics()
    reg = registry()
    for directive in directives.values():
        unknown = [code for code in directive.codes if code not in reg]
        if enabled("G104"):
            for code in unknown:
                extra.add("G104", directive.codes[code], f"'{code}' is not a diagnostic code; this noqa does not "
                                                         "hide what you meant (see `mcc explain --list`)")
        unused = [code for code in directive.codes if code not in directive.used and code not in unknown]
        if not enabled("G101"):
            continue
        if directive.bare and not directive.used_bare:
            extra.add("G101", directive.span, "this noqa suppresses nothing on its line",
                      fix=removal(directive, source))
        elif unused:
            keep = [code for code in directive.codes if code not in unused]
            listed = ", ".join(unused)
            extra.add("G101", directive.span, f"unused noqa: {listed} {'is' if len(unused) == 1 else 'are'} not "
                                              "reported on this line", fix=removal(directive, source, keep))
    return kept + extra.items


def removal(directive: Directive, source: SourceFile, keep: list[str] | None = None) -> Fix:
    """Remove a directive, or only its unused codes, leaving any other comment text alone."""
    if keep:
        span = directive.span
        text = source.text[span.start:span.end]
        head = text[:text.index(":") + 1] if ":" in text else "noqa:"
        return Fix("remove the unused codes", (Edit(span, f"{head} {', '.join(keep)}"),))
    if directive.only:
        return Fix("remove the noqa comment", (Edit(directive.comment, ""),))
    return Fix("remove the noqa", (Edit(directive.span, ""),))
