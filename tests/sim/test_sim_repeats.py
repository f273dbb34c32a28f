"""Rounds that repeat at one instant are appended to the trace instead of run, with the same result.

A loop that prints (or homes on an active switch) over and over without waiting runs into the step
limit: 200,000 operations of every validation run. Within one stretch of the run time does not pass,
so when a jump back finds the simulator in exactly the state of an earlier one, every later round
repeats the rounds between them (sim/repeats.py, docs/SIMULATOR.md "Time"). These tests hold the
replay to the trace that running every round gives, field for field, on hand-written loops, on
random loops (hypothesis) and on generated programs of every dialect; and to running far fewer
operations. The delay-paced rounds that `_went_round` jumps over have their own tests
(test_sim_polling_rounds.py); here that jump is turned off in both runs, so that the two runs
differ only by the replay.
"""

from __future__ import annotations

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from mcc.compiler import driver, ir
from mcc.sim import Options, repeats, verify
from mcc.sim.interpreter import Simulator
from mcc.sim.scenario import Scenario
from conversion import extension
from sim_helpers import c, eq, inp, module, sub
from sim_strategy import VARS, conds, exprs

STEPS = 20_000


@pytest.fixture(autouse=True)
def every_delay_round_runs(monkeypatch):
    monkeypatch.setattr(Simulator, "_went_round", lambda self, frame: None)


def run(mod: ir.Module, scenario: Scenario | None, skip: bool, **options) -> Simulator:
    options.setdefault("max_steps", STEPS)
    sim = Simulator(mod, scenario or Scenario(), Options(skip_rounds=skip, **options))
    sim.run()
    return sim


def seen(sim: Simulator) -> tuple:
    """Everything a run leaves in its trace."""
    t = sim.trace
    return (t.stopped, t.reason, t.time, t.steps, t.variables, t.outputs, t.axes, t.prints, t.repeats_from,
            t.cycle_marks, [(e.t, e.kind, e.line, e.data) for e in t.events],
            [(d.code, d.message, d.span) for d in t.diagnostics], len(t.motion_log), t.points)


def both(mod: ir.Module, scenario: Scenario | None = None, **options) -> Simulator:
    fast, slow = run(mod, scenario, True, **options), run(mod, scenario, False, **options)
    assert seen(fast) == seen(slow)
    return fast


def counter_loop() -> ir.Module:
    """Print V1, count it 0, 1, 2, 0, ... in a subroutine, for ever, at time 0 (as the print loop
    of tests/codegen_programs.py seed 20 does, whose counter the subroutine resets)."""
    count = ir.Assign(ir.Var("V1"), ir.BinOp("+", ir.Var("V1"), c(1)))
    return module(
        ("loop", [ir.Print((ir.Text("v="), ir.Var("V1"))), ir.Call("S")],
         ir.Branch(ir.Compare("<", ir.Var("V1"), c(3)), "loop", "reset")),
        ("reset", [ir.Assign(ir.Var("V1"), c(0)), ir.SetOutput(1, c(1))], ir.Jump("loop")),
        routines=[sub("S", [count])], variables={"V1": ir.VarType.INT32})


def test_a_print_loop_at_one_instant_is_replayed_with_the_trace_of_running_it():
    fast = both(counter_loop())
    assert fast.trace.stopped == "step-limit" and fast.trace.time == 0.0
    assert len(fast.trace.prints) > 2000
    assert fast.trace.steps - fast.skipped < 6000  # the stretch before the first look, and the last rounds


def test_the_step_limit_stops_a_replayed_run_at_the_same_operation():
    """Whatever the limit, the last rounds run: the same operation stops the run, with its line."""
    for limit in (4100, 4107, 9999, 50_001):
        fast = both(counter_loop(), max_steps=limit)
        assert fast.trace.steps == limit


def countdown(start: int | None, until: int = 0, step: int = 1, body=None) -> ir.Module:
    """`L = start` (none when None), then print and `L = L - step` while `L != until`: X150's `L`
    loop (lowered as a hidden counter, compiler/x150/lower.py; parker-x150.md L2328, `L` or `L0`
    loops for ever), or a loop of `start` rounds."""
    set_ = [ir.Assign(ir.Var("L"), c(start))] if start is not None else []
    count = ir.Assign(ir.Var("L"), ir.BinOp("-", ir.Var("L"), c(step)))
    return module(
        ("init", set_, ir.Jump("loop")),
        ("loop", [*(body or [ir.Print((ir.Text("x"),))]), count],
         ir.Branch(ir.Compare("!=", ir.Var("L"), c(until)), "loop", "done")),
        ("done", [ir.Print((ir.Text("done"),))], ir.End()),
        variables={"L": ir.VarType.INT32})


def test_a_loop_whose_only_change_is_a_counter_is_replayed():
    """`%L1 = %L1 - 1` until it is 0, from 0 (X150's `L` without a count, parker-x150.md L2328):
    no state repeats, but the rounds differ only by the counter, which is compared with 0 only
    and never comes back to it: replayed, with the counter where running every round leaves it."""
    fast = both(countdown(None))
    assert fast.skipped > 0 and fast.trace.steps - fast.skipped < 6000
    assert fast.trace.variables["L"] == -(STEPS - 2) // 3  # 3 operations a round, after the first 2


def test_a_counter_replayed_in_a_loop_that_adds_a_state_each_round():
    """No print, only the counter changes: `_execute` adds the loop's state to its round states
    each round (parker-x150.md L2328, `L` ... `N` with an idle body): the replay leaves them as
    running every round does, emptied when full, and the run then goes on the same."""
    for limit in (STEPS, 4100 + 256 * 3, 33_333):
        fast = both(countdown(None, body=[ir.Assign(ir.Var("V1"), c(7))]), max_steps=limit)
        assert fast.skipped > 0


def test_a_counter_stops_being_replayed_before_the_constant_it_is_compared_with():
    """A count of 100 rounds (parker-x150.md L2328, `L100`), and of 4,000 by steps of 3 from
    12,000: the replay stops short of the loop's exit, which comes at the step that running every
    round gives, and the program goes on after it."""
    for start, step in ((100, 1), (4000, 1), (12_000, 3)):
        fast = both(countdown(start, step=step))
        assert fast.trace.stopped == "end" and fast.trace.prints[-1] == (0.0, "done\n")
        assert len(fast.trace.prints) == start // step + 1
    assert both(countdown(4000)).skipped > 0


def test_a_counter_compared_where_the_replay_would_cross_it_is_not_skipped_over():
    """`L != -5000` from 0: replayed up to it, run across it, and the loop leaves there."""
    fast = both(countdown(None, until=-5000))
    assert fast.trace.prints.count((0.0, "x\n")) == 5000 and fast.trace.prints[-1] == (0.0, "done\n")


def test_a_counter_read_otherwise_is_no_counter():
    """Printed, or used in arithmetic, the counter's value reaches the trace: not replayed (no
    state repeats), the same trace either way."""
    printed = countdown(None, body=[ir.Print((ir.Text("L="), ir.Var("L")))])
    summed = countdown(None, body=[ir.Assign(ir.Var("V1"), ir.BinOp("+", ir.Var("L"), c(1)))])
    scaled = module(
        ("loop", [ir.Print((ir.Text("x"),)), ir.Assign(ir.Var("L"), ir.BinOp("*", ir.Var("L"), c(1))),
                  ir.Assign(ir.Var("L"), ir.BinOp("-", ir.Var("L"), c(1)))],
         ir.Branch(ir.Compare("!=", ir.Var("L"), c(0)), "loop", "loop")),
        variables={"L": ir.VarType.INT32})
    for mod in (printed, summed, scaled):
        assert not repeats.counters_of(mod, lambda name: ir.VarType.INT32)
        assert both(mod).skipped == 0


def test_a_counter_reset_in_the_round_is_not_replayed():
    """A loop that resets its counter each round (`L = 0` on the way back): the counter is not
    moved on by the replay; the rounds repeat as whole states instead."""
    mod = module(
        ("loop", [ir.Print((ir.Text("x"),)), ir.Assign(ir.Var("L"), c(0)),
                  ir.Assign(ir.Var("L"), ir.BinOp("-", ir.Var("L"), c(1)))],
         ir.Branch(ir.Compare("!=", ir.Var("L"), c(5)), "loop", "done")),
        ("done", [], ir.End()),
        variables={"L": ir.VarType.INT32})
    fast = both(mod)
    assert fast.skipped > 0 and fast.trace.variables["L"] == -1


def test_a_counter_whose_steps_go_both_ways_is_not_moved_on():
    """`L = L - 2` then `L = L + 1`: a round moves it by -1 but passes values beyond its ends;
    the replay leaves it alone (the trace is the same either way)."""
    mod = countdown(None, body=[ir.Print((ir.Text("x"),)), ir.Assign(ir.Var("L"), ir.BinOp("+", ir.Var("L"), c(1))),
                                ir.Assign(ir.Var("L"), ir.BinOp("-", ir.Var("L"), c(1)))])
    assert both(mod).skipped == 0


def outer_loop(start: int) -> ir.Module:
    """An endless outer loop that sets the counter L to `start`, then an inner loop that prints and
    counts it down until it is 0."""
    return module(
        ("outer", [ir.Assign(ir.Var("L"), c(start))], ir.Jump("loop")),
        ("loop", [ir.Print((ir.Text("x"),)), ir.Assign(ir.Var("L"), ir.BinOp("-", ir.Var("L"), c(1)))],
         ir.Branch(ir.Compare("!=", ir.Var("L"), c(0)), "loop", "after")),
        ("after", [ir.Print((ir.Text("after"),))], ir.Jump("outer")),
        variables={"L": ir.VarType.INT32})


def test_a_counter_in_an_outer_loop_that_resets_it():
    """X150 `REPEAT ... L ... N ... UNTIL` (parker-x150.md L2328): the reset `L = 0` is in the outer
    loop, which the inner endless loop never leaves (its exit needs the counter at 0): replayed."""
    assert both(outer_loop(0)).skipped > 0


def test_an_outer_loop_through_a_counted_inner_loop():
    """An inner loop of 3 rounds (`L3`) in an endless outer loop: the counter is reset each outer
    round and ends each at 0, so the outer rounds repeat as whole states."""
    assert both(outer_loop(3)).skipped > 0


def test_rounds_that_wait_are_not_replayed():
    """Time passes in each round (a delay): the state is never the same at one instant."""
    mod = module(("loop", [ir.SetOutput(1, c(1)), ir.Delay(c(0.001, ir.Unit.S)), ir.SetOutput(1, c(0))],
                  ir.Jump("loop")))
    fast = both(mod, until=5.0)
    assert fast.skipped == 0


def test_an_input_read_each_round_at_one_instant_repeats():
    """An input does not change while time stands still: a loop printing it repeats."""
    mod = module(("loop", [ir.Print((ir.Text("i="), inp(1)))], ir.Branch(eq(inp(1), 5), "done", "loop")),
                 ("done", [], ir.End()))
    fast = both(mod, Scenario(inputs={1: 1}))
    assert fast.skipped > 0


def test_no_replay_under_a_debugger():
    """A debugger's observer sees every operation run."""
    sim = Simulator(counter_loop(), Scenario(), Options(max_steps=STEPS))
    steps = []
    sim.observer = lambda kind, frame, item, *rest: steps.append(kind)
    sim.run()
    assert sim.skipped == 0 and steps.count("step") == STEPS + 1  # (and the one the limit refuses)


@st.composite
def loops(draw):
    """A main loop at one instant: random assignments, prints, outputs and calls of a subroutine
    that changes the variables too, going round on a random condition or through a second block
    that brings a variable back into a range (so that some states come back and some never do).
    With a counter `L` too (X150's `L` loops, parker-x150.md L2328): stepped by a whole constant,
    mostly down, compared with constants in the loop's condition, sometimes reset in the second
    block, now and then printed (then it is no counter)."""
    def body(size: int) -> list:
        made = []
        for _ in range(draw(st.integers(0, size))):
            kind = draw(st.sampled_from(["assign", "assign", "print", "output", "call", "count", "count"]))
            if kind == "assign":
                made.append(ir.Assign(ir.Var(draw(st.sampled_from(VARS))), draw(exprs(depth=1))))
            elif kind == "print":
                made.append(ir.Print((ir.Text("v="), ir.Var(draw(st.sampled_from((*VARS, "L")))))))
            elif kind == "output":
                made.append(ir.SetOutput(draw(st.integers(1, 3)), ir.BinOp("&", ir.Var(draw(st.sampled_from(VARS))),
                                                                            c(1))))
            elif kind == "count":
                made.append(ir.Assign(ir.Var("L"), ir.BinOp(draw(st.sampled_from(["-", "-", "+"])), ir.Var("L"),
                                                             c(draw(st.integers(0, 3))))))
            else:
                made.append(ir.Call("S"))
        return made
    var = draw(st.sampled_from(VARS))
    wrap = ir.Assign(ir.Var(var), ir.BinOp("%", ir.Var(var), c(draw(st.integers(2, 7)))))
    reset = [ir.Assign(ir.Var("L"), c(draw(st.integers(-20, 20))))] if draw(st.booleans()) else []
    counted = ir.Compare(draw(st.sampled_from(["=", "!=", "<", ">=", ">"])), ir.Var("L"),
                         c(draw(st.integers(-3000, 20))))
    cond = draw(st.sampled_from([draw(conds()), counted, ir.Logic("and", counted, draw(conds()))]))
    return module(
        ("loop", body(5), ir.Branch(cond, "loop", "wrap")),
        ("wrap", [wrap, *reset, *body(2)], ir.Jump("loop")),
        routines=[sub("S", body(3))], variables={v: ir.VarType.INT32 for v in (*VARS, "L")})


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(loops())
def test_random_loops_give_the_trace_of_running_every_round(mod):
    both(mod, max_steps=12_000)


@pytest.mark.parametrize("dialect, seed", [("mcode", 20), ("mcode", 3), ("arcus", 20), ("x150", 20)])
def test_generated_programs_give_the_trace_of_running_every_round(dialect, seed):
    """The random programs of tests/codegen_programs.py under every scenario validation runs them
    in (mcode seed 20 is a print loop that never waits: replayed)."""
    from codegen_programs import generate
    from test_codegen_random import enabled

    text = generate(dialect, seed, enabled(dialect)).text
    result = driver.compile_file(f"g{extension(dialect)}", dialect, text=text, opt_level="O0")
    mod = result.analysis.module
    replayed = 0
    for scenario in verify.default_scenarios(mod):
        # (a quarter of validation's step limit: the replay starts after 4,096 steps all the same)
        options = verify.default_options(scenario)
        fast = both(mod, scenario, until=options.until, max_steps=options.max_steps // 4, samples=False)
        replayed += fast.skipped > 0
    assert replayed or (dialect, seed) != ("mcode", 20)


def test_the_states_a_replayed_counter_loop_went_round_in_are_those_of_running_it():
    """After the replay the loop leaves (`L` reaches -3000) and goes round again from -2990
    through states it went round in before: running every round, `_execute` finds them among the
    states it keeps and takes the loop for a quiet one (a poll); the replay leaves those states as
    running every round does, so the poll comes at the same step (parker-x150.md L2328, `L` ... `N`
    in a loop that sets the counter back)."""
    for start, limit in ((None, STEPS), (None, 30_001), (-1000, STEPS)):
        mod = countdown(start, until=-3000, body=[ir.Assign(ir.Var("V1"), c(7))])
        mod.routines[0].blocks[2] = ir.Block("done", [ir.Assign(ir.Var("L"), c(-2990))], ir.Jump("loop"))
        fast = both(mod, max_steps=limit, until=1.0)
        assert fast.skipped > 0 and "polls in a loop" in fast.trace.reason


# An idle homing in an endless `L ... N` (parker-x150.md L2328: `L` with no number repeats for
# ever), as tests/golden/x150/policy-ok writes it: `1G` with no distance, at one instant.
X150_IDLE_LOOP = """1CUR800
1SIM5
1XE1
1XD1
1BCUR800
1BCPE2000
1PZ
1L
1G
1BY
1N
1XT
1SV
"""
# A generated program (tests/x150/test_x150_generated.py, `Program(random.Random(254), "")`):
# an endless `L N` inside a sequence, and one that calls another sequence (`XR53`) in its body,
# both inside the loops of an outer REPEAT that resets their counters.
X150_GENERATED = """A10
MC
VAR4=VAR1-VAR2*VAR3
D4000
IF(VAR1>5 AND VAR1=VAR2)
ELSE
WHILE(IN_1 OR VAR2<3)
VAR3=VAR1+2
VAR4=VAR1-VAR2*VAR3
REPEAT
L
DCLR0
GH-2
VAR4=VAR1-VAR2*VAR3
N
D(VAR3)
T0.2
UNTIL(VAR2<3)
T(VAR1)
NWHILE
WHILE(IN_X01)
NWHILE
MN
NIF
XE33
XD33
L
N
L
VAR3=VAR1+2
DTXT"HELLO WORLD"
XR53
BY
N
XG53
DPC208
XT
A0.5
A0.5
WHILE(IN_1 AND VAR1=VAR2)
O1X
OUT3B
IF(VAR1=VAR2 OR VAR1>5)
NIF
REPEAT
T0.2
UNTIL(IN_X01)
TRIP
NWHILE
XE53
XD53
XT
XR33
1SV
"""


@pytest.mark.parametrize("text", [X150_IDLE_LOOP, X150_GENERATED], ids=["idle-homing", "generated-254"])
def test_x150_endless_loops_are_replayed_with_the_trace_of_running_every_round(text):
    """X150 `L` without a count (parker-x150.md L2328) counts its hidden `%Lk` down for ever: under
    every scenario validation runs (with a quarter of its step limit, as above), the replay gives
    the trace of running every round, and replays most of it."""
    result = driver.compile_file("g.x150", "x150", text=text, opt_level="O0")
    mod = result.analysis.module
    for scenario in verify.default_scenarios(mod):
        options = verify.default_options(scenario)
        limit = options.max_steps // 4
        fast = both(mod, scenario, until=options.until, max_steps=limit, samples=False)
        assert fast.skipped > limit * 0.8


@pytest.mark.parametrize("kept, added, rounds", [(0, 1, 5), (10, 1, 246), (10, 1, 247), (10, 1, 1000),
                                                 (255, 3, 1), (40, 3, 300), (256, 2, 128), (256, 2, 129)])
def test_the_replayed_round_states_are_those_adding_them_one_by_one_leaves(kept, added, rounds):
    """`_add_states` leaves `_execute`'s round states as the replayed rounds would, each adding its
    states with the counter moved on and emptying them when full before an addition
    (sim/interpreter.py `_execute`; X150 `L` loops, parker-x150.md L2328, add one a round)."""
    from mcc.sim.interpreter import ROUND_STATES

    def state(value: int, n: int) -> tuple:
        return ("loop", (("V1", n), ("L", value)))

    states = {state(-k, 0) for k in range(kept)}
    new = [state(-kept - n, n) for n in range(added)]
    expected = set(states)
    for round_ in range(1, rounds + 1):
        for label, items in new:
            if len(expected) >= ROUND_STATES:
                expected.clear()
            expected.add((label, tuple((name, value - round_ * added) if name == "L" else (name, value)
                                       for name, value in items)))
    repeats._add_states(states, new, {"L": -added}, rounds)
    assert states == expected
