"""MCode program regions: what -Os outlines stays inside the region of its callers, and the writer
never puts a routine outside every region (lexium-mcode.txt L510-L512, L4794)."""

from __future__ import annotations

import re

from mcc.backends import mcode as backend
from mcc.compiler import driver, ir, profiles
from mcc.compiler.span import Span

PROFILE = profiles.load("lmd-c")


REPEATED = "  O1=1\n  MR 1000\n  H\n  O1=0\n  H 100\n  O2=1\n"


def program_lines(text: str) -> list[str]:
    return [line for line in text.splitlines() if not line.startswith("'")]


def test_outlined_routine_is_written_before_the_closing_pg_not_after_the_save():
    """lexium-mcode.txt L510-L512: after the closing PG a line runs at once (immediate mode), and
    L4794 (`PG 1 [MAIN PROG] [SUBROUTINES]`): a program's subroutines are inside its region. -Os
    used to write `LB Z0 / O1=1 / ... / RT` after `PG` and `S`: sent to a device it switched an
    output at once and `CL Z0` called a label the device did not hold."""
    from mcc.sim.verify import check_translation

    source = "VA K1=0\nPG 100\nLB AA\n" + REPEATED * 3 + "  E\nPG\nS\n"
    result = driver.compile_file("os.mxt", "mcode", text=source, opt_level="Os")
    assert not result.has_errors, [d.message for d in result.diagnostics]
    lines = program_lines(result.listing.text)
    assert lines[-2:] == ["PG", "S"], lines
    label = re.search(r"^CL (\w+)$", result.listing.text, re.M).group(1)
    assert lines.index(f"LB {label}") < len(lines) - 2 and lines.index("RT") < len(lines) - 2
    assert result.listing.text.splitlines()[-1] == backend.SAVE_TRAILER
    assert not check_translation("os.mxt", "mcode", source, result.listing.text, "mcode")


def test_outlined_routine_serves_only_the_program_region_it_is_written_in():
    """L4794: each program region (PG <address> ... PG) holds its own subroutines. A run repeated in
    two regions is outlined from one region only, and the routine is written inside that region."""
    from mcc.sim.verify import check_translation

    source = ("PG 100\nLB AA\n" + REPEATED * 3 + "  E\nPG\n"
              "PG 200\nLB CC\n" + REPEATED + "  H 50\n" + REPEATED + "  E\nPG\nS\n")
    result = driver.compile_file("two.mxt", "mcode", text=source, opt_level="Os")
    assert not result.has_errors, [d.message for d in result.diagnostics]
    lines = program_lines(result.listing.text)
    second = lines.index("PG 200")
    outlined = set(re.findall(r"^CL (\w+)$", result.listing.text, re.M))
    assert outlined, "the run repeated three times in PG 100 is outlined"
    for label in outlined:
        defined = lines.index(f"LB {label}")
        callers = [i for i, line in enumerate(lines) if line == f"CL {label}"]
        assert all((i < second) == (defined < second) for i in callers), lines
    assert lines[second - 1] == "PG" and lines[-2:] == ["PG", "S"]
    assert not check_translation("two.mxt", "mcode", source, result.listing.text, "mcode")


def test_a_routine_outside_every_program_region_is_refused():
    """L510-L512: a line after the closing PG runs at once and is not stored. An IR routine the
    writer would place there (after an immediate line, with PG addresses given) is refused with
    G003 at its line instead of being written as immediate commands."""
    module = ir.Module("mcode", "lmd-c")
    span = Span("x.mxt", 7, 1, 7, 5, 0, 4)
    main = ir.Routine("AA", ir.RoutineKind.MAIN, [ir.Block("AA", [ir.SetOutput(1, ir.Const(1))], ir.End(),
                                                           named=True)], origin=100)
    save = ir.Routine("immediate", ir.RoutineKind.IMMEDIATE, [ir.Block("%i", [ir.Save()], ir.FallOff())])
    late = ir.Routine("BB", ir.RoutineKind.SUBROUTINE,
                      [ir.Block("BB", [ir.SetOutput(1, ir.Const(0), span=span)], ir.Return(), named=True)])
    module.routines += [main, save, late]
    listing = backend.emit(module, PROFILE)
    assert [(d.code, d.span.line) for d in listing.diagnostics] == [("G003", 7)]
    assert "outside any program region" in next(iter(listing.diagnostics)).message


def test_a_region_whose_program_runs_off_its_end_gets_no_outlined_routine():
    """A program without E runs on into the line after it (M323; the samples end programs with E and
    put subroutines after it, L7617-L7658): an outlined routine placed there would run after the
    program, and its RT would return with no call on the stack (L8489). Such a region is left as
    written."""
    source = "PG 100\nLB AA\n" + REPEATED * 3 + "PG\nS\n"
    result = driver.compile_file("fall.mxt", "mcode", text=source, opt_level="Os")
    assert not result.has_errors, [d.message for d in result.diagnostics]
    assert "CL " not in result.listing.text and "RT" not in program_lines(result.listing.text)
