"""Code lenses and inlay hints (program memory, cycle time) while the file has errors.

The decision (docs/EDITORS.md, lsp/analysis.py `figures_wanted`): while a document has errors,
its lenses keep the figures of its last version without any, moved onto the current lines, so
that they do not change while the user types; a document that has had no version without errors
since it was opened (a file opened with an error) gets figures computed from the lines that do
analyse — the lowering leaves a statement with an error out — and every such figure says which
lines it lacks ("without line 18 (error)"). The memory budget's own error (A201 and its kin) leaves
nothing out: such a program is priced whole, and its lenses are the ones the user needs most.
"""

from __future__ import annotations

import pytest
from lsprotocol import types as t

from lsp_client import Doc, client, fixture_text  # noqa: F401 (client is the fixture)
from mcc.lsp import analysis, lenses

ARCUS = fixture_text("arcus")  # cell.prg: main program, SUB 1 (DO1 pulse), SUB 2
X150 = fixture_text("x150")  # cell.x150: sequence 2 on device 1
MCODE = "PG 1\nLB G1\n  MR 51200\n  H\n  CL K1\n  BR G1\nLB K1\n  H 2400\n  RT\nPG\n"


def titles(snap) -> list[tuple[int, str]]:
    return [(lens.range.start.line + 1, lens.command.title) for lens in lenses.code_lenses(snap)]


def hints(snap) -> list[tuple[int, str]]:
    return [(hint.position.line + 1, hint.label.strip()) for hint in lenses.inlay_hints(snap, 0, 1000)]


def opened(name: str, text: str, dialect: str):
    return analysis.analyze(f"file:///tmp/{name}", f"/tmp/{name}", 1, text, dialect=dialect)


def test_an_arcus_file_opened_with_an_error_is_priced_without_the_line():
    """SUB 1 gets an unknown word on line 18 (A101/A122): the main program and SUB 2 are priced as
    always, SUB 1 and the whole program say they lack line 18."""
    clean = opened("clean.prg", ARCUS, "arcus")
    broken = opened("broken.prg", ARCUS.replace("DO1=1\n", "DO1=1\nZZ 5\n", 1), "arcus")
    assert broken.error_lines == (18,)
    before, after = dict(titles(clean)), dict(titles(broken))
    assert after[1] == before[1] + ", without line 18 (error)"  # the whole program
    assert after[2] == before[2]  # the main program: untouched
    assert after[16] == before[16] + ", without line 18 (error)"  # SUB 1
    assert after[22] == before[21]  # SUB 2, one line lower
    main, sub1, sub2 = hints(clean)
    assert hints(broken) == [main, (16, sub1[1] + ", without line 18 (error)"), (22, sub2[1])]


def test_an_x150_file_opened_with_a_syntax_error_is_priced_without_the_line():
    broken = opened("broken.x150", X150.replace("1T0.2\n", "1T0.2\n1D(\n", 1), "x150")
    assert broken.error_lines == (13,)
    found = titles(broken)
    assert found[0][1].startswith("sequence memory: ") and found[0][1].endswith(", without line 13 (error)")
    assert (8, "sequence 2 (device 1): 50 bytes (0.6% of 8000), without line 13 (error)") in found
    assert hints(broken) == [(8, "50 bytes (0.6% of 8000), without line 13 (error)")]


def test_an_mcode_file_opened_with_an_error_is_timed_without_the_line():
    """The cycle of the main loop (MR 51200 at the default speed, then the 2.4 s wait of K1) is
    simulated without the broken line; the lenses say so."""
    clean = opened("clean.mxt", MCODE, "mcode")
    broken = opened("broken.mxt", MCODE.replace("  RT\n", "  ZZ 4\n  RT\n"), "mcode")
    assert broken.error_lines == (9,)
    assert titles(broken) == [(line, title + ", without line 9 (error)") for line, title in titles(clean)]
    assert titles(clean)  # the loop and the call have lenses


def test_a_program_over_its_memory_budget_is_priced_whole():
    """A201 (over the budget) is an error, but it leaves nothing out of the program: the lenses
    show the figures without any "without"."""
    text = "ABS\n" + "X100Y100\n" * 2000 + "END\n"
    snap = opened("big.prg", text, "arcus")
    assert any(d.code == "A201" for d in snap.diagnostics) and snap.error_lines == ()
    found = titles(snap)
    assert found and found[0][1].startswith("program memory: ") and "without" not in found[0][1]
    assert "% of 3230" in found[0][1]


@pytest.mark.asyncio(loop_scope="module")
async def test_through_the_editor_an_opened_error_then_fixed_then_typed_again(client):
    """Opened with an error: lenses from the lines that analyse (asked again after the pause, a
    code lens refresh). Fixed: the exact figures. Broken again while typing: the figures of the
    version without errors stay, unchanged, on their lines."""
    broken_text = ARCUS.replace("DO1=1\n", "DO1=1\nZZ 5\n", 1)
    client.refreshed.clear()
    doc = Doc(client, "lenses.prg", broken_text, "arcus")
    await doc.settled()
    assert "codeLens" in client.refreshed
    found = await client.text_document_code_lens_async(t.CodeLensParams(doc.id()))
    memory = {lens.range.start.line + 1: lens.command.title for lens in found}
    assert memory[16].startswith("SUB 1: ") and memory[16].endswith(", without line 18 (error)")
    assert memory[2].startswith("main program: ") and "without" not in memory[2]
    hints = await client.text_document_inlay_hint_async(t.InlayHintParams(
        doc.id(), t.Range(t.Position(0, 0), t.Position(100, 0))))
    assert len(hints) == 3 and hints[1].label.endswith(", without line 18 (error)")

    doc.edit(17, 0, 5, "")  # line 18 "ZZ 5" deleted: the file has no error
    await doc.settled()
    found = await client.text_document_code_lens_async(t.CodeLensParams(doc.id()))
    fixed = [(lens.range.start.line, lens.command.title) for lens in found]
    assert fixed and not any("without" in title for _, title in fixed)

    sub2 = doc.find("SUB 2").line
    doc.edit(sub2, 0, 0, "ZZ\n")  # an error typed above SUB 2: SUB 2 moves down one line
    diagnostics = await doc.settled()
    assert any(d.severity == t.DiagnosticSeverity.Error for d in diagnostics)
    found = await client.text_document_code_lens_async(t.CodeLensParams(doc.id()))
    kept = [(lens.range.start.line, lens.command.title) for lens in found]
    assert kept == [(line + 1 if line == sub2 else line, title) for line, title in fixed]
