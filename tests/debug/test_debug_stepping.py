"""The simulator's stepping interface (Simulator.observer) and the expressions of breakpoint
conditions, without the protocol."""

from __future__ import annotations

from pathlib import Path

import pytest

from mcc.compiler import driver
from mcc.debug import conditions
from mcc.debug.session import executable_lines
from mcc.sim.interpreter import Options, Simulator, Stop

FIXTURES = Path(__file__).parent / "fixtures"
SAMPLES = Path(__file__).resolve().parents[2] / "samples"
PROGRAMS = [FIXTURES / "loop.mxt", FIXTURES / "loop.prg", FIXTURES / "loop.x150", FIXTURES / "divide.mxt",
            FIXTURES / "waits.mxt",
            SAMPLES / "mcode" / "trip_on_input.mxt", SAMPLES / "arcus" / "drill_grid_variables.prg",
            SAMPLES / "x150" / "03_part_sorter.x150"]


def simulator(path: Path, **options) -> Simulator:
    result = driver.check_file(str(path))
    assert not result.has_errors, result.diagnostics
    return Simulator(result.analysis.module, None, Options(until=30, **options), result.profile)


@pytest.mark.parametrize("path", PROGRAMS, ids=lambda p: p.name)
def test_an_observer_that_only_watches_changes_nothing(path):
    """run() with an observer gives the very trace run() gives without one, and the observer sees
    every executed item (the count of steps) with a line from the program."""
    plain = simulator(path).run().to_json()
    watched = simulator(path)
    seen = []
    watched.observer = lambda kind, frame, item, *rest: seen.append((kind, item))
    assert watched.run().to_json() == plain
    steps = [item for kind, item in seen if kind == "step"]
    assert len(steps) == plain["steps"]
    assert all(item.span.line >= 1 for item in steps if getattr(item, "span", None) is not None)


def test_the_observer_sees_the_fault_before_the_run_stops():
    sim = simulator(FIXTURES / "divide.mxt")
    faults = []

    def observe(kind, frame, item, fault=None):
        if kind == "fault":
            faults.append((fault.code, item.span.line, dict(sim.vars)))

    sim.observer = observe
    trace = sim.run()
    assert trace.stopped == "error"
    assert faults == [("S002", 7, {"Q1": 0, "Q2": 0})]


def test_the_observer_sees_how_the_run_stopped():
    sim = simulator(FIXTURES / "waits.mxt")
    stops = []

    def observe(kind, frame, item, stop=None):
        if kind == "stop":
            stops.append((stop.stopped, frame.routine.name, dict(sim.vars)))

    sim.observer = observe
    assert sim.run().stopped == "waiting"
    assert stops == [("waiting", "A1", {"Q1": 1})]


def test_an_observer_can_end_the_run():
    sim = simulator(FIXTURES / "loop.mxt")

    def observe(kind, frame, item, fault=None):
        if kind == "step" and item.span is not None and item.span.line == 11:
            raise Stop("terminated", "the debugger ended the run")

    sim.observer = observe
    trace = sim.run()
    assert (trace.stopped, sim.vars["Q1"]) == ("terminated", 1)


def test_set_variable_and_set_input_while_paused():
    """A variable takes the variable's type (Q1 is an int32, lexium-mcode.txt VA L2802); an input
    set by the debugger holds until the scenario changes it."""
    sim = simulator(FIXTURES / "loop.mxt")
    done = []

    def observe(kind, frame, item, fault=None):
        if kind == "step" and not done and item.span is not None and item.span.line == 12:
            assert sim.set_variable("Q1", 2.7) == 2
            sim.set_input(1, 0)
            done.append(True)

    sim.observer = observe
    trace = sim.run()
    assert [text.strip() for _, text in trace.prints] == ["INPUT"]
    assert any(e.kind == "input" and e.data.get("by") == "debugger" for e in trace.events)


def test_lines_that_generate_nothing_are_not_executable():
    result = driver.check_file(str(FIXTURES / "loop.mxt"))
    lines = executable_lines(result.analysis.module, str(FIXTURES / "loop.mxt"))
    assert {6, 8, 10, 11, 12, 20}.issubset(lines)
    assert not {1, 4, 5, 19} & lines  # the comment, PG, the labels a jump never runs through


class FakeMachine(conditions.Machine):
    def __init__(self):
        super().__init__(simulator=None)

    def variable(self, name):
        table = {"Q1": 3, "V2": 2.5}
        if name.upper() in table:
            return table[name.upper()]
        if name == "time":
            return 1.5
        raise conditions.ExpressionError(f"'{name}' is not a variable")

    def call(self, name, argument):
        return {"input": 1, "output": 0, "position": 1000.0, "speed": 0.0}[name]


@pytest.mark.parametrize("text, value", [
    ("Q1 = 3", 1), ("Q1 <> 3", 0), ("Q1 >= 3 AND input(1) = 1", 1), ("q1 > 5 or NOT output(2)", 1),
    ("V2 * 2", 5.0), ("position(X) / 10", 100.0), ("time > 1", 1), ("(Q1 + 1) % 3", 1), ("-Q1", -3),
])
def test_expressions_in_the_dialects_spelling(text, value):
    assert conditions.evaluate(text, FakeMachine()) == value


@pytest.mark.parametrize("text, message", [
    ("Q1 ==", "cannot read"), ("__import__('os')", "not allowed"), ("Q1.real", "not allowed"),
    ("Q1 / 0", "divides by zero"), ("nosuch = 1", "not a variable"),
])
def test_expressions_that_are_refused_say_why(text, message):
    with pytest.raises(conditions.ExpressionError, match=message):
        conditions.evaluate(text, FakeMachine())


@pytest.mark.parametrize("text, hits, stops", [
    ("3", [1, 2, 3, 4], [False, False, True, False]), ("== 2", [2], [True]), (">= 2", [1, 2, 5], [False, True, True]),
    ("> 2", [2, 3], [False, True]), ("% 2", [1, 2, 3, 4], [False, True, False, True]),
])
def test_hit_conditions(text, hits, stops):
    assert conditions.hit_condition_error(text) is None
    assert [conditions.hit_matches(text, n) for n in hits] == stops


def test_a_hit_condition_that_cannot_be_read():
    assert "not understood" in conditions.hit_condition_error("sometimes")


def test_mcc_debug_help_explains_the_command():
    from click.testing import CliRunner

    from mcc.cli.commands import cli

    out = CliRunner().invoke(cli, ["debug", "--help"])
    assert out.exit_code == 0
    for words in ("Debug Adapter Protocol", "--port", "stopOnEntry", "hit count", "docs/EDITORS.md"):
        assert words in out.output, words
