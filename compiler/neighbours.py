"""Recognising a file written in a neighbouring controller's language (Parker 6K, another
indexer's X-code) that was given to the wrong reader (an Arcus PMX-2ED-SA, ACE-SDE or DMX-ETH program
is one of the arcus dialect's products: compiler/selection.py suggests its profile, G021).

Such a file fails on most of its lines. Instead of one error per line, mcc reports one diagnostic
(G020) that names what the file looks like, with the lines that show it, so the file never gets a
cascade of errors. The languages and their
markers are data: compiler/catalogs/neighbours.toml. This runs only when the reader already found
many errors, so it costs nothing on programs of the right dialect.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from functools import lru_cache

from mcc.compiler import toml
from mcc.compiler.catalog import CATALOG_DIR
from mcc.compiler.diagnostics import Diagnostic, Diagnostics
from mcc.compiler.span import SourceFile

COMMENT = re.compile(r"[;'`].*$")


@dataclass(frozen=True)
class Language:
    name: str
    readers: tuple[str, ...]
    min_markers: int
    advice: str
    markers: tuple[re.Pattern, ...]
    error_share: float | None = None  # overrides the table's share for this language


@dataclass(frozen=True)
class Table:
    min_errors: int
    error_share: float
    languages: tuple[Language, ...]


@lru_cache(maxsize=1)
def table() -> Table:
    data = toml.load_data_file(CATALOG_DIR / "neighbours.toml")
    languages = tuple(
        Language(raw["name"], tuple(raw.get("readers", ())), int(raw.get("min_markers", 2)), raw.get("advice", ""),
                 tuple(re.compile(m) for m in raw.get("markers", ())),
                 float(raw["error_share"]) if "error_share" in raw else None)
        for raw in data.get("language", []))
    return Table(int(data.get("min_errors", 3)), float(data.get("error_share", 0.3)), languages)


def error_share(source: SourceFile, diagnostics: list[Diagnostic], rules: Table) -> float:
    """The share of statement lines with an error (0 when there are fewer than `min_errors`)."""
    error_lines = {d.span.line for d in diagnostics if d.severity.value == "error"}
    if len(error_lines) < rules.min_errors:
        return 0.0
    statements = sum(1 for line in source.text.splitlines() if COMMENT.sub("", line).strip())
    return len(error_lines) / statements if statements else 0.0


def recognise(source: SourceFile, dialect: str, diagnostics: list[Diagnostic]) -> tuple[Language, list[int]] | None:
    """The neighbouring language the file is written in, and the lines that show it; or None."""
    rules = table()
    share = error_share(source, diagnostics, rules)
    candidates = [lang for lang in rules.languages if dialect in lang.readers
                  and share > 0 and share >= (lang.error_share if lang.error_share is not None else rules.error_share)]
    if not candidates:
        return None
    lines = [COMMENT.sub("", line).upper() for line in source.text.splitlines()]
    best: tuple[int, Language, list[int]] | None = None
    for lang in candidates:
        matched = 0
        evidence: list[int] = []
        for marker in lang.markers:
            hits = [n for n, text in enumerate(lines, 1) if marker.search(text)]
            if hits:
                matched += 1
                evidence.append(hits[0])
        if matched >= lang.min_markers and (best is None or matched > best[0]):
            best = (matched, lang, sorted(set(evidence)))
    return (best[1], best[2]) if best else None


def report(source: SourceFile, dialect: str, title: str, found: tuple[Language, list[int]],
           errors: int) -> Diagnostics:
    """The one diagnostic that replaces the cascade."""
    lang, evidence = found
    diags = Diagnostics()
    shown = ", ".join(str(n) for n in evidence[:6])
    diags.add("G020", source.line_span(evidence[0]),
              f"this file looks like {lang.name}, not {title}: read as {dialect} it has {errors} errors "
              f"(lines {shown} show it); {lang.advice}",
              notes=tuple(f"{source.path}:{n}: {source.line_text(n).strip()}" for n in evidence[:6]))
    return diags
