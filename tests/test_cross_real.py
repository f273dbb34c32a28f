"""Cross-compilation of real programs (issue 24): features that a target has under another name, or
needs no statement for, are converted instead of refused; what stays refused names its line.

Every conversion here is validated by simulation (driver.compile_file verifies by default), so a
program written is one that behaves like its source."""

from __future__ import annotations

import conversion
from mcc.compiler import driver

convert, written, body = conversion.convert, conversion.written, conversion.body


# -- MCode IS set-up on targets with inputs of their own ---------------------------------------------

HOME_AND_LIMIT = "IS=4,1,1\nIS=3,3,0\n"


def test_home_and_limit_setup_needs_no_arcus_statement() -> None:
    """lexium-mcode.txt L6942 (IS=4,1,1: input 4 is home) and L6958 (IS=3,3,0: limit-): the
    PMX-4EX-SA has +limit, -limit and home inputs of its own per axis (arcus-pmx-4ex-sa.txt L333),
    whose level is set from the host (POX, L700-L704), so the set-up is written as nothing."""
    out = written(HOME_AND_LIMIT, "mcode", "arcus")
    assert body(out, "arcus") == ["END"]


def test_home_and_limit_setup_needs_no_x150_command() -> None:
    """X150 has a HOME input and limit inputs of its own (parker-x150.md L3841, L3799); IN assigns
    functions to the 10 user inputs only (L2058-L2070), and none of its letters is home or a limit."""
    out = written(HOME_AND_LIMIT, "mcode", "x150")
    assert not [line for line in body(out, "x150") if "IN" in line]


def test_general_input_setup_needs_no_arcus_statement_when_unread() -> None:
    """lexium-mcode.txt L6959 (IS=2,0,1: general purpose, active high): the PMX-4EX-SA's DI1-DI8
    are general inputs with nothing to set up; the program never reads input 2."""
    out = written("IS=2,0,1\n", "mcode", "arcus")
    assert body(out, "arcus") == ["END"]


def test_general_input_level_is_refused_when_the_program_reads_it() -> None:
    """The level decides what the program reads from the line (lexium-mcode.txt L6936: active
    states); when the program reads input 2 itself at a level that changes over the run, the
    PMX-4EX-SA (no level statement in a program) refuses the set-up on its line rather than read
    another level. (`IS=2,0,0` alone, once this test's program, sets the power-up level, L3500, and
    now converts: tests/test_cross_from_mcode.py.)"""
    program = "IS=2,0,0\nPG 1\nLB A1\nBR A1, I2=0\nIS=2,0,1\nLB B1\nBR B1, I2=0\nE\nPG\n"
    _, errors = convert(program, "mcode", "arcus")
    assert [(code, line) for code, line, _ in errors] == [("G003", 1), ("G003", 5)], errors
    assert "level" in errors[0][2] and "DI2" in errors[0][2]


def test_home_line_read_by_the_program_keeps_its_setup() -> None:
    """A line the program reads as an input itself would be another input on the target (DI4 is not
    the home switch, arcus-pmx-4ex-sa.txt L333): the set-up is not dropped, it is refused on line 1."""
    program = "IS=4,1,1\nPG 1\nLB A1\nBR A1, I4=0\nE\nPG\n"
    _, errors = convert(program, "mcode", "arcus")
    assert errors and errors[0][1] == 1, errors


def test_jog_input_is_still_refused() -> None:
    """lexium-mcode.txt L6936 (IS=1,8,0: jog-): the PMX-4EX-SA has no jog input, a meaning it cannot
    express; the refusal names line 1."""
    _, errors = convert("IS=1,8,0\n", "mcode", "arcus")
    assert errors and errors[0][1] == 1 and "input_function" in errors[0][2]


# -- the target's step resolution, chosen when the program does not fix it ---------------------------

def test_x150_output_sets_a_cur_that_makes_mcode_positions_whole() -> None:
    """parker-x150.md L731-L747: CUR sets the user steps per revolution (1-32,767), the motor's travel
    unchanged. 20000 MCode steps (51200/rev, lexium-mcode.txt L645) fall between two steps at the
    profile's CUR4000, and are 10000 user steps at CUR25600 (half the source's). VI=400: X150 starts
    moves from standstill, and at MCode's power-up VI of 1000 steps/s (lexium-mcode.txt L662-L666)
    the move would end 2 ms later, which is refused (X216)."""
    out = body(written("VI=400\nMA 20000\n", "mcode", "x150"), "x150")
    assert out[0] == "1CUR25600" and "1D10000" in out


def test_x150_keeps_the_profile_cur_when_it_is_exact() -> None:
    """25600 MCode steps are 2000 user steps at the profile's CUR4000 (x 5/64): no CUR is written
    (VI=400 as above, lexium-mcode.txt L662-L666)."""
    out = body(written("VI=400\nMA 25600\n", "mcode", "x150"), "x150")
    assert not [line for line in out if "CUR" in line] and "1D2000" in out


def test_mcode_resolution_fixed_by_the_program_is_not_chosen() -> None:
    """An MCode program that sets MS itself (lexium-mcode.txt L4282) fixes its resolution: no CUR is
    chosen, and a position between two X150 steps is refused on its line (VI=400 as above)."""
    _, errors = convert("MS=256\nVI=400\nMA 20000\n", "mcode", "x150")
    assert [(code, line) for code, line, _ in errors] == [("X207", 3)]


def test_mcode_output_sets_a_legal_ms_for_a_computed_x150_distance() -> None:
    """An X150 distance held in a variable (D(VAR5), parker-x150.md L836) at CUR4000 would be
    x12.8 at MS=256 (51200 steps/rev), which MCode cannot compute exactly. MS=20 (4000 steps/rev)
    is no MS code (lexium-mcode.txt L4282-L4340), so the output sets MS=100 (20000 steps/rev) and
    multiplies the distance by 5."""
    out = body(written("VAR5=40000\nD(VAR5)\nG\n", "x150", "mcode"), "mcode")
    assert "MS=100" in out and out.index("MS=100") < out.index("PG 1")
    assert any(line.startswith("MR ") and line.endswith("*5") for line in out), out
    assert not any(line.startswith("MS=20") and line != "MS=200" for line in out)


def test_resolution_choice_can_be_turned_off_in_the_profile() -> None:
    """`cross.choose_resolution = false` in a target profile keeps its steps_per_rev (docs/CROSS.md)."""
    import dataclasses

    from mcc.compiler import profiles
    base = profiles.load("x150-pdhx")
    fixed = dataclasses.replace(base, data={**base.data, "cross": {"choose_resolution": False}})
    result = driver.compile_file("fixture.mxt", "mcode", "x150", profile=fixed, text="VI=400\nMA 20000\n")
    assert [d.code for d in result.diagnostics if d.severity.value == "error"] == ["X207"]


# -- abs without an abs function -----------------------------------------------------------------------

def test_x150_direction_on_the_distance_is_written_with_an_if_on_arcus() -> None:
    """parker-x150.md L1854 (H+ & H- Set Direction): H- makes the distance negative (the IR's D = -abs(D)); the
    PMX-4EX-SA has no abs function but IF/ENDIF and one-operator assignments
    (arcus-pmx-4ex-sa.txt L2671-L2677): V = V*-1 when V > 0. Validated by simulation."""
    out = body(written("MC\nH-\nA10\nV10\nG\n", "x150", "arcus"), "arcus")
    at = out.index(next(line for line in out if line.startswith("IF ")))
    assert out[at].endswith(">0") and out[at + 1].endswith("*-1") and out[at + 2] == "ENDIF", out
    assert "JOGX-" in out


# -- a constant output bank on X150 --------------------------------------------------------------------

def test_a_constant_output_bank_is_the_x150_pattern_of_the_source_outputs() -> None:
    """lexium-mcode.txt L851-L853: OT=5 sets the outputs 1-3 to 101 (the drive has three); X150 O
    sets outputs by pattern, X leaving one as it is (parker-x150.md L2731-L2753): `O101`, outputs
    4-6 untouched. The validation compares the outputs both products have (the profiles'
    `[machine.outputs] count`: 3 and 6; docs/CROSS.md, "Output banks"). This test expected a
    refusal before the simulator knew each product's outputs."""
    out = body(written("PG 1\nOT=5\nH 100\nOT=2\nE\nPG\n", "mcode", "x150"), "x150")
    first = out.index("O101")
    assert out[first:first + 3] == ["O101", "T0.1", "O010"]


def test_x150_cur_is_the_unit_the_arcus_pulses_count_in() -> None:
    """parker-x150.md L731-L745: CUR sets the user steps per revolution, `1CUR2000` then `D4000` is 2
    revolutions. The IR counts in those steps (the module's 2000/rev) and the PMX-4EX-SA output
    counts one pulse per source step (its header says so): the CUR statement has nothing left to say
    and the move is X4000."""
    out = body(written("1CUR2000\nD4000\nG\n", "x150", "arcus"), "arcus")
    assert "X4000" in out and not any("CUR" in line for line in out)
