"""Delay-paced polling loops: the rounds that cannot differ are jumped over, with the same result.

A loop such as `WHILE DI1=0 / DELAY=5 / ENDWHILE` goes round 200 times a virtual second. The
simulator jumps over the rounds that start from the same state as the one just run
(`Simulator._went_round`, docs/SIMULATOR.md "Time"); these tests hold it to giving exactly the
trace that running every round gives, and to a cost that does not grow with the polling rate.
"""

from __future__ import annotations

import pytest

from mcc.compiler import ir
from mcc.sim import Options
from mcc.sim.interpreter import Simulator
from mcc.sim.scenario import InputEvent, Scenario
from sim_helpers import c, eq, inp, module, move, speed, accel, sub

U = ir.Unit


def delay(seconds: float) -> ir.Delay:
    return ir.Delay(c(seconds, U.S))


def poller(period: float, extra=()) -> ir.Module:
    """Wait for input 1 polling every `period` s, pulse output 1 for 0.2 s, count, go round."""
    count = ir.Assign(ir.Var("V1"), ir.BinOp("+", ir.Var("V1"), c(1)))
    return module(
        ("wait", [*extra, delay(period)], ir.Branch(eq(inp(1), 0), "wait", "act")),
        ("act", [ir.SetOutput(1, c(1)), delay(0.2), ir.SetOutput(1, c(0)), count], ir.Jump("wait")),
        variables={"V1": ir.Variable("V1")})


def pulses(every: float, until: float) -> Scenario:
    events, t = [], every
    while t < until:
        events += [InputEvent(1, 1, at=t), InputEvent(1, 0, at=t + 0.1)]
        t += every
    return Scenario(events=events)


def run(mod: ir.Module, scenario: Scenario, skip: bool, **options) -> Simulator:
    sim = Simulator(mod, scenario, Options(skip_rounds=skip, **options))
    sim.run()
    return sim


def same(a: Simulator, b: Simulator) -> None:
    ta, tb = a.trace, b.trace
    assert (ta.stopped, ta.time, ta.steps, ta.variables, ta.prints) == (tb.stopped, tb.time, tb.steps, tb.variables,
                                                                          tb.prints)
    assert [(e.t, e.kind, e.line, e.data) for e in ta.events] == [(e.t, e.kind, e.line, e.data) for e in tb.events]
    assert ta.cycle_marks == tb.cycle_marks  # the passes of the main loop (`mcc sim`'s cycle time)


@pytest.mark.parametrize("period", [0.005, 0.01, 0.05, 0.003])
def test_jumping_over_quiet_rounds_gives_the_trace_of_running_every_round(period):
    scenario = pulses(7.3, 120.0)
    fast, slow = run(poller(period), scenario, True, until=120.0), run(poller(period), scenario, False, until=120.0)
    same(fast, slow)
    assert fast.skipped > 0
    assert fast.trace.variables["V1"] == 16  # one count per pulse: 7.3, 14.6, ... 116.8


def test_a_polling_round_costs_the_same_whatever_its_period():
    """An hour of polling every 1 ms or every 100 ms runs about as many operations."""
    scenario = pulses(60.0, 3600.0)
    executed = []
    for period in (0.001, 0.1):
        sim = run(poller(period), scenario, True, until=3600.0, max_steps=10 ** 9)
        executed.append(sim.trace.steps - sim.skipped)
        assert sim.trace.variables["V1"] == 59
    assert max(executed) < 2000
    assert executed[0] < 2 * executed[1] + 200


def test_the_step_limit_stops_a_skipping_run_where_it_stops_a_running_one():
    scenario = pulses(50.0, 600.0)
    fast = run(poller(0.005), scenario, True, until=600.0, max_steps=5000)
    slow = run(poller(0.005), scenario, False, until=600.0, max_steps=5000)
    assert fast.trace.stopped == "step-limit"
    same(fast, slow)


def test_a_round_that_reads_a_moving_position_is_not_skipped():
    """The position changes with time, so each round may go another way (L: it is read each round)."""
    read = ir.Assign(ir.Var("V2"), ir.Status("position", axis="X"))
    mod = module(
        ("go", [speed("X", 100), *accel("X", 1000), move("X", 1000)], ir.Jump("wait")),
        ("wait", [read, delay(0.01)], ir.Branch(ir.Compare("<", ir.Var("V2"), c(500)), "wait", "done")),
        ("done", [ir.SetOutput(1, c(1))], ir.End()),
        variables={"V1": ir.Variable("V1"), "V2": ir.Variable("V2")})
    fast, slow = run(mod, Scenario(), True, until=30.0), run(mod, Scenario(), False, until=30.0)
    same(fast, slow)


def test_a_round_that_reads_the_timer_is_not_skipped():
    read = ir.Assign(ir.Var("V2"), ir.Status("timer", index=1))
    mod = module(("wait", [read, delay(0.01)], ir.Branch(ir.Compare("<", ir.Var("V2"), c(5)), "wait", "done")),
                 ("done", [ir.SetOutput(1, c(1))], ir.End()),
                 variables={"V1": ir.Variable("V1"), "V2": ir.Variable("V2")})
    fast, slow = run(mod, Scenario(), True, until=30.0), run(mod, Scenario(), False, until=30.0)
    same(fast, slow)
    assert fast.skipped == 0


def test_a_round_that_calls_a_subroutine_is_not_skipped_and_matches():
    """Calls leave events in the trace, so such rounds run one by one."""
    mod = poller(0.01, extra=[ir.Call("S")])
    mod.routines.append(sub("S", [ir.Assign(ir.Var("V3"), c(7))]))
    mod.variables["V3"] = ir.Variable("V3")
    scenario = pulses(3.1, 20.0)
    fast, slow = run(mod, scenario, True, until=20.0), run(mod, scenario, False, until=20.0)
    same(fast, slow)


def test_a_loop_cycling_through_the_same_states_is_polling():
    """A dispatch loop (`WHILE V63!=0` with one IF arm per block, the Arcus backend's form for
    deep nests) alternates its state variable between two values while it waits for an input:
    every round differs from the last, yet the loop only cycles through states it has been in.
    It must count as polling, as its structured source `WAIT: IF DI1=0 GOTO WAIT` does, and see
    the input at the same time, not run into the step limit (tests/arcus/test_structure.py found
    it with seed 605)."""
    state = ir.Var("V63")
    mod = module(
        ("top", [], ir.Branch(eq(state, 2), "two", "three")),
        ("two", [ir.Assign(state, c(3))], ir.Jump("next")),
        ("three", [ir.Assign(state, c(2))], ir.Branch(eq(inp(1), 0), "next", "done")),
        ("next", [], ir.Jump("top")),
        ("done", [ir.SetOutput(1, c(1))], ir.End()),
        variables={"V63": ir.Variable("V63", init=c(2))})
    sim = run(mod, Scenario(events=[InputEvent(1, 1, at=5.0)]), skip=True, max_steps=20_000)
    assert sim.trace.stopped == "end", sim.trace.reason
    outputs = [e for e in sim.trace.events if e.kind == "output"]
    assert [(e.t, e.data["value"]) for e in outputs] == [(5.0, 1)]


def test_the_passes_of_a_polled_main_loop_are_counted_through_the_jump():
    """The main loop polls with a delay: each round is a pass of its header (sim/cycles.py), also
    the rounds jumped over, at the times running them gives; the cycle time says 5 ms per pass,
    not one long pass for the whole jump."""
    from mcc.sim import cycles

    scenario = pulses(7.3, 30.0)
    fast, slow = run(poller(0.005), scenario, True, until=30.0), run(poller(0.005), scenario, False, until=30.0)
    same(fast, slow)
    assert fast.skipped > 0
    assert max(cycles.timing(fast.trace).cycles) < 0.5
