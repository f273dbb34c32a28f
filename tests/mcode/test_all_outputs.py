"""Setting every output at once: MCode's OT takes 0-7, outputs 1-3 as bits (lexium-mcode.txt
L4669; the range line L4671 prints 1-7, the catalog takes 0-7 since OT=0 clears all three)."""

from __future__ import annotations

from mcc.backends import mcode as backend
from mcc.compiler import driver, ir, profiles
from mcc.compiler.span import Span
from mcc.sim.verify import check_translation

PROFILE = profiles.load("lmd-c")


def compile_to_mcode(path: str, dialect: str, source: str):
    return driver.compile_file(path, dialect, target="mcode", text=source)


def errors(result) -> list[tuple[str, int, str]]:
    return [(d.code, d.span.line, d.message) for d in result.diagnostics if d.severity.value == "error"]


def test_an_arcus_value_above_7_is_refused_on_its_line_not_written_as_ot_9():
    """L4669: OT is a 3-bit value. Arcus `DO=9` (outputs 1 and 4) was written `OT=9`, which the drive
    does not take and whose output 4 it lacks: now G003 on line 1."""
    result = compile_to_mcode("o.prg", "arcus", "DO=9\nDELAY=100\nDO=0\nEND\n")
    assert [(code, line) for code, line, _ in errors(result)] == [("G003", 1)]
    assert "OT takes 0-7" in errors(result)[0][2]


def test_an_arcus_value_within_0_to_7_is_ot_and_behaves_the_same():
    """L4669: `DO=5` sets outputs 1 and 3: `OT=5`; `DO=0` clears them: `OT=0`."""
    source = "DO=5\nDELAY=100\nDO=0\nEND\n"
    result = compile_to_mcode("o.prg", "arcus", source)
    assert not errors(result), errors(result)
    lines = result.listing.text.splitlines()
    assert "OT=5" in lines and "OT=0" in lines
    assert not check_translation("o.prg", "arcus", source, result.listing.text, "mcode")


def test_an_x150_pattern_is_split_per_output_and_one_above_3_is_refused():
    """An X150 pattern with X (leave as is) becomes one `On=` per output it sets, also a full 3-bit one
    (`O101`: output 1 first); a pattern setting output 4, which the drive lacks (L4669: outputs 1-3),
    is refused on its line."""
    source = "1O1X0\nT0.1\n1O101\nT0.1\n"
    result = compile_to_mcode("o.x150", "x150", source)
    assert not errors(result), errors(result)
    lines = [line for line in result.listing.text.splitlines() if not line.startswith("'")]
    first = lines.index("O1=1")
    assert lines[first:first + 3] == ["O1=1", "O3=0", "H 100"]  # output 2 (X) is left as it is
    full = lines.index("O1=1", first + 1)
    assert lines[full:full + 3] == ["O1=1", "O2=0", "O3=1"]
    assert not check_translation("o.x150", "x150", source, result.listing.text, "mcode")
    refused = compile_to_mcode("o.x150", "x150", source + "1O1101\n")
    assert [(code, line) for code, line, _ in errors(refused)] == [("G003", 5)]


def test_a_run_time_value_of_another_dialect_is_refused_an_mcode_ones_is_kept():
    """L4669: a value computed at run time may have a bit above output 3 in another dialect (Arcus DO
    is 8 bits): refused; an MCode source's own `OT=R1` is written as it was (the drive checks it)."""
    span = Span("o.prg", 2, 1, 2, 6, 0, 5)
    op = ir.SetOutput(None, ir.Var("V1"), span=span)
    arcus = ir.Module("arcus", "pmx-4ex-sa", {"V1": ir.Variable("V1")},
                      [ir.Routine("main", ir.RoutineKind.MAIN, [ir.Block("%1", [op], ir.End())])])
    listing = backend.emit(arcus, PROFILE)
    assert [(d.code, d.span.line) for d in listing.diagnostics] == [("G003", 2)]
    mcode = ir.Module("mcode", "lmd-c", {"R1": ir.Variable("R1")},
                      [ir.Routine("AA", ir.RoutineKind.MAIN, [ir.Block("AA", [ir.SetOutput(None, ir.Var("R1"))],
                                                                         ir.End(), named=True)], origin=1)])
    assert "OT=R1" in backend.emit(mcode, PROFILE).text.splitlines()
