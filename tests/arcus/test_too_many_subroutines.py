"""More subroutines than SUB numbers: a diagnostic for each one left over, never an internal error."""

from mcc.backends import arcus
from mcc.compiler import ir, profiles


def test_subroutines_without_a_number_are_reported():
    module = ir.Module("arcus", "pmx-4ex-sa")
    calls = [ir.Call(f"S{i}") for i in range(40)]
    module.routines.append(ir.Routine("MAIN", ir.RoutineKind.MAIN, [ir.Block("%m", calls, ir.End())]))
    for i in range(40):
        module.routines.append(ir.Routine(f"S{i}", ir.RoutineKind.SUBROUTINE, [ir.Block(f"%s{i}", [], ir.Return())]))
    listing = arcus.emit(module, profiles.load("pmx-4ex-sa"))
    codes = [d.code for d in listing.diagnostics]
    assert codes.count("A207") == 40 - 31  # numbers 1-31 are allocated, SUB 0 is kept free
    assert all(d.kind.value != "internal" for d in listing.diagnostics)
    assert sum(line.startswith("SUB ") for line in listing.text.splitlines()) == 31
