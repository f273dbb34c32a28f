"""Navigation over every occurrence of a variable, and program memory that stays while the file has
an error (issue 25's gaps), through the protocol."""

from __future__ import annotations

import pytest
from lsprotocol import types as t

from lsp_client import Doc, client  # noqa: F401 (client is the fixture)

pytestmark = pytest.mark.asyncio(loop_scope="module")

ARCUS = "HSPD=1000\nLSPD=100\nACC=100\nEO=1\nV21=1200\nXV21\nX100YV21\nV1=V21+1\nEND\n"


def texts(doc: Doc, locations) -> list[tuple[int, str]]:
    lines = doc.text.split("\n")
    return [(loc.range.start.line, lines[loc.range.start.line][loc.range.start.character:loc.range.end.character])
            for loc in locations]


async def test_an_arcus_variable_as_a_move_target(client):
    """arcus-pmx-4ex-sa.txt L2759 `XV10`: move X to the value of V10. Definition, references and
    rename reach the variable inside the move."""
    doc = Doc(client, "target.prg", ARCUS)
    await doc.settled()
    at = doc.find("XV21", offset=2)
    [definition] = await client.text_document_definition_async(t.DefinitionParams(doc.id(), at))
    assert texts(doc, [definition]) == [(4, "V21")]
    found = await client.text_document_references_async(t.ReferenceParams(
        text_document=doc.id(), position=at, context=t.ReferenceContext(include_declaration=True)))
    assert texts(doc, found) == [(4, "V21"), (5, "V21"), (6, "V21"), (7, "V21")]
    edit = await client.text_document_rename_async(t.RenameParams(text_document=doc.id(), position=at, new_name="V30"))
    changed = sorted((e.range.start.line, e.range.start.character, e.new_text) for e in edit.changes[doc.uri])
    assert changed == [(4, 0, "V30"), (5, 1, "V30"), (6, 5, "V30"), (7, 3, "V30")]
    hover = await client.text_document_hover_async(t.HoverParams(doc.id(), at))
    assert "- written 1 time, read 3 times" in hover.contents.value


async def test_an_x150_assignment_target(client):
    """parker-x150.md L4565: `VARn=<expr>` assigns; the whole name `VAR1` of the target is the
    variable (definition, references and rename)."""
    doc = Doc(client, "assign.x150", "VAR1=5\n1D(VAR1)\nVAR2=VAR1+1\n")
    await doc.settled()
    on_name = t.Position(0, 1)  # on the `A` of VAR1=5
    [definition] = await client.text_document_definition_async(t.DefinitionParams(doc.id(), on_name))
    assert texts(doc, [definition]) == [(0, "VAR1")]
    found = await client.text_document_references_async(t.ReferenceParams(
        text_document=doc.id(), position=doc.find("VAR1+1"), context=t.ReferenceContext(include_declaration=True)))
    assert [line for line, _ in texts(doc, found)] == [0, 1, 2]
    edit = await client.text_document_rename_async(t.RenameParams(text_document=doc.id(), position=on_name, new_name="VAR9"))
    lines = doc.text.split("\n")
    for e in sorted(edit.changes[doc.uri], key=lambda e: (e.range.start.line, e.range.start.character), reverse=True):
        line = lines[e.range.start.line]
        lines[e.range.start.line] = line[:e.range.start.character] + e.new_text + line[e.range.end.character:]
    assert lines[:3] == ["VAR9=5", "1D(VAR9)", "VAR2=VAR9+1"]


async def test_lenses_and_hints_stay_while_the_file_has_an_error(client):
    """A program with an error cannot be priced; the lenses and hints keep the last figures."""
    doc = Doc(client, "priced.prg", ARCUS + "SUB 1\nDO1=1\nENDSUB\n")
    await doc.settled()
    before = await client.text_document_code_lens_async(t.CodeLensParams(doc.id()))
    assert [lens.command.title.split(":")[0] for lens in before][1:] == ["main program", "SUB 1"]
    doc.edit(1, 0, 8, "LSPD=(")  # a syntax error
    diagnostics = await doc.settled()
    assert any(d.severity == t.DiagnosticSeverity.Error for d in diagnostics)
    during = await client.text_document_code_lens_async(t.CodeLensParams(doc.id()))
    assert [lens.command.title for lens in during] == [lens.command.title for lens in before]
    hints = await client.text_document_inlay_hint_async(t.InlayHintParams(
        doc.id(), t.Range(t.Position(0, 0), t.Position(20, 0))))
    assert len(hints) == 2
