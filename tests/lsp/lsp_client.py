"""A real `mcc lsp` process driven through the protocol by pytest-lsp's client (import `client` into a test module to use it).

One server per test module (starting Python and the parsers costs about a second); each test
opens its own documents under a fresh URI. `settled` waits, through mcc's own `mcc/status`
request, until the server's latest finished analysis (lint rules included) is of the version the
test sent, so a test never races the debounced analysis.
"""

from __future__ import annotations

import asyncio
import sys
from pathlib import Path

import pytest

pytest.importorskip("pytest_lsp", reason="the lsp tests need the test extra: pip install -e '.[test]'")

import pytest_lsp  # noqa: E402
from lsprotocol import types as t  # noqa: E402
from pytest_lsp import ClientServerConfig, LanguageClient, client_capabilities  # noqa: E402

FIXTURES = Path(__file__).resolve().parent / "fixtures"
DIALECT_FILES = {"mcode": "feeder.mxt", "arcus": "cell.prg", "x150": "cell.x150"}
SERVER = ClientServerConfig(server_command=[sys.executable, "-m", "mcc", "lsp"])


@pytest_lsp.fixture(config=SERVER, scope="module")
async def client(lsp_client: LanguageClient):
    lsp_client.refreshed = []  # the lens and hint refreshes the server asked for, in order
    lsp_client.registrations = []  # what the server registered dynamically (file watchers)

    @lsp_client.feature(t.CLIENT_REGISTER_CAPABILITY)
    def register_capability(params: t.RegistrationParams) -> None:
        lsp_client.registrations.extend(params.registrations)

    @lsp_client.feature(t.WORKSPACE_CODE_LENS_REFRESH)
    def code_lens_refresh(params) -> None:
        lsp_client.refreshed.append("codeLens")

    @lsp_client.feature(t.WORKSPACE_INLAY_HINT_REFRESH)
    def inlay_hint_refresh(params) -> None:
        lsp_client.refreshed.append("inlayHint")

    @lsp_client.feature(t.WORKSPACE_SEMANTIC_TOKENS_REFRESH)
    def semantic_tokens_refresh(params) -> None:
        lsp_client.refreshed.append("semanticTokens")

    await lsp_client.initialize_session(t.InitializeParams(
        capabilities=client_capabilities("visual-studio-code"),
        root_uri=FIXTURES.as_uri(),
        # the program memory and cycle time at once, not after a pause in the typing (memoryDelay,
        # 200 ms by default): `settled` waits for them, and the tests edit in steps, not keystrokes
        initialization_options={"debounce": 20, "memoryDelay": 0}))
    yield
    await lsp_client.shutdown_session()


class Doc:
    """One open document of the test: its URI, text and version, and helpers to edit it."""

    counter = 0

    def __init__(self, client: LanguageClient, name: str, text: str, language: str = ""):
        Doc.counter += 1
        self.client = client
        self.path = FIXTURES / f"t{Doc.counter}_{name}"
        self.uri = self.path.as_uri()
        self.text = text
        self.version = 1
        client.text_document_did_open(t.DidOpenTextDocumentParams(
            t.TextDocumentItem(uri=self.uri, language_id=language or "plaintext", version=1, text=text)))

    def id(self) -> t.TextDocumentIdentifier:
        return t.TextDocumentIdentifier(uri=self.uri)

    def edit(self, line: int, start: int, end: int, new: str) -> None:
        """Replace characters [start, end) of `line` (0-based) — one incremental change."""
        self.version += 1
        lines = self.text.split("\n")
        lines[line] = lines[line][:start] + new + lines[line][end:]
        self.text = "\n".join(lines)
        self.client.text_document_did_change(t.DidChangeTextDocumentParams(
            text_document=t.VersionedTextDocumentIdentifier(uri=self.uri, version=self.version),
            content_changes=[t.TextDocumentContentChangePartial(
                range=t.Range(t.Position(line, start), t.Position(line, end)), text=new)]))

    def find(self, needle: str, nth: int = 0, offset: int = 0) -> t.Position:
        """The position of the nth occurrence of `needle` (plus `offset` characters)."""
        at = -1
        for _ in range(nth + 1):
            at = self.text.index(needle, at + 1)
        line = self.text.count("\n", 0, at)
        column = at - (self.text.rfind("\n", 0, at) + 1)
        return t.Position(line, column + offset)

    async def settled(self, timeout: float = 60.0) -> list[t.Diagnostic]:
        loop = asyncio.get_running_loop()
        deadline = loop.time() + timeout
        while loop.time() < deadline:
            status = await self.client.protocol.send_request_async("mcc/status", {"uri": self.uri})
            if field(status, "version") == self.version and field(status, "complete"):
                await asyncio.sleep(0.05)  # the publish notification follows the status
                return list(self.client.diagnostics.get(self.uri, []))
            await asyncio.sleep(0.02)
        raise AssertionError(f"no finished analysis of {self.uri} version {self.version} in {timeout} s")


def field(obj, name: str):
    """A field of a result the client could not type (mcc's own request)."""
    return obj.get(name) if isinstance(obj, dict) else getattr(obj, name, None)


def fixture_text(dialect: str) -> str:
    return (FIXTURES / DIALECT_FILES[dialect]).read_text(encoding="utf-8")


async def open_fixture(client: LanguageClient, dialect: str) -> Doc:
    doc = Doc(client, DIALECT_FILES[dialect], fixture_text(dialect))
    await doc.settled()
    return doc


def apply_edits(text: str, edits: list) -> str:
    """The text edits applied as an editor applies them (LSP lines end at CRLF, CR or LF)."""
    from mcc.lsp.edits import LINE

    starts = [0]
    for line in LINE.findall(text):
        starts.append(starts[-1] + len(line))

    def offset(position) -> int:
        return min(starts[min(position.line, len(starts) - 1)] + position.character, len(text))

    for edit in sorted(edits, key=lambda e: (e.range.start.line, e.range.start.character), reverse=True):
        text = text[:offset(edit.range.start)] + edit.new_text + text[offset(edit.range.end):]
    return text
