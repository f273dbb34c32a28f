"""X150 sequences converted to MCode: how a called sequence ends, and jumps between sequences.

An X150 sequence ends at XT, which returns when XR/GOSUB ran it (parker-x150.md L1750, L5138);
MCode returns from a CL only with RT (lexium-mcode.txt L2121, L5232), and E ends the whole program
(L2527). XG/GOTO hands over without a new return address (L5077, L1790)."""

from __future__ import annotations

import re

from mcc.compiler import driver
from mcc.sim.verify import check_translation


def compile_to_mcode(source: str):
    return driver.compile_file("s.x150", "x150", target="mcode", text=source)


def errors(result) -> list[tuple[str, int, str]]:
    return [(d.code, d.span.line, d.message) for d in result.diagnostics if d.severity.value == "error"]


def routines(text: str) -> dict[str, list[str]]:
    """The lines of each labelled routine of an MCode listing, up to the next label or PG."""
    found: dict[str, list[str]] = {}
    current = None
    for line in text.splitlines():
        if line.startswith("LB "):
            current = line[3:]
            found[current] = []
        elif line.startswith("PG"):
            current = None
        elif current is not None:
            found[current].append(line)
    return found


# The manual's GOSUB example (parker-x150.md L1762-L1776), with a constant distance in sequence 2 and
# lines after each XR, so a called sequence that ended the program (E) would lose them.
GOSUB = """XE5
XD5
A2
V5
GOSUB2
1O0
GOSUB2
XT
XE2
XD2
MN
MPI
D25000
G
1O1
XT
XR5
1O0
T0.5
XR2
"""


def test_a_called_sequence_ends_with_rt_not_e_and_behaves_as_its_source():
    """L1750/L5138: XT of a sequence run by XR/GOSUB returns; L5232: RT returns from a CL, L2527: E
    ends the program. The conversion wrote E at the end of sequence 5 (the program stopped after
    `XR5`, output 1 was never set to 0) and nothing at the end of sequence 2 (the last one)."""
    result = compile_to_mcode(GOSUB)
    assert not errors(result), errors(result)
    text = result.listing.text
    called = set(re.findall(r"^CL (\w+)$", text, re.M))
    bodies = routines(text)
    assert len(called) == 2
    for label in called:
        assert bodies[label][-1] == "RT" and "E" not in bodies[label], bodies
    assert not check_translation("s.x150", "x150", GOSUB, text, "mcode")


GOTO_FROM_CALLED = """XE5
XD5
1O1
GOTO3
XT
XE3
XD3
1O0
T0.1
XT
XE6
XD6
GOSUB3
1O1
XT
XR5
1O1
T0.2
XR6
"""


def test_a_goto_to_another_sequence_is_a_call_then_the_callers_own_end():
    """L5077/L1790: GOTO hands over to sequence 3 without a new return address, so its XT returns to
    the XR5 that ran sequence 5. A BR from one MCode routine into another is M302 (a routine left
    without RT); the conversion writes `CL <sequence 3>` then sequence 5's own end (RT), which returns
    to the same place, and no BR leaves a routine."""
    result = compile_to_mcode(GOTO_FROM_CALLED)
    assert not errors(result), errors(result)
    text = result.listing.text
    bodies = routines(text)
    assert not [line for lines in bodies.values() for line in lines if line.startswith("BR ")]
    five = next(lines for lines in bodies.values() if lines[:1] == ["O1=1"])
    assert five[-2:][0].startswith("CL ") and five[-1] == "RT", five
    assert not check_translation("s.x150", "x150", GOTO_FROM_CALLED, text, "mcode")


def test_a_sequence_run_both_called_and_as_a_program_is_refused_at_its_end():
    """L1750 (XT returns to a GOSUB) against a power-up sequence (XP1), whose XT stops the program:
    MCode must choose RT (L5232) or E (L2527), so the conversion refuses with G003 on the XT line."""
    source = "XE1\nXD1\n1O1\nT0.1\nXT\nXE5\nXD5\nGOSUB1\n1O0\nXT\nXP1\nXR5\n"
    result = compile_to_mcode(source)
    found = [e for e in errors(result) if e[0] == "G003" and "SEQ1" in e[2]]
    assert [line for _, line, _ in found] == [5]
    assert "RT and E cannot do both" in found[0][2]


def test_jumps_that_cycle_between_sequences_are_refused_at_each_jump():
    """XG/GOTO 3 in sequence 5 and GOTO 5 in sequence 3 loop without end (L5077: no nesting). Written
    as CL each round would nest one call deeper (Error 43, lexium-mcode.txt L8489), and a BR out of a
    routine is M302: refused with G003 on each GOTO line."""
    source = "XE5\nXD5\n1O1\nGOTO3\nXT\nXE3\nXD3\n1O0\nT0.1\nGOTO5\nXT\nXR5\n"
    result = compile_to_mcode(source)
    assert sorted(line for code, line, message in errors(result) if code == "G003" and "leads back" in message) \
        == [4, 10]


def test_a_jump_from_one_converted_routine_into_another_is_refused():
    """A BR out of a routine leaves it without RT (M302: the return address stays on the stack,
    lexium-mcode.txt L2121, L8489): another dialect's IR that jumps into another routine's block is
    refused with G003 on the jump's line rather than written as a BR across routines."""
    from mcc.backends import mcode as backend
    from mcc.compiler import ir, profiles
    from mcc.compiler.span import Span

    span = Span("x.prg", 3, 1, 3, 5, 0, 4)
    main = ir.Routine("main", ir.RoutineKind.MAIN,
                      [ir.Block("%1", [ir.Call("S1"), ir.SetOutput(1, ir.Const(1))], ir.Jump("%3", span))])
    sub = ir.Routine("S1", ir.RoutineKind.SUBROUTINE,
                     [ir.Block("%2", [ir.SetOutput(2, ir.Const(1))], ir.Return()),
                      ir.Block("%3", [ir.SetOutput(3, ir.Const(1))], ir.Return())])
    module = ir.Module("arcus", "pmx-4ex-sa", {}, [main, sub])
    listing = backend.emit(module, profiles.load("lmd-c"))
    assert [(d.code, d.span.line) for d in listing.diagnostics] == [("G003", 3)]
    assert "into another routine" in next(iter(listing.diagnostics)).message
