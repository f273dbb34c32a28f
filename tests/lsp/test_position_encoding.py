"""Positions in the client's encoding: columns after non-ASCII text are converted both ways.

LSP counts columns in the units of the negotiated position encoding (UTF-16 unless the client
offers another; Neovim 0.11 offers UTF-8 first), mcc in characters. Each request that takes or
returns a position is checked here on a line with `é`, `°` (two UTF-8 bytes, one UTF-16 unit) and
`😀` (four bytes, two UTF-16 units) before the symbol. Without the conversion a rename of `Np` in
`PR "Température °C: ",Np` wrote `NqNp` into the user's file.
"""

from __future__ import annotations

import sys

import pytest
import pytest_lsp
from lsprotocol import types as t
from pytest_lsp import ClientServerConfig, LanguageClient, client_capabilities

from lsp_client import FIXTURES, Doc

pytestmark = pytest.mark.asyncio(loop_scope="module")

TEXT = 'VA Np=0\nPG 100\n  Np=Np+1\n  PR "Température °C: ",Np\n  PR "😀 x",Np\nE\nPG\n'
SERVER = ClientServerConfig(server_command=[sys.executable, "-m", "mcc", "lsp"])


def units(encoding: str, text: str) -> int:
    """The length of `text` in the encoding's units."""
    if encoding == "utf-8":
        return len(text.encode("utf-8"))
    if encoding == "utf-16":
        return len(text.encode("utf-16-le")) // 2
    return len(text)


def position(encoding: str, text: str, needle: str, nth: int = 0) -> t.Position:
    at = -1
    for _ in range(nth + 1):
        at = text.index(needle, at + 1)
    line = text.count("\n", 0, at)
    start = text.rfind("\n", 0, at) + 1
    return t.Position(line, units(encoding, text[start:at]))


def apply(encoding: str, text: str, edits: list[t.TextEdit]) -> str:
    """Apply edits whose columns are in the encoding's units, as an editor does."""
    lines = text.split("\n")

    def offset(pos: t.Position) -> int:
        line = lines[pos.line]
        raw = line.encode("utf-8" if encoding == "utf-8" else "utf-16-le" if encoding == "utf-16" else "utf-32-le")
        width = 1 if encoding == "utf-8" else 2 if encoding == "utf-16" else 4
        chars = len(raw[:pos.character * width].decode(raw and encoding.replace("utf-16", "utf-16-le")
                                                         .replace("utf-32", "utf-32-le")))
        return sum(len(x) + 1 for x in lines[:pos.line]) + chars

    for edit in sorted(edits, key=lambda e: (e.range.start.line, e.range.start.character), reverse=True):
        text = text[:offset(edit.range.start)] + edit.new_text + text[offset(edit.range.end):]
        lines = text.split("\n")
    return text


def capabilities(encoding: str | None) -> t.ClientCapabilities:
    caps = client_capabilities("neovim")
    caps.general = t.GeneralClientCapabilities(position_encodings=[encoding] if encoding else None)
    return caps


async def start(lsp_client: LanguageClient, encoding: str | None) -> str:
    result = await lsp_client.initialize_session(t.InitializeParams(
        capabilities=capabilities(encoding), root_uri=FIXTURES.as_uri(), initialization_options={"debounce": 20}))
    return str(result.capabilities.position_encoding or "utf-16")


@pytest_lsp.fixture(config=SERVER, scope="module")
async def utf8(lsp_client: LanguageClient):
    lsp_client.encoding = await start(lsp_client, "utf-8")
    yield
    await lsp_client.shutdown_session()


@pytest_lsp.fixture(config=SERVER, scope="module")
async def utf16(lsp_client: LanguageClient):
    lsp_client.encoding = await start(lsp_client, None)  # no offer: UTF-16, as VS Code
    yield
    await lsp_client.shutdown_session()


async def check_every_request(client: LanguageClient) -> None:
    enc = client.encoding
    doc = Doc(client, "enc.mxt", TEXT)
    diagnostics = await doc.settled()
    where = position(enc, TEXT, "Np", 3)  # `,Np` after the degree sign

    # rename: the edits land on the symbol's characters, the file stays intact
    edit = await client.text_document_rename_async(t.RenameParams(doc.id(), where, "Nq"))
    assert apply(enc, TEXT, edit.changes[doc.uri]) == TEXT.replace("Np", "Nq")
    prepared = await client.text_document_prepare_rename_async(t.PrepareRenameParams(doc.id(), where))
    assert prepared.range.start == where and prepared.range.end.character == where.character + 2

    # the emoji line: two UTF-16 units, four UTF-8 bytes before it
    emoji = position(enc, TEXT, "Np", 4)
    refs = await client.text_document_references_async(t.ReferenceParams(
        text_document=doc.id(), position=emoji, context=t.ReferenceContext(include_declaration=True)))
    assert sorted((r.range.start.line, r.range.start.character) for r in refs) == sorted(
        (p.line, p.character) for p in (position(enc, TEXT, "Np", n) for n in range(5)))

    hover = await client.text_document_hover_async(t.HoverParams(doc.id(), where))
    assert hover is not None and hover.range.start == where
    definition = await client.text_document_definition_async(t.DefinitionParams(doc.id(), emoji))
    assert [(d.range.start.line, d.range.start.character) for d in definition] == [(0, 3)]
    highlights = await client.text_document_document_highlight_async(t.DocumentHighlightParams(doc.id(), where))
    assert where in [h.range.start for h in highlights]

    # semantic tokens: the variable after the degree sign starts at its column in the client's units
    tokens = await client.text_document_semantic_tokens_full_async(t.SemanticTokensParams(doc.id()))
    line = col = 0
    starts = []
    for n in range(0, len(tokens.data), 5):
        dl, dc, length = tokens.data[n:n + 3]
        line, col = line + dl, (col + dc if dl == 0 else dc)
        starts.append((line, col, length))
    assert (where.line, where.character, 2) in starts
    assert (emoji.line, emoji.character, 2) in starts

    # diagnostics: M309 on the last line is unaffected; every range lies within its line
    lines = TEXT.split("\n")
    for diag in diagnostics:
        assert diag.range.end.character <= units(enc, lines[diag.range.end.line])


async def test_utf8_clients_get_byte_columns(utf8):
    assert utf8.encoding == "utf-8"
    await check_every_request(utf8)


async def test_utf16_clients_get_utf16_columns(utf16):
    assert utf16.encoding == "utf-16"
    await check_every_request(utf16)
