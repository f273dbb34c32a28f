"""The server never dies: a failing request is answered with an error and the next one works;
random edits and requests at random places (as the CLI is fuzzed) never stop it."""

from __future__ import annotations

import random

import pytest
from lsprotocol import types as t

from lsp_client import DIALECT_FILES, Doc, client, field, fixture_text  # noqa: F401 (client is the fixture)

pytestmark = pytest.mark.asyncio(loop_scope="module")

PIECES = {
    "mcode": ["MA", "MR", "PG", "LB", "BR", "CL", "RT", "E", "VA", "PR", "=", ",", "\"", "'", "-", "!", "1", "100",
              "K1", "G1", " ", "\n", "<>", "=<", "I1", "H", "\t", "µ", "😀"],
    "arcus": ["IF", "ELSE", "ENDIF", "WHILE", "ENDWHILE", "SUB", "ENDSUB", "GOSUB", "END", "X", "V1", "=", "+",
              ";", "HSPDX", "JOGX+", "DO7", "1000", ":", " ", "\n", "!=", "~", "😀"],
    "x150": ["XD1", "XT", "XE1", "1A10", "V5", "D-100", "G", "L5", "N", "IF(", ")", "VAR1", "=", " ", "\n", ";",
             "\"", "1OUT3B", "TRE_X1", "NIF", "XR2", "AND", "😀"],
}


async def test_a_failing_request_is_an_error_and_the_server_goes_on(client):
    doc = Doc(client, DIALECT_FILES["mcode"], fixture_text("mcode"))
    await doc.settled()
    with pytest.raises(Exception, match="unknown diagnostic code"):
        await client.workspace_execute_command_async(t.ExecuteCommandParams(command="mcc.explain",
                                                                            arguments=["Q999"]))
    # a request for a document the server never saw, and positions far outside the text
    unknown = t.TextDocumentIdentifier(uri="file:///nowhere/never.mxt")
    assert await client.text_document_hover_async(t.HoverParams(unknown, t.Position(0, 0))) is None
    far = t.Position(10_000, 10_000)
    await client.text_document_hover_async(t.HoverParams(doc.id(), far))
    await client.text_document_definition_async(t.DefinitionParams(doc.id(), far))
    # the server still answers
    hover = await client.text_document_hover_async(t.HoverParams(doc.id(), doc.find("MR 51200")))
    assert "**MR**" in hover.contents.value


REQUESTS = ["hover", "completion", "definition", "references", "highlight", "rename", "signature", "symbols",
            "folding", "semantic", "actions", "formatting", "lens"]


async def request(client, kind: str, doc: Doc, position: t.Position, rng: random.Random):
    ident = doc.id()
    if kind == "hover":
        return await client.text_document_hover_async(t.HoverParams(ident, position))
    if kind == "completion":
        return await client.text_document_completion_async(t.CompletionParams(ident, position))
    if kind == "definition":
        return await client.text_document_definition_async(t.DefinitionParams(ident, position))
    if kind == "references":
        return await client.text_document_references_async(t.ReferenceParams(
            text_document=ident, position=position, context=t.ReferenceContext(include_declaration=True)))
    if kind == "highlight":
        return await client.text_document_document_highlight_async(t.DocumentHighlightParams(ident, position))
    if kind == "rename":
        return await client.text_document_rename_async(t.RenameParams(ident, position,
                                                                      rng.choice(["G9", "7", "V3", "", "MA"])))
    if kind == "signature":
        return await client.text_document_signature_help_async(t.SignatureHelpParams(ident, position))
    if kind == "symbols":
        return await client.text_document_document_symbol_async(t.DocumentSymbolParams(ident))
    if kind == "folding":
        return await client.text_document_folding_range_async(t.FoldingRangeParams(ident))
    if kind == "semantic":
        return await client.text_document_semantic_tokens_full_async(t.SemanticTokensParams(ident))
    if kind == "actions":
        return await client.text_document_code_action_async(t.CodeActionParams(
            ident, t.Range(position, position), t.CodeActionContext(diagnostics=[])))
    if kind == "formatting":
        return await client.text_document_formatting_async(t.DocumentFormattingParams(
            ident, t.FormattingOptions(tab_size=4, insert_spaces=True)))
    return await client.text_document_code_lens_async(t.CodeLensParams(ident))


@pytest.mark.parametrize("dialect", ["mcode", "arcus", "x150"])
async def test_fuzz_random_edits_and_requests(client, dialect):
    rng = random.Random(f"mcc-lsp-{dialect}")
    doc = Doc(client, DIALECT_FILES[dialect], fixture_text(dialect))
    await doc.settled()
    failures = 0
    for _ in range(60):
        lines = doc.text.split("\n")
        line = rng.randrange(len(lines))
        start = rng.randrange(len(lines[line]) + 1)
        end = min(len(lines[line]), start + rng.randrange(4))
        doc.edit(line, start, end, "".join(rng.choice(PIECES[dialect]) for _ in range(rng.randrange(3))))
        position = t.Position(rng.randrange(len(doc.text.split("\n")) + 2), rng.randrange(40))
        try:
            await request(client, rng.choice(REQUESTS), doc, position, rng)
        except Exception as exc:  # an error answer is allowed (a refused rename); a dead server is not
            failures += 1
            assert "RuntimeError" not in type(exc).__name__ or "exited" not in str(exc)
    await doc.settled()
    status = await client.protocol.send_request_async("mcc/status", {"uri": doc.uri})
    assert field(status, "version") == doc.version
    assert failures < 60
