"""The MCode writer holds (`H`) before a move or homing whose axis may still be moving.

The manual never says what MA/MR does to a move in progress; it asks for an H after every move
(lexium-mcode.txt L3048: "a Hold should always follow a programmed motion instruction such as MA
... or MR") and for motion to have stopped before the next motion command after `SL 0` (L5404).
In the IR a move on a moving axis waits for it to stop (docs/SIMULATOR.md, move_while_busy =
block), so the output must hold there for the drive to do the same."""

from __future__ import annotations

from mcc.compiler import driver
from mcc.sim.verify import check_translation


def program(text: str) -> list[str]:
    return [line for line in text.splitlines() if not line.startswith("'")]


def compiled(path: str, dialect: str, source: str) -> str:
    result = driver.compile_file(path, dialect, target="mcode", text=source)
    errors = [(d.code, d.span.line, d.message) for d in result.diagnostics if d.severity.value == "error"]
    assert not errors, errors
    return result.listing.text


def test_arcus_moves_one_after_another_get_a_hold_between_them():
    """L3048: an Arcus `X1000` then `X2000` (the second waits for the first in the IR) was written
    `MA 1000 / MA 2000`; now an H comes before each move while the axis may still move, and the
    output behaves as its source."""
    source = "ABS\nHSPD=3000\nLSPD=500\nACC=250\nX1000\nX2000\nDO1=1\nX500\nWAITX\nDO1=0\nEND\n"
    text = compiled("m.prg", "arcus", source)
    lines = program(text)
    first, second, third = (lines.index(f"MA {p}") for p in (1000, 2000, 500))
    assert lines[second - 1] == "H" and lines[third - 1] == "H"
    assert lines[first - 1] != "H"  # nothing ran before the first move
    assert lines[third + 1] == "H" and lines.count("H") == 3  # the WAITX is the H after MA 500, not a second one
    assert not check_translation("m.prg", "arcus", source, text, "mcode")


MCODE = """PG 1
LB AA
  MR 51200
  SL 0
  MR 100
  O1=1
  CL BB
  MA 0
  H
  MA 10
  H
  E
LB BB
  MR 200
  RT
PG
"""


def test_after_sl_0_across_calls_and_never_twice():
    """L5404: after `SL 0` stops an MR, motion must stop before the next motion command: H before
    `MR 100`. A subroutine called while the axis moves holds before its move, the caller holds after
    a call that leaves the axis moving, and a move already after an H gets no second one. Compiling
    the output again gives the same text."""
    text = compiled("h.mxt", "mcode", MCODE)
    assert program(text) == ["PG 1", "LB AA", "MR 51200", "SL 0", "H", "MR 100", "O1=1", "CL BB", "H", "MA 0", "H",
                             "MA 10", "H", "E", "LB BB", "H", "MR 200", "RT", "PG"]
    assert compiled("again.mxt", "mcode", text) == text
    assert not check_translation("h.mxt", "mcode", MCODE, text, "mcode")


def test_a_loop_that_waits_at_its_end_gets_no_hold_at_its_head():
    """The data flow follows branches: a loop whose body ends with H starts settled on every pass,
    so no H is written at its head (L3048 is met by the H after the move)."""
    source = "PG 1\nLB AA\n  R1=0\nLB BB\n  MR 100\n  H\n  IC R1\n  BR BB,R1<3\n  E\nPG\n"
    lines = program(compiled("l.mxt", "mcode", source))
    assert lines[lines.index("LB BB") + 1] == "MR 100"
    assert lines.count("H") == 1


def test_a_trip_handler_holds_before_its_move_only_when_the_program_may_be_moving():
    """A handler interrupts the program wherever it is (docs/SIMULATOR.md): when the program only
    moves with an H after each move the handler's first move needs none; when the program leaves a
    move running (a slew) the handler holds first."""
    idle = "PG 1\nLB G1\n  TI 1,X1\n  TE=1\nLB G2\n  BR G2\n  E\nLB X1\n  MR 100\n  H\n  TE=1\n  RT\nPG\n"
    lines = program(compiled("t.mxt", "mcode", idle))
    assert lines[lines.index("LB X1") + 1] == "MR 100"
    slewing = idle.replace("  TE=1\nLB G2", "  TE=1\n  SL 1000\nLB G2")
    lines = program(compiled("t.mxt", "mcode", slewing))
    assert lines[lines.index("LB X1") + 1] == "H"
