"""Completion items carry the range they replace, so that a device address or an axis letter in front
of the word being typed does not hide them (an editor filters items by the text of that range)."""

from __future__ import annotations

import pytest
from lsprotocol import types as t

from lsp_client import Doc, client  # noqa: F401 (client is the fixture)

pytestmark = pytest.mark.asyncio(loop_scope="module")


def applied(line: str, item: t.CompletionItem) -> str:
    """The line after the editor applied the item's text edit (snippet placeholders dropped)."""
    edit = item.text_edit
    new = edit.new_text.split("$", 1)[0]
    return line[:edit.range.start.character] + new + line[edit.range.end.character:]


async def items_at(client, doc: Doc, line: int, column: int) -> dict[str, t.CompletionItem]:
    answer = await client.text_document_completion_async(t.CompletionParams(doc.id(), t.Position(line, column)))
    return {item.label: item for item in answer.items}


@pytest.mark.parametrize("typed,label,result", [("1D", "D", "1D"), ("2G", "G", "2G"), ("12A", "A", "12A")])
async def test_x150_commands_after_a_device_address(client, typed, label, result):
    """parker-x150.md L179: a command is made device specific by its device address (`1D`); the item replaces
    only the command's letters."""
    doc = Doc(client, "addressed.x150", f"1CUR4000\n{typed}\n")
    await doc.settled()
    found = await items_at(client, doc, 1, len(typed))
    item = found[label]
    address = len(typed) - len(label)
    assert item.text_edit.range.start == t.Position(1, address)
    assert item.text_edit.range.end == t.Position(1, len(typed))
    # no filterText: filtered by the label (LSP's default); Neovim's omnifunc honours the range
    # only for items without one (tests/editors/test_neovim_completion.py)
    assert item.filter_text is None
    assert applied(typed, item) == result


async def test_arcus_variable_as_a_move_target(client):
    """arcus-pmx-4ex-sa.txt L2759: `XV10` moves X to the value of V10; after `XV2` the variables
    are offered, replacing `V2` (the axis letter stays)."""
    doc = Doc(client, "target.prg", "V21=1200\nV3=5\nXV2\nEND\n")
    await doc.settled()
    found = await items_at(client, doc, 2, 3)
    assert {"V21", "V3"} <= set(found)  # (and V2: the text being typed names it too)
    assert not {"HSPD", "ABS", "END"} & set(found)  # a move target is a number or a variable
    assert found["V21"].text_edit.range == t.Range(t.Position(2, 1), t.Position(2, 3))
    assert applied("XV2", found["V21"]) == "XV21"
    two_axes = Doc(client, "two.prg", "V21=1200\nX1000YV\nEND\n")
    await two_axes.settled()
    found = await items_at(client, two_axes, 1, 7)
    assert applied("X1000YV", found["V21"]) == "X1000YV21"


async def test_mcode_conditions_after_a_branch(client):
    """lexium-mcode.txt L1807 (BR <label>, [VAR/FLG/IN]<condition>) and L2124 (CL): after the comma
    the variables, flags and inputs are offered, not labels."""
    doc = Doc(client, "branch.mxt", "VA Np=0\nPG 1\nLB G1\n  BR G1,I\n  CL G1,\n  E\nPG\n")
    await doc.settled()
    found = await items_at(client, doc, 3, 9)
    assert "Np" in found and "MV" in found and "G1" not in found
    assert found["MV"].text_edit.range == t.Range(t.Position(3, 8), t.Position(3, 9))
    assert applied("  BR G1,I", found["I1"] if "I1" in found else found["MV"]).startswith("  BR G1,")
    after_call = await items_at(client, doc, 4, 8)
    assert "Np" in after_call and "G1" not in after_call


@pytest.mark.parametrize("typed", ["  TI 1,", "  TT=0.5,", "  OE=", "  BR "])
async def test_mcode_labels_where_a_command_takes_one(client, typed):
    """lexium-mcode.txt L5711 (TI <input>,<label>), L5908 (TT=<time>,<label>), L4551 (OE=<label>),
    L1807 (BR <label>): the labels are offered and inserted at the cursor."""
    doc = Doc(client, "labels.mxt", f"PG 1\nLB G1\n{typed}\n  E\nPG\n")
    await doc.settled()
    found = await items_at(client, doc, 2, len(typed))
    assert set(found) == {"G1"}
    assert applied(typed, found["G1"]) == typed + "G1"


async def test_x150_sequence_numbers_and_a_lone_device_address(client):
    """parker-x150.md L5125 (`<a>XRn`): after `1XR2` only the number is replaced; after a device
    address alone (`1`) the commands are inserted after it, the address kept."""
    doc = Doc(client, "sequences.x150", "1XD2\n1G\n1XT\n1XR2\n1\n")
    await doc.settled()
    found = await items_at(client, doc, 3, 4)
    assert found["2"].text_edit.range == t.Range(t.Position(3, 3), t.Position(3, 4))
    assert applied("1XR2", found["2"]) == "1XR2"
    found = await items_at(client, doc, 4, 1)
    assert found["G"].text_edit.range == t.Range(t.Position(4, 1), t.Position(4, 1))
    assert applied("1", found["G"]) == "1G"
