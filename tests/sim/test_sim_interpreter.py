"""The interpreter on hand-built IR: motion timing, waits, inputs, handlers, stops and errors."""

from __future__ import annotations

import math

import pytest

from mcc.compiler import ir
from mcc.compiler.ir import VarType
from mcc.sim import Options, simulate
from mcc.sim.interpreter import ContractError
from mcc.sim.scenario import AxisSwitches, InputEvent, Scenario
from mcc.sim.verify import compare
from sim_helpers import U, accel, at, c, eq, inp, kinds, module, move, speed, steps, sub


def test_a_trapezoidal_move_takes_the_time_its_settings_give():
    # 4000 steps at 1000 steps/s with 1000 steps/s²: 1 s up (500 steps), 3 s cruise, 1 s down
    trace = simulate(module([speed("X", 1000), *accel("X", 1000), move("X", 4000), ir.WaitMotion("X")]))
    assert trace.stopped == "end"
    assert trace.time == pytest.approx(5.0)
    assert trace.axes["X"] == 4000
    (end,) = kinds(trace, "move_end")
    assert end.t == pytest.approx(5.0)


def test_a_short_move_has_a_triangular_profile():
    # 1000 steps with a = d = 1000: peak sqrt(1000 * 1000) = 1000 steps/s at 1 s, arrive at 2 s
    trace = simulate(module([speed("X", 5000), *accel("X", 1000), move("X", 1000), ir.WaitMotion("X")]))
    assert trace.time == pytest.approx(2.0)
    assert max(abs(v) for _, _, v in trace.samples["X"]) == pytest.approx(1000, rel=1e-6)


def test_an_s_curve_takes_as_long_as_the_trapezoid_and_starts_gently():
    ops = [speed("X", 1000), *accel("X", 1000), move("X", 4000), ir.WaitMotion("X")]
    smooth = [ir.SetMotion(ir.MotionParam.PROFILE, "X", c(1))] + ops
    a, b = simulate(module(ops)), simulate(module(smooth))
    assert b.time == pytest.approx(a.time)
    early_a = next(v for t, _, v in a.samples["X"] if 0 < t < 0.5)
    early_b = next(v for t, _, v in b.samples["X"] if 0 < t < 0.5)
    assert early_b < early_a


def test_ramp_times_turn_into_accelerations_with_the_speeds_in_force():
    ops = [speed("X", 1000), ir.SetMotion(ir.MotionParam.ACCEL_TIME, "X", c(0.5, U.S)),
           ir.SetMotion(ir.MotionParam.DECEL_TIME, "X", c(0.5, U.S)), move("X", 2000), ir.WaitMotion("X")]
    # 0.5 s ramps (250 steps each), 1500 steps of cruise at 1000 steps/s: 2.5 s
    assert simulate(module(ops)).time == pytest.approx(2.5)


def test_relative_moves_add_to_the_position_and_moves_do_not_block_the_program():
    ops = [speed("X", 1000), *accel("X", 1e9), move("X", 1000), ir.SetOutput(1, c(1), at(3)),
           ir.WaitMotion("X"), move("X", -300, ir.MoveMode.RELATIVE), ir.WaitMotion("X")]
    trace = simulate(module(ops))
    assert trace.axes["X"] == 700
    (output,) = kinds(trace, "output")
    assert output.t == 0 and output.line == 3


def test_a_move_on_a_busy_axis_waits_for_it_to_stop():
    ops = [speed("X", 1000), *accel("X", 1e9), move("X", 1000), move("X", 0), ir.WaitMotion("X")]
    trace = simulate(module(ops))
    starts = [e.t for e in kinds(trace, "move")]
    assert starts == [0, pytest.approx(1.0)]
    assert trace.time == pytest.approx(2.0)


def test_linear_interpolation_brings_every_axis_in_together():
    two = ir.Move(ir.MoveMode.ABSOLUTE, (("X", steps(3000)), ("Y", steps(4000))))
    trace = simulate(module([speed("X", 1000), *accel("X", 1e9), two, ir.WaitMotion("*")]))
    ends = {e.data["axis"]: e.t for e in kinds(trace, "move_end")}
    assert ends["X"] == ends["Y"] == pytest.approx(5.0)  # path length 5000 at 1000 steps/s
    assert trace.axes == {"X": 3000, "Y": 4000}


def test_an_arc_ends_on_its_circle():
    arc = ir.Arc(("X", "Y"), (steps(0), steps(0)), clockwise=False, angle=ir.Const(90, U.DEGREES))
    trace = simulate(module([move("X", 1000), move("Y", 0), ir.WaitMotion("*"), arc, ir.WaitMotion("*")]))
    assert trace.axes["X"] == pytest.approx(0, abs=1e-6)
    assert trace.axes["Y"] == pytest.approx(1000)


@pytest.mark.parametrize(("start", "clockwise", "degrees", "end", "turned"), [
    ((0, 1000), True, 180, (1000, 0), 90),       # arcus-pmx-4ex-sa.txt L604-L610: ARCP0:0:180000
    ((-1000, 0), False, 450, (0, 1000), 270),    # L612-L614: ARCN0:0:450000 (450 = 90 + a turn)
    ((-1000, 0), False, 0, (-1000, 0), 360),     # the end is the start: a full turn
])
def test_an_arc_s_angle_is_its_end_point_s_direction_clockwise_from_the_negative_first_axis(
        start, clockwise, degrees, end, turned):
    """arcus-pmx-4ex-sa.txt L598: "The θ value should be calculated by making the 0° reference
    point to be the negative x-axis"; both examples (L604-L614) put the end point at θ measured
    clockwise. The arc runs from the start in its direction to that point (docs/IR.md, "Arcs")."""
    arc = ir.Arc(("X", "Y"), (steps(0), steps(0)), clockwise=clockwise, angle=ir.Const(degrees, U.DEGREES))
    trace = simulate(module([move("X", start[0]), move("Y", start[1]), ir.WaitMotion("*"), arc,
                             ir.WaitMotion("*")]))
    assert trace.axes["X"] == pytest.approx(end[0], abs=1e-6)
    assert trace.axes["Y"] == pytest.approx(end[1], abs=1e-6)
    length = [e for e in trace.motion_log if e[0] == "X"][-1][1].path.length
    assert length == pytest.approx(1000 * math.radians(turned))


def test_delays_advance_virtual_time_and_prints_keep_their_time():
    ops = [ir.Delay(c(1.5, U.S)), ir.Print((ir.Text("at "), ir.Status("timer", index=1)), span=at(2))]
    trace = simulate(module(ops))
    assert trace.prints == [(1.5, "at 1.5\n")]
    assert trace.time == 1.5


def test_waiting_on_an_input_the_scenario_sets():
    ops = [ir.WaitInput(eq(inp(2), 1), at(4)), ir.SetOutput(3, c(1))]
    trace = simulate(module(ops), Scenario(events=[InputEvent(2, 1, at=7.25)]))
    assert trace.stopped == "end" and trace.time == 7.25 and trace.outputs == {3: 1}


def test_waiting_on_an_input_the_scenario_never_sets_is_reported_as_waiting():
    trace = simulate(module([ir.WaitInput(eq(inp(2), 1), at(4))]))
    assert trace.stopped == "waiting"
    assert "line 4" in trace.reason and "input" in trace.reason


def test_a_polling_loop_sees_a_scenario_input():
    loop = ("poll", [], ir.Branch(eq(inp(1), 1), "done", "poll"))
    done = ("done", [ir.SetOutput(1, c(1))], ir.End())
    trace = simulate(module(loop, done), Scenario(events=[InputEvent(1, 1, at=3.0)]))
    assert trace.stopped == "end" and trace.time == 3.0


def test_a_polling_loop_on_a_position_sees_the_axis_pass():
    start = ("start", [speed("X", 1000), *accel("X", 1e9), move("X", 5000)], ir.Jump("poll"))
    loop = ("poll", [], ir.Branch(ir.Compare(">=", ir.Status("position", "X"), c(2000)), "done", "poll"))
    done = ("done", [ir.SetOutput(1, c(1))], ir.End())
    trace = simulate(module(start, loop, done))
    (output,) = kinds(trace, "output")
    assert output.t == pytest.approx(2.0, abs=0.002)


def test_an_axis_passing_a_position_sets_an_input():
    scenario = Scenario(events=[InputEvent(3, 1, axis="X", passes=2500)])
    ops = [speed("X", 1000), *accel("X", 1e9), move("X", 4000), ir.WaitInput(eq(inp(3), 1)), ir.SetOutput(1, c(1))]
    trace = simulate(module(ops), scenario)
    (output,) = kinds(trace, "output")
    assert output.t == pytest.approx(2.5)


def test_homing_runs_to_the_switch_and_zeroes_the_position():
    scenario = Scenario(axes={"X": AxisSwitches(home=-1500)})
    ops = [speed("X", 1000), *accel("X", 1e9), ir.Home("X", "switch", -1), ir.WaitMotion("X"),
           move("X", 100), ir.WaitMotion("X")]
    trace = simulate(module(ops), scenario)
    (home_end,) = kinds(trace, "home_end")
    assert home_end.t == pytest.approx(1.5)
    assert trace.axes["X"] == 100


def test_homing_with_a_speed_of_its_own_seeks_at_that_speed_not_the_max_speed():
    scenario = Scenario(axes={"X": AxisSwitches(home=-1500)})
    ops = [speed("X", 1000), *accel("X", 1e9), ir.Home("X", "switch", -1, speed=c(500, U.STEPS_PER_S)),
           ir.WaitMotion("X")]
    (home_end,) = kinds(simulate(module(ops), scenario), "home_end")
    assert home_end.t == pytest.approx(3.0)  # X150 GH: 1500 steps at 500 steps/s, V says 1000


def test_a_setting_the_simulator_does_not_model_is_reported_once():
    ops = [ir.Setting("following_mode", "X", c(5)), ir.Setting("following_mode", "X", c(5)),
           ir.Setting("following_mode", "X", c(0)), ir.Setting("trace", "X", c(1))]
    trace = simulate(module(ops))
    assert [d.code for d in trace.diagnostics] == ["S014"]
    assert "following" in trace.diagnostics[0].message


def test_a_limit_switch_stops_the_run_with_the_line_of_the_move():
    scenario = Scenario(axes={"X": AxisSwitches(limit_plus=3000)})
    ops = [speed("X", 1000), *accel("X", 1e9), move("X", 5000, line=7), ir.WaitMotion("X")]
    trace = simulate(module(ops), scenario)
    assert trace.stopped == "error"
    (diag,) = trace.diagnostics
    assert diag.code == "S004" and diag.span.line == 7
    assert trace.axes["X"] == pytest.approx(3000)


def test_stop_with_a_ramp_decelerates_and_abort_stops_at_once():
    ramp = [speed("X", 1000), *accel("X", 1000), ir.Slew("X", ir.Const(1000, U.STEPS_PER_S)),
            ir.Delay(c(2, U.S)), ir.Stop("X", True), ir.WaitMotion("X")]
    trace = simulate(module(ramp))
    # 1 s ramp (500) + 1 s at speed (1000), then 1 s down (500)
    assert trace.time == pytest.approx(3.0) and trace.axes["X"] == pytest.approx(2000)
    abort = ramp[:-2] + [ir.Stop("X", False), ir.WaitMotion("X")]
    trace = simulate(module(abort))
    assert trace.time == pytest.approx(2.0) and trace.axes["X"] == pytest.approx(1500)


def test_int32_variables_wrap_and_divide_toward_zero():
    ops = [ir.Assign(ir.Var("A"), c(2 ** 31 - 1)), ir.Assign(ir.Var("A"), ir.BinOp("+", ir.Var("A"), c(1))),
           ir.Assign(ir.Var("B"), ir.BinOp("/", c(-7), c(2))), ir.Assign(ir.Var("C"), ir.BinOp("%", c(-7), c(2)))]
    trace = simulate(module(ops, variables={"A": ir.VarType.INT32, "B": ir.VarType.INT32, "C": ir.VarType.INT32}))
    assert trace.variables == {"A": -(2 ** 31), "B": -3, "C": -1}


def test_float_and_decimal_variables_keep_fractions():
    ops = [ir.Assign(ir.Var("F"), ir.BinOp("/", c(10), c(4.0))),
           ir.Assign(ir.Var("D"), ir.BinOp("/", ir.BinOp("+", ir.Var("D"), c(10)), c(3)))]
    trace = simulate(module(ops, variables={"F": ir.VarType.FLOAT64, "D": ir.VarType.DECIMAL}))
    assert trace.variables == {"F": 2.5, "D": 3.333333}


def test_x150_variables_default_to_decimal():
    ops = [ir.Assign(ir.Var("VAR1"), ir.BinOp("/", ir.BinOp("+", ir.Var("VAR1"), c(7)), c(2)))]
    trace = simulate(module(ops, dialect="x150"))
    assert trace.variables["VAR1"] == 3.5


def test_division_by_zero_stops_with_its_line():
    ops = [ir.Assign(ir.Var("V1"), ir.BinOp("/", c(1), ir.Var("V2")), at(9))]
    trace = simulate(module(ops))
    assert trace.stopped == "error" and "line 9" in trace.reason
    assert [d.code for d in trace.diagnostics] == ["S002"]


def test_an_error_handler_catches_the_error_and_the_program_goes_on():
    handler = sub("OOPS", [ir.SetOutput(8, c(1))])
    ops = [ir.SetHandler("error", "OOPS"), ir.Assign(ir.Var("V1"), ir.BinOp("/", c(1), c(0))), ir.SetOutput(1, c(1))]
    trace = simulate(module(ops, routines=(handler,)))
    assert trace.stopped == "end" and trace.outputs == {8: 1, 1: 1}


def test_recursion_overflows_the_stack_at_the_profile_limit():
    recurse = sub("S1", [ir.Call("S1", span=at(12))])
    trace = simulate(module([ir.Call("S1")], routines=(recurse,)), options=Options(nesting=5))
    assert trace.stopped == "error" and trace.diagnostics[0].code == "S003"
    assert len(kinds(trace, "call")) == 6  # the sixth call does not fit


def test_calls_return_to_the_next_operation():
    s1 = sub("S1", [ir.Assign(ir.Var("V1"), ir.BinOp("+", ir.Var("V1"), c(1)))])
    trace = simulate(module([ir.Call("S1"), ir.Call("S1"), ir.SetOutput(1, ir.Var("V1"))], routines=(s1,)))
    assert trace.variables["V1"] == 2 and trace.outputs == {1: 1}


def test_an_input_handler_interrupts_a_delay():
    handler = sub("TRIP", [ir.SetOutput(2, c(1))])
    ops = [ir.SetHandler("input", "TRIP", (c(1), c(1))), ir.Setting("handler_enable", "1", c(1)), ir.Delay(c(5, U.S))]
    trace = simulate(module(ops, routines=(handler,), dialect="mcode"), Scenario(events=[InputEvent(1, 1, at=2)]))
    (output,) = kinds(trace, "output")
    assert output.t == 2 and trace.time == 5


def test_a_one_shot_handler_fires_once():
    """An MCode trip (SetHandler once, gated) fires once and must be re-enabled (TE, L5667)."""
    handler = sub("TRIP", [ir.Assign(ir.Var("N"), ir.BinOp("+", ir.Var("N"), c(1)))])
    trip = ir.SetHandler("input", "TRIP", (c(1), c(1)), once=True, gated=True)
    ops = [trip, ir.Setting("handler_enable", "1", c(1)), ir.Delay(c(5, U.S))]
    pulses = [InputEvent(1, v, at=t) for t, v in ((1, 1), (2, 0), (3, 1))]
    trace = simulate(module(ops, routines=(handler,), dialect="mcode"), Scenario(events=pulses))
    assert trace.variables["N"] == 1


def test_the_handler_facts_come_from_the_ir_not_the_dialect():
    """The same handler without `once` fires on every pulse, whatever the module's dialect."""
    handler = sub("TRIP", [ir.Assign(ir.Var("N"), ir.BinOp("+", ir.Var("N"), c(1)))])
    pulses = [InputEvent(1, v, at=t) for t, v in ((1, 1), (2, 0), (3, 1))]
    for dialect in ("mcode", "arcus", "x150"):
        ops = [ir.SetHandler("input", "TRIP", (c(1), c(1))), ir.Delay(c(5, U.S))]
        trace = simulate(module(ops, routines=(handler,), dialect=dialect), Scenario(events=pulses))
        assert trace.variables["N"] == 2, dialect


def test_a_gated_handler_waits_for_its_enable_bit():
    """A gated trip installed without TE does not fire (TE default 0, disabled, L5670)."""
    handler = sub("TRIP", [ir.SetOutput(2, c(1))])
    ops = [ir.SetHandler("input", "TRIP", (c(1), c(1)), once=True, gated=True), ir.Delay(c(5, U.S))]
    trace = simulate(module(ops, routines=(handler,), dialect="mcode"), Scenario(events=[InputEvent(1, 1, at=2)]))
    assert kinds(trace, "output") == []


def test_a_when_handler_runs_when_its_condition_becomes_true():
    handler = sub("W", [ir.SetOutput(4, c(1))], kind=ir.RoutineKind.HANDLER)
    ops = [ir.SetHandler("when", "W", (eq(inp(5), 1),)), ir.Delay(c(3, U.S))]
    trace = simulate(module(ops, routines=(handler,), dialect="x150"), Scenario(events=[InputEvent(5, 1, at=1)]))
    assert [e.t for e in kinds(trace, "output")] == [1]


def test_a_time_handler_fires_once():
    handler = sub("T", [ir.SetOutput(6, c(1))])
    ops = [ir.SetHandler("time", "T", (c(0.25, U.S),)), ir.Delay(c(1, U.S))]
    trace = simulate(module(ops, routines=(handler,)))
    assert [e.t for e in kinds(trace, "output")] == [0.25]


def test_the_time_limit_stops_an_endless_wait():
    loop = ("l", [ir.Delay(c(1, U.S))], ir.Jump("l"))
    trace = simulate(module(loop), options=Options(until=10))
    assert trace.stopped == "time-limit" and trace.time == 10


def test_the_step_limit_stops_a_loop_that_never_waits():
    loop = ("l", [ir.Assign(ir.Var("V1"), ir.BinOp("+", ir.Var("V1"), c(1)))], ir.Jump("l"))
    trace = simulate(module(loop), options=Options(max_steps=500))
    assert trace.stopped == "step-limit" and trace.steps == 500


def test_outputs_from_a_mask_and_a_pattern():
    ops = [ir.SetOutput(None, c(0b101)), ir.SetOutput(None, ir.Pattern("X1X0"))]
    trace = simulate(module(ops))
    assert {n: v for n, v in trace.outputs.items() if v} == {1: 1, 2: 1, 3: 1}  # X keeps output 3


def test_a_module_that_breaks_the_contract_is_refused_naming_the_violation():
    bad = module([ir.Delay(ir.Const(250, U.MS))])
    with pytest.raises(ContractError, match="dialect unit 'ms'"):
        simulate(bad)


def test_a_call_to_an_external_routine_stops_with_s005():
    m = module([ir.Call("SEQ5", span=at(3))])
    m.externals.append("SEQ5")
    trace = simulate(m)
    assert trace.stopped == "error" and trace.diagnostics[0].code == "S005"


def test_the_documentation_demo_runs_three_cycles():
    import demo_program as demo

    trace = simulate(demo.program(), demo.scenario(), Options(until=30))
    assert trace.stopped == "end" and trace.variables["V1"] == 3
    # X homes as Arcus HOMEX- does (arcus-pmx-4ex-sa.txt L662): 0 at the switch, then it brakes
    # (8000² - 400²) / (2 · 20000) = 1596 steps past it, so the first cycle starts at -1596
    assert trace.time == pytest.approx(8.887, abs=0.01)
    assert [e.data["value"] for e in kinds(trace, "output")] == [1, 0] * 3
    assert trace.prints[-1][1] == "cycles: 3\n"


def test_the_nesting_limit_comes_from_the_profile():
    from mcc.compiler.profiles import Profile

    profile = Profile("tiny", "arcus", "test", data={"limits": {"nesting": 3}})
    recurse = sub("S1", [ir.Call("S1")])
    trace = simulate(module([ir.Call("S1")], routines=(recurse,)), profile=profile)
    assert trace.stopped == "error" and "3 calls deep" in trace.reason


def test_a_loop_that_keeps_commanding_the_same_slew_lets_time_pass():
    # like MCode's analog speed sample: the loop re-commands the slew and reads an input
    loop = ("l", [ir.Slew("X", ir.Const(500, U.STEPS_PER_S)), ir.Call("S1")],
            ir.Branch(eq(inp(3), 1), "done", "l"))
    done = ("done", [ir.Stop("X", True), ir.WaitMotion("X")], ir.End())
    s1 = sub("S1", [ir.Assign(ir.Var("V1"), c(7))])
    trace = simulate(module(loop, done, routines=(s1,)), Scenario(events=[InputEvent(3, 1, at=4.0)]))
    assert trace.stopped == "end"
    # the default deceleration is 10 rev/s² = 40,000 steps/s² at 4000 steps/rev: 500 steps/s stop in 0.0125 s
    assert trace.time == pytest.approx(4.0125)
    assert len(kinds(trace, "slew")) == 1
    without_input = simulate(module(loop, done, routines=(s1,)), options=Options(until=20))
    assert without_input.stopped == "time-limit" and without_input.axes["X"] > 9000


def test_moves_still_running_when_the_program_ends_finish():
    trace = simulate(module([speed("X", 1000), *accel("X", 1e9), move("X", 3000), ir.SetOutput(1, c(1))]))
    assert trace.stopped == "end" and trace.time == pytest.approx(3.0) and trace.axes["X"] == 3000


def racy_loop(rotated: bool) -> ir.Module:
    """A loop that reads input 1 into V1 and leaves when the input is above V1 at the test: it leaves
    only if the input rises between the read and the test (a race on a real controller). The
    rotated form is what a structurer may write: the same reads and test, round at another point."""
    v1 = ir.Var("V1")
    read, test = ir.Assign(v1, inp(1)), ir.Compare("<", v1, inp(1))
    if rotated:
        return module(("r", [read], ir.Jump("t")), ("t", [], ir.Branch(test, "x", "back")),
                      ("back", [], ir.Jump("r")), ("x", [ir.SetOutput(1, c(1))], ir.End()), variables={"V1": VarType.INT32})
    return module(("e", [], ir.Jump("r")), ("t", [], ir.Branch(test, "x", "r")), ("r", [read], ir.Jump("t")),
                  ("x", [ir.SetOutput(1, c(1))], ir.End()), variables={"V1": VarType.INT32})


def test_a_race_between_two_reads_of_a_polling_round_is_not_a_divergence():
    pulse = [Scenario(name="pulse", events=[InputEvent(1, 1, at=0.5), InputEvent(1, 0, at=0.6)])]
    source, rotated = racy_loop(False), racy_loop(True)
    a, b = simulate(source, pulse[0]), simulate(rotated, pulse[0])
    assert a.stopped != b.stopped  # the one interleaving each run takes differs ...
    # ... and the source takes the other way when time passes at another point of its round
    assert any(simulate(source, pulse[0], Options(poll_offset=k)).stopped == b.stopped for k in range(1, 4))
    assert compare(source, rotated, pulse) is None
    # a program that does what no interleaving of the source does is still found
    assert compare(source, module([ir.SetOutput(2, c(1))]), pulse) is not None


def test_a_value_a_variable_cannot_hold_is_the_runs_error_not_a_crash():
    """X150 variables hold decimals within the manual's range; 65536 multiplied in nine times does
    not fit: the run stops with S002 on its line, also when the validation runs it (a fuzz finding,
    bench/findings/x150-verify-arithmetic-fault.x150, escaped as an internal error)."""
    ops = [ir.Assign(ir.Var("VAR1"), c(65536 ** 5), at(7))]
    trace = simulate(module(ops, dialect="x150"))
    assert trace.stopped == "error" and "line 7" in trace.reason
    assert [d.code for d in trace.diagnostics] == ["S002"]
