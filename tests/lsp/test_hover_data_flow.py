"""Hover on a variable reports what the check's data flow found (the def-use chains the analysis
keeps, compiler/symbols.py), in every dialect."""

from __future__ import annotations

import pytest

from mcc.lsp import analysis, hover

PROGRAMS = {
    # (file, text, (a variable the program reads, one it only writes))
    "mcode": ("p.mxt", "VA CT=0\nVA NR=0\nPG 1\nLB K1\nIC CT\nNR=3\nBR K1, CT<5\nE\nPG\n", ("CT", "NR")),
    "arcus": ("p.prg", "V3=5\nV4=V3*2\nV5=V6\nEND\n", ("V3", "V4")),
    "x150": ("p.x150", "VAR1=5\nVAR2=VAR1*2\nVAR3=VAR4\n", ("VAR1", "VAR2")),
}


def hover_text(dialect: str, name: str, occurrence: int = 0) -> str:
    path, text, _ = PROGRAMS[dialect]
    snap = analysis.analyze(f"file:///{path}", path, 1, text)
    offset = -1
    for _ in range(occurrence + 1):
        offset = text.index(name, offset + 1)
    found = hover.hover(snap, offset + len(name) - 1)  # X150's VAR1= names the variable by its number
    assert found is not None
    return found.contents.value


@pytest.mark.parametrize("dialect", sorted(PROGRAMS))
def test_a_variable_that_is_read_says_how_often_it_is_written_and_read(dialect):
    read, _ = PROGRAMS[dialect][2]
    text = hover_text(dialect, read)
    counted = "- used 2 times" if dialect == "mcode" else "- written 1 time, read 1 time"
    assert counted in text and "never read" not in text


@pytest.mark.parametrize("dialect", sorted(PROGRAMS))
def test_a_variable_only_written_says_its_value_is_never_read(dialect):
    _, written = PROGRAMS[dialect][2]
    assert "- data flow: its value is never read" in hover_text(dialect, written)


def test_the_counts_are_the_analysis_own_def_use_chains():
    path, text, _ = PROGRAMS["arcus"]
    snap = analysis.analyze(f"file:///{path}", path, 1, text)
    assert snap.analysis is not None and snap.analysis.defuse is snap.analysis.defuse  # built once, kept
    assert "never" not in hover_text("arcus", "V3")
    assert "- data flow: never written in this file" in hover_text("arcus", "V6")


COUNTED = {
    # issue 25: hover said "used 0 times" next to "data flow: 1 read". One count now, of the
    # occurrences find-references lists: (file, text, variable, occurrence to hover, written, read)
    "arcus move target": ("m.prg", "V21=1200\nXV21\nEND\n", "V21", 0, 1, 1),  # arcus L2759
    "x150 assignment": ("a.x150", "VAR1=5\n1D(VAR1)\nVAR2=VAR1+1\n", "VAR1", 0, 1, 2),
    "mcode increment": ("i.mxt", "VA CT=0\nPG 1\nLB K1\nIC CT\nBR K1, CT<5\nE\nPG\n", "CT", 1, 1, 2),
}


@pytest.mark.parametrize("case", sorted(COUNTED))
def test_the_counts_agree_with_find_references(case):
    path, text, name, occurrence, written, read = COUNTED[case]
    snap = analysis.analyze(f"file:///{path}", path, 1, text)
    offset = -1
    for _ in range(occurrence + 1):
        offset = text.index(name, offset + 1)
    symbol = snap.index.symbol_at(offset)
    found = hover.hover(snap, offset).contents.value
    assert (len(symbol.definitions), len(symbol.references)) == (written, read)
    counted = f"- used {hover.times(read)}" if path.endswith(".mxt") else \
        f"- written {hover.times(written)}, read {hover.times(read)}"
    assert counted in found
    assert "used 0 times" not in found


def test_a_variable_read_only_by_its_own_update_says_so():
    snap = analysis.analyze("file:///u.prg", "u.prg", 1, "V1=0\nV1=V1+1\nEND\n")
    found = hover.hover(snap, 0).contents.value
    assert "- data flow: its value is never read (read only to update itself)" in found
