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
    assert "- data flow: " in text and "never read" not in text


@pytest.mark.parametrize("dialect", sorted(PROGRAMS))
def test_a_variable_only_written_says_its_value_is_never_read(dialect):
    _, written = PROGRAMS[dialect][2]
    assert "(its value is never read)" in hover_text(dialect, written)


def test_the_counts_are_the_analysis_own_def_use_chains():
    path, text, _ = PROGRAMS["arcus"]
    snap = analysis.analyze(f"file:///{path}", path, 1, text)
    assert snap.analysis is not None and snap.analysis.defuse is snap.analysis.defuse  # built once, kept
    assert "- data flow: 1 write, 1 read" in hover_text("arcus", "V3")
    assert "(never written in this file)" in hover_text("arcus", "V6")
