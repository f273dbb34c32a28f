"""MCode programs converted to X150 and to the Arcus PMX-4EX-SA (issue 24): constructs the target has
under another form are converted, and each conversion is validated by simulation (driver.compile_file
verifies by default), so a program written behaves like its source."""

from __future__ import annotations

import conversion

body = conversion.body


def convert(text: str, target: str, source: str = "mcode"):
    return conversion.convert(text, source, target)


def written(text: str, target: str, source: str = "mcode") -> str:
    return conversion.written(text, source, target)


# -- a slew at a velocity into Arcus ----------------------------------------------------------------

SLEW = "VI=1000\nVM=768000\nA=1000000\nD=1000000\nPG 100\nSL 200000\nH 1000\nSL 0\nH\nMR 5000\nH\nE\nPG\n"


def test_slew_at_a_velocity_is_a_jog_at_that_high_speed() -> None:
    """lexium-mcode.txt L5393-L5404: `SL 200000` slews at 200000 steps/s, accelerating at A. The
    PMX-4EX-SA jogs "using current high speed, low speed, and acceleration" (arcus-pmx-4ex-sa.txt
    L2302-L2310) and ramps in ACC ms from LSPD to HSPD (L436-L441): HSPD=200000 with ACC=199
    ((200000-1000)/1000000 s) gives the same acceleration; HSPD and ACC in force (768000, 767 ms) are
    written back after the JOG for the move that follows. `SL 0` is STOPX (a ramped stop)."""
    out = body(written(SLEW, "arcus"), "arcus")
    jog = out.index("JOGX+")
    assert out[jog - 2:jog + 3] == ["HSPDX=200000", "ACCX=199", "JOGX+", "HSPDX=768000", "ACCX=767"]
    assert "STOPX" in out


def test_slew_in_the_negative_direction() -> None:
    """A negative SL velocity (L5393: the sign is the direction) is JOGX-."""
    out = body(written(SLEW.replace("SL 200000", "SL -200000"), "arcus"), "arcus")
    assert "JOGX-" in out


def test_slew_while_a_move_may_run_is_refused() -> None:
    """A slew right after a move without H changes the speed of a running motion: Arcus changes speed
    on the fly only with SSPD (arcus-pmx-4ex-sa.txt L529-L533), so it stays refused on its line."""
    program = "VI=1000\nVM=768000\nA=1000000\nD=1000000\nPG 100\nMR 5000\nSL 200000\nE\nPG\n"
    _, errors = convert(program, "arcus")
    assert ("G003", 7) in [(code, line) for code, line, _ in errors], errors


def test_slew_at_a_computed_velocity_is_refused() -> None:
    """`SL V1` (a velocity known at run time only): HSPD and the ramp time cannot be computed."""
    program = "VA V1=200000\nPG 100\nSL V1\nE\nPG\n"
    _, errors = convert(program, "arcus")
    assert ("G003", 3) in [(code, line) for code, line, _ in errors], errors


# -- D=A: a setting that reads another --------------------------------------------------------------

DECEL_IS_ACCEL = "VI=50\nVM=51200\nA=102400\nD=A\nPG 100\nMR 51200\nH\nE\nPG\n"


def test_decel_set_to_the_acceleration_converts_to_x150() -> None:
    """`D=A` (lexium-mcode.txt L7626, in the manual's applications; D sets the deceleration, L2270)
    gives D the acceleration in force, 102400 steps/s^2: X150 decelerates at A (parker-x150.md L195-L203),
    so nothing more is written, where a deceleration read at run time was refused before."""
    out = body(written(DECEL_IS_ACCEL, "x150"), "x150")
    assert "1A2" in out  # 102400 / 51200 rev/s^2


def test_decel_set_to_the_acceleration_converts_to_arcus() -> None:
    """The same into the PMX-4EX-SA: one ACC ramps up and down (arcus-pmx-4ex-sa.txt L436-L441),
    (51200 - 50) / 102400 s = 499.5, 500 ms."""
    out = body(written(DECEL_IS_ACCEL, "arcus"), "arcus")
    assert "ACCX=500" in out


# -- input levels the target reads without a statement ----------------------------------------------

def test_input_level_as_at_power_up_needs_no_arcus_statement() -> None:
    """`IS=1,0,0` (lexium-mcode.txt L6936-L6959: input 1 general purpose, active low) sets the level
    MCode inputs have at power-up (L3500): it changes nothing, so input 1 reads as an input the
    program does not set, its level inverted for the PMX-4EX-SA, whose DI1 reads the level
    (arcus-pmx-4ex-sa.txt L1900-L1905): `I1=1` (active, low) is `DI1=0`."""
    program = "IS=1,0,0\nPG 100\nLB A1\nBR A1, I1=0\nMR 100\nH\nE\nPG\n"
    out = body(written(program, "arcus"), "arcus")
    assert "WHILE DI1=1" in out, out


def test_input_level_the_target_reads_needs_no_arcus_statement() -> None:
    """`IS=1,0,1` (active high) before anything else runs: MCode then reads input 1 as the level,
    as the PMX-4EX-SA's DI1 does (arcus-pmx-4ex-sa.txt L1900-L1905): no statement, no inversion."""
    program = "IS=1,0,1\nPG 100\nLB A1\nBR A1, I1=0\nMR 100\nH\nE\nPG\n"
    out = body(written(program, "arcus"), "arcus")
    assert "WHILE DI1=0" in out, out


def test_input_level_changed_later_stays_refused() -> None:
    """An active-high level set after the program has read the input (and low-active before): the
    reads differ in polarity over the run, which the PMX-4EX-SA cannot follow: refused on line 4."""
    program = "PG 100\nLB A1\nBR A1, I1=0\nIS=1,0,1\nLB B1\nBR B1, I1=0\nE\nPG\n"
    _, errors = convert(program, "arcus")
    assert ("G003", 4) in [(code, line) for code, line, _ in errors], errors


# -- the save-on-load idiom -------------------------------------------------------------------------

def test_save_after_the_program_is_left_out_on_arcus() -> None:
    """`S` after the final PG saves the program on load (lexium-mcode.txt L5250-L5263); the
    PMX-4EX-SA writes a standalone program to flash when it is downloaded (arcus-pmx-4ex-sa.txt
    L844, L1032): written as nothing, with a warning on line 5."""
    result, errors = convert("PG 100\nMR 100\nH\nE\nPG\nS\n", "arcus")
    assert not errors, errors
    assert [d.span.line for d in result.diagnostics if d.severity.value == "warning" and "save" in d.message] == [6]


def test_save_while_the_program_runs_stays_refused_on_arcus() -> None:
    """`S` inside a program keeps values the run computed (L5250-L5256): the PMX-4EX-SA stores to
    flash from the PC only (STORE, arcus-pmx-4ex-sa.txt L819), so it stays refused on line 2."""
    _, errors = convert("PG 100\nS\nE\nPG\n", "arcus")
    assert ("G003", 2) in [(code, line) for code, line, _ in errors], errors


# -- MCode's power-up initial speed into X150 ---------------------------------------------------------

def test_power_up_initial_speed_is_refused_at_the_first_move() -> None:
    """An MCode program that sets no VI starts its moves at 1000 steps/s (lexium-mcode.txt L662-L666);
    X150 starts every move from standstill (docs/dialects/x150.md; A ramps from 0, parker-x150.md
    L195-L203), so at A=1000000 each move ends up to 2 ms later, more than `[x150] start_speed_drift`
    (1 ms): refused (X216) at the first move, line 2, naming the VI that would convert, rather than
    by the validation (S010) with no advice (lexium-mcode.txt L751-L759, the manual's H example)."""
    _, errors = convert("PG 100\nMR 20000\nH\nMR -20000\nH\nE\nPG\n", "x150")
    assert [(code, line) for code, line, _ in errors] == [("X216", 2)], errors
    assert "500 steps/s or less" in errors[0][2]


def test_low_initial_speed_set_by_the_program_converts() -> None:
    """The same program with VI=400 (L662-L666): moves end at most 0.8 ms later, within the profile's
    1 ms, and the conversion is written (warning X205: the initial speed is left out)."""
    out = body(written("VI=400\nPG 100\nMR 20000\nH\nMR -20000\nH\nE\nPG\n", "x150"), "x150")
    assert out[0] == "1CUR25600" and "1D10000" in out and "1D-10000" in out


# -- output set-up the PMX-4EX-SA needs none of -------------------------------------------------------

def test_general_output_active_high_needs_no_arcus_statement() -> None:
    """`OS=1,16,1` (lexium-mcode.txt L4602-L4640: output 1 general purpose user, HIGH active; the
    manual's relay example L7109-L7118): the PMX-4EX-SA's DO1-DO8 are general outputs and one turned
    on sources VS (arcus-pmx-4ex-sa.txt L357, L752), so the set-up is written as nothing and
    `O1=1` is `DO1=1`."""
    out = body(written("OS=1,16,1\nPG 100\nO1=1\nE\nPG\n", "arcus"), "arcus")
    assert "DO1=1" in out and not [line for line in out if line.startswith("OS")]


def test_low_active_or_other_output_function_stays_refused() -> None:
    """`OS=1,16,0` (LOW active, L4620) is the opposite of what an Arcus output does when on, and
    `OS=1,17,1` (moving, L4627) has no Arcus output function: both refused on line 1."""
    for program in ("OS=1,16,0\nPG 100\nO1=1\nE\nPG\n", "OS=1,17,1\nPG 100\nMR 100\nH\nE\nPG\n"):
        _, errors = convert(program, "arcus")
        assert ("G003", 1) in [(code, line) for code, line, _ in errors], (program, errors)


def test_slew_after_a_move_sent_as_a_command_is_refused() -> None:
    """`MA 5000` sent before the program, with no H after it (H is what waits for a move to end,
    lexium-mcode.txt L3048), may still run when the program's `SL` starts: refused as above."""
    program = "VI=1000\nVM=768000\nA=1000000\nD=1000000\nMA 5000\nPG 100\nSL 200000\nE\nPG\n"
    _, errors = convert(program, "arcus")
    assert ("G003", 7) in [(code, line) for code, line, _ in errors], errors
