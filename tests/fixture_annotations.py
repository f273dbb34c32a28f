"""The annotations of the lint rules' and the semantic checks' fixtures (tests/lint/fixtures,
tests/checks/fixtures): a comment on a line that must be reported holds `<severity>: <CODE>`, or
several codes separated by commas (`' error: M106`, `; warning: X127, X110`). One reader for both,
so a fixture of either kind is annotated the same way."""

from __future__ import annotations

import re

ANNOTATION = re.compile(r"\b(error|warning|info): ([A-Z]\d{3}(?:\s*,\s*[A-Z]\d{3})*)")
# the header comment of a fixture cites the manual lines its rule or check rests on
MANUAL_LINE = re.compile(r"\b(lexium-mcode\.txt|parker-x150\.md|arcus-pmx-4ex-sa\.txt) L\d+")


def expected(text: str, comment: str) -> set[tuple[int, str, str]]:
    """(line, severity, code) of every annotation: a comment holding `<severity>: <CODE>[, <CODE>]`."""
    found = set()
    for number, line in enumerate(text.splitlines(), start=1):
        at = line.find(comment)
        if at < 0:
            continue
        for severity, codes in ANNOTATION.findall(line[at:]):
            found |= {(number, severity, code.strip()) for code in codes.split(",")}
    return found
