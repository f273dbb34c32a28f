"""X150 commands with a meaning other dialects share lower to neutral operations and settings
(issue 8): the X150 backend writes each back as written, and the other backends write it or refuse
it by name, never drop it."""

from __future__ import annotations

from mcc.backends import x150 as backend
from mcc.compiler import driver, ir, profiles
from mcc.compiler.span import Span

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
