"""Cycle time (issue 27): how long each pass through the program's main loop and each subroutine
call takes in a simulated run, and the worst position each axis reached over a sweep of scenarios.

A cycle is a pass through the outermost loop of the main routine: from one entry into its header
to the next (the simulator records each entry, `Trace.cycle_marks`). A call lasts from its `call`
event to the matching `return`. The figures are the simulator's motion rules (docs/SIMULATOR.md),
so they are as true as the simulated device results.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from mcc.sim.trace import Trace


@dataclass
class Timing:
    cycles: list[float] = field(default_factory=list)  # seconds, each complete pass of the main loop
    calls: dict[str, list[float]] = field(default_factory=dict)  # routine -> seconds of each call
    moves_per_cycle: int = 0  # moves started in the first complete cycle
    loop: str = ""  # the label of the main loop's header (empty: the main routine has no loop)
    loop_entered: float | None = None  # when the main loop was first entered
    ran: float = 0.0  # virtual seconds the run lasted (a cycle not complete by then is longer)
    stopped: str = ""  # why the run stopped (Trace.stopped: "time-limit", "step-limit", "waiting", "end", ...)

    def summary(self) -> list[str]:
        lines = []
        if self.cycles:
            worst = max(self.cycles)
            lines.append(f"cycle {self.cycles[0]:.3f} s, {self.moves_per_cycle} moves ({len(self.cycles)} complete "
                         f"passes of the main loop, longest {worst:.3f} s)")
        for name, times in sorted(self.calls.items()):
            lines.append(f"call {name}: {max(times):.3f} s (longest of {len(times)})")
        return lines


def timing(trace: Trace) -> Timing:
    out = Timing(ran=trace.time, stopped=trace.stopped)
    marks = trace.cycle_marks
    if marks:
        outer = outermost(marks)
        times = [t for label, t in marks if label == outer]
        out.loop, out.loop_entered = outer, times[0]
        out.cycles = [round(b - a, 9) for a, b in zip(times, times[1:])]
        if len(times) >= 2:
            out.moves_per_cycle = sum(1 for e in trace.events if e.kind == "move" and times[0] <= e.t < times[1])
    stack: list[tuple[str, float]] = []
    for event in trace.events:
        if event.kind == "call":
            stack.append((str(event.data.get("routine", "")), event.t))
        elif event.kind == "return" and stack:
            name, start = stack.pop()
            out.calls.setdefault(name, []).append(round(event.t - start, 9))
    return out


def outermost(marks: list[tuple[str, float]]) -> str:
    """The header whose entries span the longest stretch of the run (an inner loop's entries lie
    within its outer loop's passes; a set-up loop before the main loop ends early); the first
    entered on a tie."""
    first: dict[str, float] = {}
    last: dict[str, float] = {}
    for label, t in marks:
        first.setdefault(label, t)
        last[label] = t
    return max(first, key=lambda label: (last[label] - first[label], -first[label]))


@dataclass
class Worst:
    axis: str
    low: float
    low_scenario: str
    high: float
    high_scenario: str


def worst_positions(runs: list[tuple[str, Trace]]) -> list[Worst]:
    """Per axis, the lowest and highest position any run reached (or asked for, when it ran into
    its end of travel), and the scenario that did."""
    best: dict[str, Worst] = {}
    for name, trace in runs:
        for event in trace.events:
            reached = []
            if event.kind == "move_end" and "axis" in event.data:
                reached.append((event.data["axis"], event.data["position"]))
            elif event.kind == "travel":
                reached.append((event.data["axis"], event.data["target"]))
            elif event.kind == "move":
                reached += list(event.data.get("to", {}).items())
            for axis, position in reached:
                w = best.get(axis)
                if w is None:
                    best[axis] = Worst(axis, position, name, position, name)
                    continue
                if position < w.low:
                    w.low, w.low_scenario = position, name
                if position > w.high:
                    w.high, w.high_scenario = position, name
        for axis, position in trace.axes.items():
            w = best.setdefault(axis, Worst(axis, position, name, position, name))
            if position < w.low:
                w.low, w.low_scenario = position, name
            if position > w.high:
                w.high, w.high_scenario = position, name
    return [best[a] for a in sorted(best)]


BOUNDED_UNTIL = 30.0  # virtual seconds of the bounded run `mcc compile` reports a cycle time from
BOUNDED_STEPS = 200_000


def bounded_timing(module, profile=None) -> Timing | None:
    """The cycle time of a short simulation with every input low (None when it cannot run): what
    `mcc compile` prints beside the program's size."""
    from mcc.sim.files import simulate_module
    from mcc.sim.interpreter import Options

    trace, _ = simulate_module(module, module.path, None,
                               Options(until=BOUNDED_UNTIL, max_steps=BOUNDED_STEPS, samples=False), profile)
    return timing(trace) if trace is not None else None


def cycle_title(found) -> str:
    """What `mcc compile` and the language server's lens say of the main loop: its first complete pass; "cycle > N s" when the run's bound
    came before the loop closed; that it waits when it only polls an input that stays low; nothing
    when the loop ended without closing (the program leaves it)."""
    # a loop that only polls an input: passes of no time, then the simulator gives up waiting
    polls = found.stopped == "waiting" and bool(found.cycles) and found.cycles[0] == 0 and found.moves_per_cycle == 0
    if found.cycles and not polls:
        return f"cycle {found.cycles[0]:.3f} s, {found.moves_per_cycle} moves"
    if found.stopped == "waiting":
        return "cycle: waits for an input (all inputs low)"
    if found.stopped in ("time-limit", "step-limit") and found.loop_entered is not None:
        return f"cycle > {found.ran - found.loop_entered:.1f} s"
    return ""
