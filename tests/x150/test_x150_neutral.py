"""X150 commands with a meaning other dialects share lower to neutral operations and settings
(issue 8): the X150 backend writes each back as written, and the other backends write it or refuse
it by name, never drop it."""

from __future__ import annotations

from mcc.backends import x150 as backend
from mcc.compiler import driver, ir, ir_names, profiles
from mcc.compiler.span import Span
from mcc.compiler.x150 import neutral

from x150_helpers import module, output

PROFILE = profiles.load("x150-pdhx")
SETTINGS = "1LD3\n1FSC1\n1FSD1\n1CER1000\n1CMR4000\n1DW10\n1FSB1\n1SSH1\n1IV2\n"
LINES = "1IN4C\n1OUT2B\n1INL_X1\n1OUTLX0X1\n"
OTHERS = "1ST1\n1ST0\n1SB\n1PR\n"


def test_shared_meanings_are_neutral_and_written_back_as_written():
    text = SETTINGS + LINES + OTHERS
    mod = module(text)
    ops = [op for _, block in mod.blocks() for op in block.ops]
    assert not [op for op in ops if isinstance(op, ir.Native)]
    names = [op.name for op in ops if isinstance(op, ir.Setting)]
    assert names[:9] == ["limits_disabled", "position_maintenance", "stop_on_stall", "encoder_resolution",
                         "motor_resolution", "position_deadband", "encoder_step_mode", "keep_buffer_on_stop",
                         "speed_change"]
    iv = next(op for op in ops if isinstance(op, ir.Setting) and op.name == "speed_change")
    assert iv.value == ir.Const(8000, ir.Unit.STEPS_PER_S, iv.value.span)  # 2 rev/s at 4000 steps/rev
    kill = next(op for op in ops if isinstance(op, ir.Setting) and op.name == "input_function")
    assert (kill.index, kill.value.value) == (4, "kill")
    assert [(op.index, op.value.value) for op in ops if isinstance(op, ir.Setting)
            and op.name == "output_active_high"] == [(2, 0), (4, 1)]
    assert [type(op).__name__ for op in ops[-4:]] == ["DriveEnable", "DriveEnable", "Stop", "Print"]
    assert output(text) == text.splitlines()


def test_a_setting_that_needs_the_host_is_refused_inside_a_sequence():
    """Arcus SSPD inside a program: X150's IV is immediate, a sequence cannot store it."""
    span = Span("p.prg", 3, 1, 3, 5, 0, 4)
    change = ir.Setting("speed_change", "X", ir.Const(8000, ir.Unit.STEPS_PER_S), span)
    main = ir.Routine("main", ir.RoutineKind.MAIN, [ir.Block("a", [change], ir.End(span), span)], span)
    listing = backend.emit(ir.Module("arcus", "pmx-4ex-sa", routines=[main], steps_per_rev=4000), PROFILE)
    [refusal] = [d for d in listing.diagnostics if d.severity.value == "error"]
    assert refusal.code == "G003" and refusal.span.line == 3 and "IV" in refusal.message


def test_other_dialects_refuse_what_they_cannot_set_by_name():
    to_arcus = driver.compile_file("s.x150", "x150", target="arcus", text="1LD3\n")
    assert any("limits_disabled" in d.message for d in to_arcus.diagnostics if d.severity.value == "error")
    # MCode's IS sets the function and the active level together: a function alone is not written
    # with a level the source never set
    to_mcode = driver.compile_file("s.x150", "x150", target="mcode", text="1IN4A\n")
    assert any("active level" in d.message for d in to_mcode.diagnostics if d.severity.value == "error")
    both = driver.compile_file("s.x150", "x150", target="mcode", text="1IN4A\n1INL_XXX1\n")
    assert not both.has_errors and "IS=4,0,1" in both.listing.text


# One line per X150 setting command the IR names (neutral.SETTINGS), with its neutral value.
NAMED_SETTINGS = {
    "1GA20": ("home_accel", 80000, ir.Unit.STEPS_PER_S2),  # 20 rev/s^2 at 4000 steps/rev
    "1GHF0.5": ("home_final_speed", 2000.0, ir.Unit.STEPS_PER_S),
    "1SIM1": ("following_mode", 1, ir.Unit.NONE),
    "1FOL50": ("following_ratio", 50, ir.Unit.PERCENT),
    "1CCS3": ("command_source", 3, ir.Unit.NONE),
    "1XST1": ("single_step", 1, ir.Unit.NONE),
    "1XTR0": ("trace", 0, ir.Unit.NONE),
    "DCNT1": ("panel_pause_keys", 1, ir.Unit.NONE),
    "DSTP0": ("panel_stop_key", 0, ir.Unit.NONE),
    "1LA900": ("limit_decel", 3600000, ir.Unit.STEPS_PER_S2),
    "1CPE4000": ("position_error_limit", 4000, ir.Unit.NONE),
    "1CIT20": ("in_position_time", 0.02, ir.Unit.S),  # ms on the X150, seconds in the IR
    "1CAG100": ("following_filter_time", 0.1, ir.Unit.S),
}


def test_configuration_commands_are_named_settings_in_ir_units_and_written_back():
    text = "".join(line + "\n" for line in NAMED_SETTINGS)
    ops = [op for _, block in module(text).blocks() for op in block.ops]
    assert [(op.name, op.value.value, op.value.unit) for op in ops] == list(NAMED_SETTINGS.values())
    assert output(text) == text.splitlines()


def test_servo_settings_and_ms_settings_in_a_sequence_keep_their_b_prefix():
    text = "1CPG91\n1CTG0.7\n1XE1\n1XD1\n1BCPG50\n1BCIT30\n1XT\n"
    ops = [op for _, block in module(text).blocks() for op in block.ops]
    assert [op.name for op in ops] == ["servo_proportional_gain", "servo_filter_time", "servo_proportional_gain",
                                       "in_position_time"]
    assert output(text, "x150e-bdhxe") == text.splitlines()


def test_every_input_and_output_function_letter_but_one_has_a_neutral_name():
    text = "".join(f"1IN{n % 10 + 1}{letter}\n" for n, letter in enumerate(neutral.INPUT_FUNCTIONS))
    text += "".join(f"1OUT{n % 6 + 1}{letter}\n" for n, letter in enumerate(neutral.OUTPUT_FUNCTIONS))
    ops = [op for _, block in module(text).blocks() for op in block.ops]
    assert all(isinstance(op, ir.Setting) and op.value.value in (ir_names.INPUT_FUNCTIONS + ir_names.OUTPUT_FUNCTIONS)
               for op in ops)
    assert output(text) == text.splitlines()
    assert isinstance(module("1OUT3L\n").routines[0].blocks[0].ops[0], ir.Native)  # changeover: no meaning


def test_gh_is_a_homing_move_at_its_own_speed_that_the_program_waits_for():
    text = "1V5\n1GH-2\n1D4000\n1G\n"
    ops = [op for _, block in module(text).blocks() for op in block.ops]
    home, wait = ops[1], ops[2]
    assert isinstance(home, ir.Home) and (home.axis, home.method, home.direction) == ("1", "switch", -1)
    assert home.speed.value == 8000 and home.speed.unit is ir.Unit.STEPS_PER_S  # 2 rev/s
    assert isinstance(wait, ir.WaitMotion) and wait.axis == "1"
    assert output(text) == ["1V5", "1GH-2", "1MN", "1MPI", "1D4000", "1G"]


def test_a_homing_move_x150_cannot_write_is_refused_and_gh_is_refused_elsewhere():
    span = Span("p.mxt", 2, 1, 2, 5, 0, 4)
    # a homing as GH does it (creep back at GHF 0.1 rev/s, 0 at the end, ramps at GA 10 rev/s²:
    # parker-x150.md L1715, L1722, L1726, L1686) but at a max speed the program never set
    seek = ir.Home("X", "switch", 1, span=span, creep=-1, creep_speed=ir.Const(400, ir.Unit.STEPS_PER_S), zero="end",
                   accel=ir.Const(40000, ir.Unit.STEPS_PER_S2))
    main = ir.Routine("main", ir.RoutineKind.MAIN, [ir.Block("a", [seek, ir.WaitMotion("X", span)], ir.End(span),
                                                             span)], span)
    listing = backend.emit(ir.Module("mcode", "", routines=[main], steps_per_rev=4000), PROFILE)
    [refusal] = [d for d in listing.diagnostics if d.severity.value == "error"]
    assert refusal.code == "G003" and "speed" in refusal.message and refusal.span.line == 2
    for target, words in (("mcode", "VM"), ("arcus", "HSPD")):
        result = driver.compile_file("h.x150", "x150", target=target, text="1V5\n1GH2\n")
        assert any(d.code == "G003" and words in d.message and d.span.line == 2 for d in result.diagnostics)


def test_another_dialects_homing_is_refused_because_gh_moves_the_zero():
    """MCode HM creeps off the switch at VI and leaves P counting (lexium-mcode.txt L3198; its
    example sets P=0 itself, L8084-L8086); X150 GH zeroes the counter where it stops (parker-x150.md
    L1715): written as GH, the program's position 0 would be elsewhere on the machine, so the
    conversion is refused on the HM line."""
    source = "PG 1\nVM=25600\nA=102400\nD=102400\nHM 1\nH\nMA 51200\nH\nE\nPG\n"
    result = driver.compile_file("h.mxt", "mcode", target="x150", text=source)
    # the move on line 7 is refused too: it starts at MCode's power-up VI (X216, lexium-mcode.txt L662-L666)
    [refusal] = [d for d in result.diagnostics if d.severity.value == "error" and d.code != "X216"]
    assert refusal.code == "G003" and refusal.span.line == 5 and "zero" in refusal.message


def test_a_conditional_call_is_an_if_around_the_call():
    """MCode `CL SB, I1=1`: X150 has no conditional call; IF(c) XRn NIF runs the same.

    The drive's moves start at its power-up VI of 1000 steps/s (lexium-mcode.txt L662), X150's from
    standstill: the move would end up to 19 ms later in X150, refused (X216) on the move; with
    VI=50 (at most 0.98 ms later, within `[x150] start_speed_drift`) it converts and validates."""
    source = "PG 1\nLB K1\nVM=25600\nA=102400\nD=102400\nCL SB, I1=1\nCL SB, I2=0\nE\nLB SB\nMR 51200\nH\nRT\nPG\n"
    refused = driver.compile_file("c.mxt", "mcode", target="x150", text=source)
    assert [(d.code, d.span.line) for d in refused.diagnostics if d.severity.value == "error"] == [("X216", 10)]
    source = source.replace("VM=25600", "VI=50\nVM=25600")
    result = driver.compile_file("c.mxt", "mcode", target="x150", text=source)
    assert not result.has_errors, [(d.code, d.message) for d in result.diagnostics]
    lines = result.listing.text.splitlines()
    first = lines.index("IF(IN_1)")
    assert lines[first:first + 6] == ["IF(IN_1)", "XR2", "NIF", "IF(IN_X0)", "XR2", "NIF"]
    assert not driver.compile_file("out.x150", "x150", text=result.listing.text).has_errors
