"""After every edit of a series, and after a burst of keystrokes sent without waiting, the
diagnostics the server publishes are those `mcc check` + `mcc lint` report for the same text:
the same codes, ranges, severities and messages. The server parses incrementally, abandons stale
analyses at checkpoints and reuses cached answers (lsp/incremental.py, lsp/documents.py); none of
that may change what the user is told. Each series runs in every dialect on a sample program."""

from __future__ import annotations

import random

import pytest
from lsprotocol import types as t

from conftest import sample_files
from lsp_client import Doc, client  # noqa: F401 (client is the fixture)
from mcc.compiler.config import Resolver
from mcc.compiler.lint import engine

pytestmark = pytest.mark.asyncio(loop_scope="module")

SEVERITY = {"error": t.DiagnosticSeverity.Error, "warning": t.DiagnosticSeverity.Warning,
            "info": t.DiagnosticSeverity.Information}
TYPED = {"mcode": ["1", "0", "\n", " MA 100", "ZZ", " H", "'"], "arcus": ["1", "0", "\n", "X100", "ZZ", "WAITX", ";"],
         "x150": ["1", "0", "\n", "1D100", "ZZ", "1G", ";"]}
EXTENSION = {"mcode": ".mxt", "arcus": ".prg", "x150": ".x150"}


def expected(doc: Doc) -> list[tuple]:
    """What `mcc lint` (which includes `mcc check`) reports for the document's text."""
    _, found = engine.lint_text(str(doc.path), doc.text, Resolver().for_path(str(doc.path)))
    out = []
    for d in found:
        if d.span.file != str(doc.path):
            continue
        span = d.span
        out.append((d.code, (max(span.line - 1, 0), max(span.column - 1, 0), max(span.end_line - 1, 0),
                             max(span.end_column - 1, 0)), SEVERITY[d.severity.value], d.message))
    return sorted(out)


def published(diagnostics: list[t.Diagnostic]) -> list[tuple]:
    out = []
    for d in diagnostics:
        r = d.range
        # the server appends the notes and the fix's description to the message: compare the message itself
        message = d.message.split("\nnote: ")[0].split("\nfix: ")[0]
        out.append((d.code, (r.start.line, r.start.character, r.end.line, r.end.character), d.severity, message))
    return sorted(out)


def random_edit(doc: Doc, rng: random.Random, dialect: str) -> tuple[int, int, int, str]:
    """A position in the text and what is typed there (or a few characters deleted)."""
    lines = doc.text.split("\n")
    line = rng.randrange(len(lines))
    start = rng.randint(0, len(lines[line]))
    if rng.random() < 0.25 and start < len(lines[line]):
        return line, start, min(len(lines[line]), start + rng.randint(1, 3)), ""
    return line, start, start, rng.choice(TYPED[dialect])


@pytest.mark.parametrize("dialect", ["mcode", "arcus", "x150"])
async def test_after_each_edit_the_diagnostics_are_mcc_lints(client, dialect):
    rng = random.Random(f"equal-{dialect}")
    sample = sample_files(dialect)[0]
    doc = Doc(client, f"equal{EXTENSION[dialect]}", sample.read_text(encoding="utf-8"), dialect)
    assert published(await doc.settled()) == expected(doc)
    for _ in range(12):
        doc.edit(*random_edit(doc, rng, dialect))
        assert published(await doc.settled()) == expected(doc), f"after version {doc.version}:\n{doc.text}"


@pytest.mark.parametrize("dialect", ["mcode", "arcus", "x150"])
async def test_after_a_burst_of_typing_the_diagnostics_are_mcc_lints(client, dialect):
    """Keystrokes sent one after the other without waiting: the analyses of the earlier ones are
    abandoned; what is published for the last is what `mcc lint` says of the final text."""
    rng = random.Random(f"burst-{dialect}")
    sample = sample_files(dialect)[-1]
    doc = Doc(client, f"burst{EXTENSION[dialect]}", sample.read_text(encoding="utf-8"), dialect)
    await doc.settled()
    for _ in range(3):
        for _ in range(6):
            doc.edit(*random_edit(doc, rng, dialect))
        assert published(await doc.settled()) == expected(doc), f"after version {doc.version}:\n{doc.text}"
