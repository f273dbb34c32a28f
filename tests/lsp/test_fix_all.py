""""Fix all" (`source.fixAll.mcc`): the document after its edits is what `mcc lint --fix` writes for
the same file (the safe fixes only, line ends kept), asked for by kind as an editor does on save,
and from the light bulb through codeAction/resolve."""

from __future__ import annotations

import pytest
from lsprotocol import types as t

from lsp_client import DIALECT_FILES, Doc, client, fixture_text  # noqa: F401 (client is the fixture)
from mcc.compiler.config import Resolver
from mcc.compiler.lint import engine
from test_formatting_equals_fmt import apply

pytestmark = pytest.mark.asyncio(loop_scope="module")

FIX_ALL = "source.fixAll.mcc"


def mcc_lint_fix(path, text: str, settings_path) -> str:
    """What `mcc lint --fix` writes (engine.lint_file with the command's default options)."""
    path.write_bytes(text.encode("utf-8"))
    options = engine.Options(fix=True, verify=True, verify_required=False)
    engine.lint_file(str(path), Resolver().for_path(str(settings_path)), options)
    return path.read_bytes().decode("utf-8")


async def actions(client, doc: Doc, only=None) -> list:
    return await client.text_document_code_action_async(t.CodeActionParams(
        text_document=doc.id(), range=t.Range(t.Position(0, 0), t.Position(0, 0)),
        context=t.CodeActionContext(diagnostics=[], only=only)))


@pytest.mark.parametrize("newline", ["\n", "\r\n"], ids=["lf", "crlf"])
@pytest.mark.parametrize("dialect", ["mcode", "arcus", "x150"])
async def test_fix_all_on_save_equals_mcc_lint_fix(client, dialect, newline, tmp_path):
    text = fixture_text(dialect).replace("\n", newline)
    doc = Doc(client, DIALECT_FILES[dialect], text)
    await doc.settled()
    [action] = await actions(client, doc, only=[FIX_ALL])  # what VS Code asks on save
    assert action.kind == FIX_ALL and action.edit is not None
    fixed = apply(text, action.edit.changes[doc.uri])
    expected = mcc_lint_fix(tmp_path / DIALECT_FILES[dialect], text, doc.path)
    assert fixed != text and fixed == expected
    # only the safe fixes: the unsafe ones' diagnostics remain
    assert [a.kind for a in await actions(client, doc, only=[t.CodeActionKind.SourceFixAll])] == [FIX_ALL]


async def test_fix_all_from_the_light_bulb_is_resolved_when_chosen(client):
    doc = Doc(client, "cell.x150", fixture_text("x150"))
    await doc.settled()
    found = [a for a in await actions(client, doc) if isinstance(a, t.CodeAction) and a.kind == FIX_ALL]
    [action] = found
    assert action.edit is None and action.data == {"uri": doc.uri}  # computed only when chosen
    resolved = await client.code_action_resolve_async(action)
    assert apply(doc.text, resolved.edit.changes[doc.uri]) != doc.text


async def test_no_fix_all_without_safe_fixes(client):
    doc = Doc(client, "clean.prg", "HSPD=1000\nLSPD=100\nACC=100\nEO=1\nX1000\nWAITX\nEND\n")
    await doc.settled()
    assert not await actions(client, doc, only=[FIX_ALL])
    quick = await actions(client, doc, only=[t.CodeActionKind.QuickFix])
    assert all(a.kind != FIX_ALL for a in quick)
