"""Every editor feature of `mcc lsp`, in each dialect, through the protocol as an editor uses it."""

from __future__ import annotations

import asyncio

import pytest
from lsprotocol import types as t

from lsp_client import Doc, client, fixture_text, open_fixture  # noqa: F401 (client is the fixture)
from mcc.compiler.lint import formatting

pytestmark = pytest.mark.asyncio(loop_scope="module")

EXPECTED = {"mcode": {"M306", "M321", "M301", "M309"}, "arcus": {"A307", "A315"}, "x150": {"X102", "X120"}}


def codes(diagnostics) -> set[str]:
    return {d.code for d in diagnostics}


@pytest.mark.parametrize("dialect", ["mcode", "arcus", "x150"])
async def test_diagnostics_are_mcc_lints_with_rule_links(client, dialect):
    doc = await open_fixture(client, dialect)
    diagnostics = await doc.settled()
    assert codes(diagnostics) == EXPECTED[dialect]
    for diag in diagnostics:
        assert diag.source == "mcc"
        assert diag.code_description is not None and diag.code_description.href.endswith(f"/{diag.code}.md")


async def test_related_information_points_at_the_move_still_running(client):
    doc = await open_fixture(client, "mcode")
    m301 = next(d for d in await doc.settled() if d.code == "M301")
    assert m301.range.start.line == 10  # PR P
    [related] = m301.related_information
    assert related.location.range.start.line == 9 and "MA Pp" in related.message


@pytest.mark.parametrize("dialect", ["mcode", "arcus", "x150"])
async def test_incremental_edit_gives_fresh_diagnostics(client, dialect):
    doc = await open_fixture(client, dialect)
    if dialect == "mcode":
        at = doc.find("=<0")
        doc.edit(at.line, at.character, at.character + 2, "<=")
        gone = "M321"
    elif dialect == "arcus":
        at = doc.find(" ; park")
        doc.edit(at.line, at.character, at.character + len(" ; park"), "")
        gone = "A315"
    else:
        at = doc.find("1g")
        doc.edit(at.line, at.character, at.character + 2, "1G")
        gone = "X102"
    after = codes(await doc.settled())
    assert after == EXPECTED[dialect] - {gone}


async def test_project_configuration_and_per_file_ignores(client, tmp_path):
    (tmp_path / "mcc.toml").write_text('ignore = ["M306"]\n[per-file-ignores]\n"legacy_*" = ["M3"]\n')
    text = fixture_text("mcode")
    first = OpenAt(client, tmp_path / "feeder.mxt", text)
    second = OpenAt(client, tmp_path / "legacy_feeder.mxt", text)
    assert codes(await first.settled()) == EXPECTED["mcode"] - {"M306"}
    assert codes(await second.settled()) == set()


def OpenAt(client, path, text) -> Doc:
    """A document opened at a chosen path (so the configuration next to it applies)."""
    doc = Doc.__new__(Doc)
    doc.client, doc.path, doc.uri, doc.text, doc.version = client, path, path.as_uri(), text, 1
    client.text_document_did_open(t.DidOpenTextDocumentParams(
        t.TextDocumentItem(uri=doc.uri, language_id="mcode" if path.suffix == ".mxt" else "plaintext",
                           version=1, text=text)))
    return doc


async def test_target_profile_from_the_configuration_filters_completion_and_hover(client, tmp_path):
    (tmp_path / "mcc.toml").write_text('target = "lmd-o"\n')
    doc = OpenAt(client, tmp_path / "open_loop.mxt", "VM=1000\nVI=100\n")
    await doc.settled()
    items = await client.text_document_completion_async(t.CompletionParams(doc.id(), t.Position(1, 0)))
    labels = {i.label for i in items.items}
    assert "MA" in labels and "VM" in labels
    assert "TQ" not in labels  # closed-loop only (lmd-c)
    other = Doc(client, "closed_loop.mxt", "VM=1000\nVI=100\n")
    await other.settled()
    items = await client.text_document_completion_async(t.CompletionParams(other.id(), t.Position(1, 0)))
    assert "TQ" in {i.label for i in items.items}


HOVER_COMMANDS = {"mcode": ("MR 51200", "MR", "Move relative"), "arcus": ("HSPD=", "HSPD", "pps"),
                  "x150": ("1D12000", "D", "Distance")}


@pytest.mark.parametrize("dialect", ["mcode", "arcus", "x150"])
async def test_hover_on_a_command_shows_the_catalog_and_availability(client, dialect):
    doc = await open_fixture(client, dialect)
    needle, name, words = HOVER_COMMANDS[dialect]
    offset = needle.index(name)
    hover = await client.text_document_hover_async(t.HoverParams(doc.id(), doc.find(needle, offset=offset)))
    text = hover.contents.value
    assert f"**{name}**" in text and words in text
    assert "manual:" in text and "✓ available" in text


async def test_hover_says_when_the_target_lacks_a_command(client, tmp_path):
    default = Doc(client, "closed.mxt", "TQ=1\n")
    await default.settled()
    hover = await client.text_document_hover_async(t.HoverParams(default.id(), t.Position(0, 0)))
    assert "✓ available on lmd-c" in hover.contents.value  # the default profile has it
    (tmp_path / "mcc.toml").write_text('target = "lmd-o"\n')
    open_loop = OpenAt(client, tmp_path / "open.mxt", "TQ=1\n")
    await open_loop.settled()
    hover = await client.text_document_hover_async(t.HoverParams(open_loop.id(), t.Position(0, 0)))
    assert "✗ not available on lmd-o: only on lmd-c" in hover.contents.value


SYMBOLS = {"mcode": ("BR G1", 3, "G1", 8, 2), "arcus": ("GOSUB 1", 6, "SUB 1", 16, 1),
           "x150": ("1XR2", 3, "sequence 2", 8, 2)}


@pytest.mark.parametrize("dialect", ["mcode", "arcus", "x150"])
async def test_hover_on_a_name_shows_its_definition_and_uses(client, dialect):
    doc = await open_fixture(client, dialect)
    needle, offset, label, line, uses = SYMBOLS[dialect]
    hover = await client.text_document_hover_async(t.HoverParams(doc.id(), doc.find(needle, offset=offset)))
    text = hover.contents.value
    assert f"**{label}**" in text and f"line {line}" in text and f"used {uses} time" in text


@pytest.mark.parametrize("dialect,needle,expected", [
    ("mcode", "MR 51200", "= 1 rev"),          # 51200 steps at MS=256, lmd-c
    ("mcode", "VM=400000", "468.75 rpm"),      # 400000 steps/s = 7.8125 rev/s
    ("x150", "1D12000", "= 3 rev"),            # CUR 4000 user steps per rev
])
async def test_hover_on_a_motion_value_shows_physical_units(client, dialect, needle, expected):
    doc = await open_fixture(client, dialect)
    position = doc.find(needle, offset=len(needle) - 1)
    hover = await client.text_document_hover_async(t.HoverParams(doc.id(), position))
    assert expected in hover.contents.value


async def test_completion_of_labels_subroutines_and_sequences(client):
    mcode = await open_fixture(client, "mcode")
    mcode.edit(13, 0, 7, "  BR ")
    await mcode.settled()
    items = await client.text_document_completion_async(t.CompletionParams(mcode.id(), t.Position(13, 5)))
    assert {i.label for i in items.items} == {"G1", "K1"}
    arcus = await open_fixture(client, "arcus")
    at = arcus.find("GOSUB 1")
    arcus.edit(at.line, 0, 7, "GOSUB ")
    await arcus.settled()
    items = await client.text_document_completion_async(t.CompletionParams(arcus.id(), t.Position(at.line, 6)))
    assert {i.label for i in items.items} == {"1", "2"}
    x150 = await open_fixture(client, "x150")
    at = x150.find("1XR2")
    x150.edit(at.line, 0, 4, "1XR")
    await x150.settled()
    items = await client.text_document_completion_async(t.CompletionParams(x150.id(), t.Position(at.line, 3)))
    assert {i.label for i in items.items} == {"2"}


@pytest.mark.parametrize("dialect,name,snippet", [
    ("mcode", "MA", "MA ${1:±position}"), ("arcus", "GOSUB", "GOSUB ${1:n}"), ("x150", "D", "D${1:±n}")])
async def test_completion_of_commands_with_snippets(client, dialect, name, snippet):
    doc = await open_fixture(client, dialect)
    line = doc.text.count("\n")  # the empty last line
    items = await client.text_document_completion_async(t.CompletionParams(doc.id(), t.Position(line, 0)))
    found = {i.label: i for i in items.items}
    assert found[name].insert_text == snippet
    assert found[name].insert_text_format == t.InsertTextFormat.Snippet


async def test_completion_respects_the_program_region(client):
    doc = await open_fixture(client, "mcode")
    inside = await client.text_document_completion_async(t.CompletionParams(doc.id(), t.Position(12, 0)))
    outside = await client.text_document_completion_async(t.CompletionParams(doc.id(), t.Position(3, 0)))
    inside_labels = {i.label for i in inside.items}
    outside_labels = {i.label for i in outside.items}
    assert "LB" in inside_labels and "LB" not in outside_labels  # LB is program-only


async def test_completion_of_variables_in_arguments(client):
    doc = await open_fixture(client, "mcode")
    items = await client.text_document_completion_async(t.CompletionParams(doc.id(), doc.find("MA Pp", offset=3)))
    labels = {i.label for i in items.items}
    assert {"Np", "Pp"} <= labels and "P" in labels


@pytest.mark.parametrize("dialect,line,character,label", [
    ("mcode", "  MA Pp", 5, "MA <±position>"), ("arcus", "GOSUB 1", 6, "GOSUB <n>")])
async def test_signature_help_while_arguments_are_typed(client, dialect, line, character, label):
    doc = await open_fixture(client, dialect)
    position = doc.find(line)
    help_ = await client.text_document_signature_help_async(t.SignatureHelpParams(
        doc.id(), t.Position(position.line, position.character + character)))
    assert help_.signatures[0].label == label
    assert help_.active_parameter == 0


NAVIGATION = {"mcode": ("CL K1", 3, 15, 2), "arcus": ("GOSUB 1", 6, 15, 2), "x150": ("1XR2", 3, 7, 3)}


@pytest.mark.parametrize("dialect", ["mcode", "arcus", "x150"])
async def test_definition_references_and_highlight(client, dialect):
    doc = await open_fixture(client, dialect)
    needle, offset, definition_line, count = NAVIGATION[dialect]
    position = doc.find(needle, offset=offset)
    [location] = await client.text_document_definition_async(t.DefinitionParams(doc.id(), position))
    assert location.range.start.line == definition_line
    refs = await client.text_document_references_async(t.ReferenceParams(
        text_document=doc.id(), position=position, context=t.ReferenceContext(include_declaration=True)))
    assert len(refs) == count
    highlights = await client.text_document_document_highlight_async(t.DocumentHighlightParams(doc.id(), position))
    assert len(highlights) == count
    assert [h.kind for h in highlights].count(t.DocumentHighlightKind.Write) == 1


RENAMES = {
    "mcode": ("BR G1", 3, "G5", "MA", "K1"),
    "arcus": ("GOSUB 1", 6, "5", "40", "2"),
    "x150": ("1XR2", 3, "7", "99", None),
}


@pytest.mark.parametrize("dialect", ["mcode", "arcus", "x150"])
async def test_rename_and_its_refusals(client, dialect):
    doc = await open_fixture(client, dialect)
    needle, offset, good, invalid, taken = RENAMES[dialect]
    position = doc.find(needle, offset=offset)
    prepared = await client.text_document_prepare_rename_async(t.PrepareRenameParams(doc.id(), position))
    assert prepared is not None
    edit = await client.text_document_rename_async(t.RenameParams(doc.id(), position, good))
    edits = edit.changes[doc.uri]
    assert len(edits) >= 2 and all(good in e.new_text for e in edits)
    with pytest.raises(Exception) as refused:
        await client.text_document_rename_async(t.RenameParams(doc.id(), position, invalid))
    assert "not a valid" in str(refused.value) or "range" in str(refused.value) or "MCode" in str(refused.value)
    if taken:
        with pytest.raises(Exception) as collided:
            await client.text_document_rename_async(t.RenameParams(doc.id(), position, taken))
        assert "already" in str(collided.value)


async def test_rename_variables_in_arcus_and_x150(client):
    arcus = await open_fixture(client, "arcus")
    edit = await client.text_document_rename_async(t.RenameParams(arcus.id(), arcus.find("V1=0"), "V7"))
    assert sorted(e.new_text for e in edit.changes[arcus.uri]) == ["V7"] * 3
    with pytest.raises(Exception, match="V0 to V63"):
        await client.text_document_rename_async(t.RenameParams(arcus.id(), arcus.find("V1=0"), "V64"))
    x150 = await open_fixture(client, "x150")
    edit = await client.text_document_rename_async(t.RenameParams(x150.id(), x150.find("VAR1", offset=3), "VAR9"))
    # the assignment target is the whole name `VAR1` too (it was its number alone, issue 25)
    assert sorted(e.new_text for e in edit.changes[x150.uri]) == ["VAR9", "VAR9"]


OUTLINES = {"mcode": ["PG 1"], "arcus": ["main program", "SUB 1", "SUB 2"], "x150": ["sequence 2 (device 1)"]}


@pytest.mark.parametrize("dialect", ["mcode", "arcus", "x150"])
async def test_document_symbols_folding_and_semantic_tokens(client, dialect):
    doc = await open_fixture(client, dialect)
    symbols = await client.text_document_document_symbol_async(t.DocumentSymbolParams(doc.id()))
    names = [s.name for s in symbols if s.kind != t.SymbolKind.Variable]
    assert names == OUTLINES[dialect]
    if dialect == "mcode":
        assert [c.name for c in symbols[-1].children] == ["G1", "K1"]
    folds = await client.text_document_folding_range_async(t.FoldingRangeParams(doc.id()))
    assert folds and all(f.end_line > f.start_line for f in folds)
    tokens = await client.text_document_semantic_tokens_full_async(t.SemanticTokensParams(doc.id()))
    assert len(tokens.data) % 5 == 0 and len(tokens.data) >= 5 * 20
    line = column = 0
    decoded = []
    for i in range(0, len(tokens.data), 5):
        dl, dc, length, kind, _ = tokens.data[i:i + 5]
        line, column = line + dl, (column + dc if dl == 0 else dc)
        decoded.append((line, column, length, kind))
    assert decoded == sorted(decoded)


async def test_workspace_symbols(client):
    await open_fixture(client, "arcus")
    found = await client.workspace_symbol_async(t.WorkspaceSymbolParams(query="SUB"))
    assert {"SUB 1", "SUB 2"} <= {s.name for s in found}


async def test_code_actions_fix_noqa_and_explain(client):
    doc = await open_fixture(client, "mcode")
    diagnostics = await doc.settled()
    m321 = next(d for d in diagnostics if d.code == "M321")
    actions = await client.text_document_code_action_async(t.CodeActionParams(
        doc.id(), m321.range, t.CodeActionContext(diagnostics=[m321])))
    titles = [a.title for a in actions]
    assert "write <= (M321)" in titles and "Silence M321 on this line (noqa)" in titles and "Explain M321" in titles
    fix = next(a for a in actions if a.title == "write <= (M321)")
    [edit] = fix.edit.changes[doc.uri]
    assert edit.new_text == "<="
    noqa = next(a for a in actions if a.title.startswith("Silence"))
    [edit] = noqa.edit.changes[doc.uri]
    assert edit.new_text == "  ' noqa: M321"
    explain = next(a for a in actions if a.title == "Explain M321")
    page = await client.workspace_execute_command_async(t.ExecuteCommandParams(
        command=explain.command, arguments=explain.arguments))
    assert page.startswith("# M321")


async def test_noqa_action_silences_the_finding(client):
    doc = await open_fixture(client, "arcus")
    [a307] = [d for d in await doc.settled() if d.code == "A307"]
    actions = await client.text_document_code_action_async(t.CodeActionParams(
        doc.id(), a307.range, t.CodeActionContext(diagnostics=[a307])))
    noqa = next(a for a in actions if a.title.startswith("Silence"))
    [edit] = noqa.edit.changes[doc.uri]
    doc.edit(edit.range.start.line, edit.range.start.character, edit.range.end.character, edit.new_text)
    assert "A307" not in codes(await doc.settled())


UNFORMATTED = {"mcode": "va np=0\npg 100\nlb g1\nma 100\nh\nbr g1\npg\n", "arcus": "abs\nx1000\nwaitx\nend\n",
               "x150": "1a10 1v5\n1d4000\n1g\n"}


@pytest.mark.parametrize("dialect", ["mcode", "arcus", "x150"])
async def test_formatting_matches_mcc_fmt(client, dialect):
    name = {"mcode": "f.mxt", "arcus": "f.prg", "x150": "f.x150"}[dialect]
    doc = Doc(client, name, UNFORMATTED[dialect])
    await doc.settled()
    edits = await client.text_document_formatting_async(t.DocumentFormattingParams(
        doc.id(), t.FormattingOptions(tab_size=4, insert_spaces=True)))
    assert edits
    result = apply(doc.text, edits)
    assert result == formatting.format_text(doc.text, str(doc.path), dialect)
    ranged = await client.text_document_range_formatting_async(t.DocumentRangeFormattingParams(
        doc.id(), t.Range(t.Position(0, 0), t.Position(0, 3)), t.FormattingOptions(tab_size=4, insert_spaces=True)))
    assert ranged and all(e.range.start.line == 0 for e in ranged)


def apply(text: str, edits: list[t.TextEdit]) -> str:
    lines = text.split("\n")
    starts = [0]
    for line in lines:
        starts.append(starts[-1] + len(line) + 1)

    def offset(p: t.Position) -> int:
        return starts[p.line] + p.character

    for edit in sorted(edits, key=lambda e: offset(e.range.start), reverse=True):
        text = text[:offset(edit.range.start)] + edit.new_text + text[offset(edit.range.end):]
    return text


@pytest.mark.parametrize("dialect,unit,routines", [
    ("arcus", "assembly lines", ["main program", "SUB 1", "SUB 2"]), ("x150", "bytes", ["sequence 2 (device 1)"])])
async def test_program_memory_as_code_lens_and_inlay_hints(client, dialect, unit, routines):
    client.refreshed.clear()
    doc = await open_fixture(client, dialect)
    # the program is priced after a pause in the typing; the editor is then asked to ask again for
    # lenses (VS Code's capabilities declare that it can be asked for lenses, not for inlay hints)
    assert client.refreshed == ["codeLens"]
    lenses = await client.text_document_code_lens_async(t.CodeLensParams(doc.id()))
    # the lenses are the memory figures and, since issue 27, the cycle time of the main loop and
    # of each called subroutine ("cycle ...", "call ...": tests/lsp/test_cycle_lens.py)
    titles = [lens.command.title for lens in lenses if not lens.command.title.startswith(("cycle ", "call "))]
    assert titles and all(unit in title and "% of" in title for title in titles)
    assert [title.split(":")[0] for title in titles[1:]] == routines
    hints = await client.text_document_inlay_hint_async(t.InlayHintParams(
        doc.id(), t.Range(t.Position(0, 0), t.Position(100, 0))))
    assert len(hints) == len(routines) and all(unit in h.label for h in hints)


async def test_signature_help_in_x150(client):
    doc = await open_fixture(client, "x150")
    position = doc.find("1D12000", offset=4)
    help_ = await client.text_document_signature_help_async(t.SignatureHelpParams(doc.id(), position))
    assert help_.signatures[0].label == "<a>D<s>n"


async def test_code_action_fix_in_x150(client):
    doc = await open_fixture(client, "x150")
    x102 = next(d for d in await doc.settled() if d.code == "X102")
    actions = await client.text_document_code_action_async(t.CodeActionParams(
        doc.id(), x102.range, t.CodeActionContext(diagnostics=[x102])))
    fix = next(a for a in actions if isinstance(a, t.CodeAction) and a.title.endswith("(X102)"))
    [edit] = fix.edit.changes[doc.uri]
    assert edit.new_text == "1G"
    doc.edit(edit.range.start.line, edit.range.start.character, edit.range.end.character, edit.new_text)
    assert "X102" not in codes(await doc.settled())


@pytest.mark.parametrize("dialect,query,expected", [("mcode", "K", {"K1"}), ("x150", "sequence", {"sequence 2 (device 1)"})])
async def test_workspace_symbols_in_mcode_and_x150(client, dialect, query, expected):
    await open_fixture(client, dialect)
    found = await client.workspace_symbol_async(t.WorkspaceSymbolParams(query=query))
    assert expected <= {s.name for s in found}


async def test_a_changed_configuration_is_read_again(client, tmp_path):
    config = tmp_path / "mcc.toml"
    config.write_text('ignore = ["M3"]\n')
    doc = OpenAt(client, tmp_path / "feeder.mxt", fixture_text("mcode"))
    assert codes(await doc.settled()) == set()
    config.write_text('ignore = ["M306"]\n')
    client.workspace_did_change_watched_files(t.DidChangeWatchedFilesParams(
        changes=[t.FileEvent(uri=config.as_uri(), type=t.FileChangeType.Changed)]))
    await doc.settled()
    for _ in range(100):
        if codes(client.diagnostics.get(doc.uri, [])) == EXPECTED["mcode"] - {"M306"}:
            break
        await asyncio.sleep(0.05)
    assert codes(client.diagnostics[doc.uri]) == EXPECTED["mcode"] - {"M306"}


async def test_x150_completion_offers_only_storable_commands_inside_a_sequence(client):
    doc = await open_fixture(client, "x150")
    inside = await client.text_document_completion_async(t.CompletionParams(doc.id(), doc.find("1T0.2")))
    outside = await client.text_document_completion_async(t.CompletionParams(doc.id(), doc.find("1A10")))
    inside_labels = {i.label for i in inside.items}
    outside_labels = {i.label for i in outside.items}
    assert "G" in inside_labels and "G" in outside_labels
    assert "CER" in outside_labels and "CER" not in inside_labels  # not saveable in a sequence


async def test_saving_the_configuration_in_the_editor_reanalyses(client, tmp_path):
    config = tmp_path / "mcc.toml"
    config.write_text('ignore = ["M3"]\n')
    doc = OpenAt(client, tmp_path / "feeder.mxt", fixture_text("mcode"))
    assert codes(await doc.settled()) == set()
    config.write_text('ignore = ["M301"]\n')
    client.text_document_did_save(t.DidSaveTextDocumentParams(text_document=t.TextDocumentIdentifier(config.as_uri())))
    for _ in range(200):
        if codes(client.diagnostics.get(doc.uri, [])) == EXPECTED["mcode"] - {"M301"}:
            break
        await asyncio.sleep(0.05)
    assert codes(client.diagnostics[doc.uri]) == EXPECTED["mcode"] - {"M301"}


async def test_colours_asked_for_before_the_first_analysis_are_refreshed(client):
    """An editor asks for semantic tokens as soon as it opens a file, before the first analysis of
    a long program has finished: the server answers empty, then asks the editor to ask again."""
    client.refreshed.clear()
    text = "".join(f"V{n % 60 + 1}={n}\n" for n in range(3000)) + "END\n"
    doc = Doc(client, "long.prg", text)  # analysing 3,000 lines takes far longer than one round trip
    early = await client.text_document_semantic_tokens_full_async(t.SemanticTokensParams(doc.id()))
    assert list(early.data) == []
    await doc.settled()
    for _ in range(100):
        if "semanticTokens" in client.refreshed:
            break
        await asyncio.sleep(0.02)
    assert "semanticTokens" in client.refreshed
    late = await client.text_document_semantic_tokens_full_async(t.SemanticTokensParams(doc.id()))
    assert len(late.data) >= 5 * 3000
