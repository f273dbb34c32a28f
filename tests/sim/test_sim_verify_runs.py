"""A validation simulates a scenario only when it can differ from one already run (sim/verify.Runs).

The scenarios of a validation share their start (all inputs low, then each input toggling after the
program's first wait): a program that ends, or loops at one instant up to the step limit, before
any toggle does the same under all of them, and was simulated once per scenario and side (an X150
homing loop: 16 runs of 200,000 operations). A run is reused only for a scenario that does the same
up to the time that run stopped; a run that stopped waiting for a change is never reused, so a
program that differs only after an input changes is still caught.
"""

from __future__ import annotations

import pytest

from mcc.compiler import ir
from mcc.sim import verify
from mcc.sim.scenario import Incident, InputEvent, Scenario
from sim_helpers import c, eq, inp, module


def test_same_until_compares_only_what_happens_up_to_the_time():
    start = Scenario(inputs={1: 0, 2: 0})
    late = Scenario(inputs={1: 0, 2: 0}, events=[InputEvent(1, 1, at=2.5)])
    assert verify.same_until(start, late, 1.0) and verify.same_until(late, start, 2.49)
    assert not verify.same_until(start, late, 2.5)  # an event at the time itself counts
    assert not verify.same_until(start, Scenario(inputs={1: 1, 2: 0}), 0.0)  # another start
    assert not verify.same_until(start, Scenario(inputs={1: 0, 2: 0}, events=[InputEvent(1, 1, axis="X", passes=5)]),
                                 0.0)  # an event at a position may come at any time
    assert not verify.same_until(start, Scenario(inputs={1: 0, 2: 0}, incidents=[Incident("stall", 0.5, "X")]), 1.0)
    assert verify.same_until(start, Scenario(inputs={1: 0, 2: 0}, incidents=[Incident("stall", 1.5, "X")]), 1.0)


def counted(monkeypatch) -> list:
    calls = []
    original = verify.simulate

    def simulate(module, scenario, *args, **kwargs):
        calls.append(scenario.name)
        return original(module, scenario, *args, **kwargs)

    monkeypatch.setattr(verify, "simulate", simulate)
    return calls


def test_a_program_that_ends_before_any_toggle_is_run_once_per_start(monkeypatch):
    """It reads inputs 1 and 2 and ends at once: the two toggling scenarios start as `inputs low`."""
    program = module([ir.SetOutput(1, ir.BinOp("+", inp(1), inp(2))), ir.SetOutput(2, c(1))])
    calls = counted(monkeypatch)
    assert verify.compare(program, program) is None
    names = [name for name in calls if "toggles" in name]
    assert names == [] and len(calls) == 2 * 4  # low, high, 1 high, 2 high; each on both sides


def test_a_difference_after_an_input_change_is_still_found():
    """Both wait for input 1 (a run that stops waiting is never reused); the output then sets
    another output: only the scenarios where the input rises show it."""
    source = module([ir.WaitInput(eq(inp(1), 1)), ir.SetOutput(1, c(1))])
    output = module([ir.WaitInput(eq(inp(1), 1)), ir.SetOutput(2, c(1))])
    found = verify.compare(source, output)
    assert found is not None


@pytest.mark.parametrize("stop_at", [0.05, 0.5])
def test_a_difference_after_the_program_ended_is_not_there(stop_at):
    """A program that ended at `stop_at` does nothing after: the toggles cannot change its run,
    reused or not, and the verdict is the one of simulating every scenario."""
    program = module([ir.Delay(c(stop_at, ir.Unit.S)), ir.SetOutput(1, inp(1))])
    reused = verify.compare(program, program)
    scenarios = verify.default_scenarios(program)
    each = [verify.compare(program, program, [s]) for s in scenarios]
    assert reused is None and each == [None] * len(scenarios)


def test_one_source_against_many_outputs_is_simulated_once_per_scenario(monkeypatch):
    """`compare(..., source_runs=)`: the optimizer's tests compare one source with every level's
    output. The source's runs are shared, and an output that differs is still found."""
    source = module([ir.WaitInput(eq(inp(1), 1)), ir.SetOutput(1, c(1))])
    same = module([ir.WaitInput(eq(inp(1), 1)), ir.SetOutput(1, c(1))])
    wrong = module([ir.WaitInput(eq(inp(1), 1)), ir.SetOutput(2, c(1))])
    scenarios = verify.default_scenarios(source)
    runs = verify.Runs(source, None)
    assert verify.compare(source, same, scenarios, source_runs=runs) is None
    calls = counted(monkeypatch)
    assert verify.compare(source, wrong, scenarios, source_runs=runs) is not None
    assert calls and all(name in {s.name for s in scenarios} for name in calls)
    sources = len(calls)
    calls.clear()
    assert verify.compare(source, same, scenarios, source_runs=runs) is None
    assert len(calls) == len(scenarios) and sources >= 1  # only the output's runs: the source's are kept


def test_runs_of_another_module_are_not_used():
    """A `Runs` made for another module (or profile) is ignored: its traces are not this source's."""
    source = module([ir.SetOutput(1, c(1))])
    other = module([ir.SetOutput(2, c(1))])
    runs = verify.Runs(other, None)
    assert verify.compare(other, other, source_runs=runs) is None
    assert verify.compare(source, other, source_runs=runs) is not None
