"""Benchmark of the simulator: a looping pick-and-place program run for one hour of virtual time,
and programs that poll inputs with short delays.

    .venv/bin/python bench/bench_sim.py [--hours H] [--repeat R]

The program (hand-built IR, so the benchmark does not depend on any frontend) loops forever:
two-axis interpolated move, wait, output on, a 0.2 s delay, a relative move back, a subroutine
that counts parts, output off, a check of an input (set by the scenario every 30 s) and a
polling-free wait. The run stops at the time limit. Reported: virtual time / wall time (the
target is at least 10,000x), operations per second, trace size, and the peak memory the run
allocated (tracemalloc, measured in a separate run so it does not slow the timed one). The figures
are the best of R runs; the CPU time is shown too, since a loaded machine stretches wall time.

The second table runs programs whose loops poll an input with a short delay (the samples' conveyor
and sorting station, and an MCode and an X150 polling loop written here), each for H hours of
virtual time with the input arriving now and then: a polling round must cost the same whatever its
period when nothing changes (target: at least 5,000x each).
"""

from __future__ import annotations

import argparse
import time
import tracemalloc

from pathlib import Path

from mcc.compiler import ir
from mcc.sim import Options, simulate
from mcc.sim.files import simulate_file
from mcc.sim.scenario import InputEvent, Scenario

ROOT = Path(__file__).resolve().parent.parent

# Polling programs: (name, file or (dialect, text), input that ends a wait, seconds between arrivals)
# Inputs held at a level for the whole run: the conveyor sample stops when DI6 reads 1, and an
# Arcus input nothing drives reads 1 (not sunk to ground, arcus-pmx-4ex-sa.txt L797, L1905;
# docs/SIMULATOR.md, "Inputs"), so the bench holds DI6 at 0 to keep the conveyor running for the hour.
HELD = {"arcus conveyor (DELAY=50)": {6: 0}}
MCODE_POLL = """\
PG 100
  LB A1
  H 5
  BR A1, I1=0
  O1=1
  H 200
  O1=0
  BR A1
E
PG
"""
X150_POLL = """\
1XE1
1XD1
1L0
1WHILE(IN_0)
1T0.01
1NWHILE
1O1
1T0.2
1O0
1N
1XT
1XR1
"""
POLLERS = [
    ("arcus conveyor (DELAY=50)", "samples/arcus/conveyor_speed_change.prg", 4, 300.0),
    ("arcus sorting station (DELAY=5)", "samples/arcus/sorting_station.prg", 1, 60.0),
    ("mcode polling loop (H 5)", ("mcode", MCODE_POLL), 1, 30.0),
    ("x150 polling loop (T0.01)", ("x150", X150_POLL), 1, 30.0),
]

U = ir.Unit


def program() -> ir.Module:
    def const(v, unit=U.NONE):
        return ir.Const(v, unit)

    setup = [ir.SetMotion(ir.MotionParam.MAX_SPEED, "X", const(20000, U.STEPS_PER_S)),
             ir.SetMotion(ir.MotionParam.INITIAL_SPEED, "X", const(500, U.STEPS_PER_S)),
             ir.SetMotion(ir.MotionParam.ACCEL, "X", const(200000, U.STEPS_PER_S2)),
             ir.SetMotion(ir.MotionParam.DECEL, "X", const(200000, U.STEPS_PER_S2))]
    body = [ir.Move(ir.MoveMode.ABSOLUTE, (("X", const(12000, U.STEPS)), ("Y", const(5000, U.STEPS)))),
            ir.WaitMotion("*"),
            ir.SetOutput(1, const(1)),
            ir.Delay(const(0.2, U.S)),
            ir.Move(ir.MoveMode.RELATIVE, (("X", const(-12000, U.STEPS)), ("Y", const(-5000, U.STEPS)))),
            ir.WaitMotion("*"),
            ir.Call("COUNT"),
            ir.SetOutput(1, const(0))]
    loop = ir.Block("loop", body, ir.Branch(ir.Compare("=", ir.Status("input", index=1), const(1)), "pause", "loop"))
    pause = ir.Block("pause", [ir.WaitInput(ir.Compare("=", ir.Status("input", index=1), const(0)))], ir.Jump("loop"))
    main = ir.Routine("main", ir.RoutineKind.MAIN, [ir.Block("start", setup, ir.Jump("loop")), loop, pause])
    count = ir.Routine("COUNT", ir.RoutineKind.SUBROUTINE, [ir.Block("c", [
        ir.Assign(ir.Var("V1"), ir.BinOp("+", ir.Var("V1"), const(1))),
        ir.Assign(ir.Var("V2"), ir.BinOp("%", ir.Var("V1"), const(100)))], ir.Return())])
    variables = {"V1": ir.Variable("V1"), "V2": ir.Variable("V2")}
    return ir.Module("arcus", "pmx-4ex-sa", variables, [main, count], steps_per_rev=4000)


def scenario(hours: float) -> Scenario:
    """Input 1 pauses the loop for 2 s every 30 s."""
    events = []
    t = 30.0
    while t < hours * 3600:
        events += [InputEvent(1, 1, at=t), InputEvent(1, 0, at=t + 2)]
        t += 30.0
    return Scenario(events=events)


def run(hours: float, samples: bool):
    return simulate(program(), scenario(hours), Options(until=hours * 3600, max_steps=10 ** 9, samples=samples))


def pulses(index: int, every: float, hours: float, held: dict[int, int] | None = None) -> Scenario:
    """The input is on for 1 s every `every` seconds; `held` inputs keep their level throughout."""
    events, t = [], every
    while t < hours * 3600:
        events += [InputEvent(index, 1, at=t), InputEvent(index, 0, at=t + 1)]
        t += every
    return Scenario(inputs=dict(held or {}), events=events)


def run_poller(source, index: int, every: float, hours: float, held: dict[int, int] | None = None):
    if isinstance(source, tuple):
        dialect, text = source
        path = str(ROOT / f"poll.{ {'mcode': 'mxt', 'x150': 'x150'}[dialect] }")
        return simulate_file(path, dialect, scenario=pulses(index, every, hours, held), text=text,
                             options=Options(until=hours * 3600, max_steps=10 ** 9)).trace
    return simulate_file(str(ROOT / source), scenario=pulses(index, every, hours, held),
                         options=Options(until=hours * 3600, max_steps=10 ** 9)).trace


def pollers(hours: float, repeat: int) -> None:
    print()
    print(f"{'polling program':34} {'virtual':>9} {'cpu':>8} {'speed':>10}  stopped  (target >= 5,000x)")
    for name, source, index, every in POLLERS:
        best = float("inf")
        trace = None
        for _ in range(repeat):
            start = time.process_time()
            trace = run_poller(source, index, every, hours, HELD.get(name))
            best = min(best, time.process_time() - start)
        assert trace is not None, name
        print(f"{name:34} {trace.time:8,.0f}s {best:7.3f}s {trace.time / best:9,.0f}x  {trace.stopped} "
              f"({trace.steps:,} operations)")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--hours", type=float, default=1.0)
    parser.add_argument("--repeat", type=int, default=3)
    args = parser.parse_args()
    virtual = args.hours * 3600
    best = best_cpu = float("inf")
    trace = None
    for _ in range(args.repeat):
        start, start_cpu = time.perf_counter(), time.process_time()
        trace = run(args.hours, samples=True)
        best = min(best, time.perf_counter() - start)
        best_cpu = min(best_cpu, time.process_time() - start_cpu)
    assert trace is not None and trace.stopped == "time-limit", trace.reason
    tracemalloc.start()
    run(args.hours, samples=True)
    _, peak = tracemalloc.get_traced_memory()
    tracemalloc.stop()
    points = sum(len(p) for p in trace.samples.values())
    print(f"virtual time      {virtual:,.0f} s ({args.hours:g} h), stopped: {trace.stopped}")
    print(f"wall time         {best:.3f} s (best of {args.repeat})")
    print(f"speed             {virtual / best:,.0f}x virtual/wall (target >= 10,000x)")
    print(f"cpu time          {best_cpu:.3f} s: {virtual / best_cpu:,.0f}x virtual/cpu (what a quiet machine's "
          "wall time approaches)")
    print(f"operations        {trace.steps:,} ({trace.steps / best:,.0f} per second)")
    print(f"cycles            {trace.variables.get('V1', 0):,}")
    print(f"trace             {len(trace.events):,} events, {points:,} motion samples")
    print(f"peak memory       {peak / 2 ** 20:.1f} MiB (tracemalloc, trace included)")
    pollers(args.hours, args.repeat)


if __name__ == "__main__":
    main()
