"""Formatting from the editor equals `mcc fmt` byte for byte: the document after the server's edits
is what `mcc fmt` writes for the same file (final newline and line ends included), over every
sample of the project and variants an editor holds (trailing blanks, no final newline, CRLF)."""

from __future__ import annotations

from pathlib import Path

import pytest
from lsprotocol import types as t

from lsp_client import Doc, apply_edits, client  # noqa: F401 (client is the fixture)
from mcc.compiler.config import Resolver
from mcc.compiler.lint import formatting

pytestmark = pytest.mark.asyncio(loop_scope="module")

SAMPLES = sorted((Path(__file__).resolve().parents[2] / "samples").glob("*/*"))


def variants(text: str) -> dict[str, str]:
    messy = "\n".join(line + "   " if line else line for line in text.split("\n"))
    return {
        "as is": text,
        "trailing blanks": messy,
        "no final newline": text.rstrip("\n"),
        "blank lines at the end": text + "\n\n\n",
        "crlf": messy.replace("\n", "\r\n"),
        "crlf, no final newline": text.rstrip("\n").replace("\n", "\r\n"),
    }


apply = apply_edits


def mcc_fmt(path: Path, text: str, settings_path: Path) -> str:
    """What `mcc fmt` writes (formatting.format_file, the command's own step) for a file holding `text`."""
    path.write_bytes(text.encode("utf-8"))
    outcome = formatting.format_file(str(path), Resolver().for_path(str(settings_path)))
    assert not outcome.error, outcome.error
    return path.read_bytes().decode("utf-8")


@pytest.mark.parametrize("sample", SAMPLES, ids=lambda p: f"{p.parent.name}/{p.name}")
async def test_editor_formatting_equals_mcc_fmt(client, sample, tmp_path):
    for name, text in variants(sample.read_text(encoding="utf-8")).items():
        doc = Doc(client, sample.name, text)
        await doc.settled()
        edits = await client.text_document_formatting_async(t.DocumentFormattingParams(
            doc.id(), t.FormattingOptions(tab_size=4, insert_spaces=True)))
        expected = mcc_fmt(tmp_path / sample.name, text, doc.path)
        assert apply(text, edits or []) == expected, f"{sample.name} ({name})"
