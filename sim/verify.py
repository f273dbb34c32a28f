"""`--verify`: run a source and its translation on the same scenarios and compare what they do.

A translation (compile to the same or another dialect, fmt, lint --fix, an optimizer pass) must
not change what the machine does. `compare(source, output, scenarios)` simulates both modules on
each scenario, to the same horizon, and compares their traces in the IR's units
(docs/SIMULATOR.md, "Verification"):

- the **observable events** in order: moves (their end positions), arcs, slews, stops, homing,
  position changes, outputs, prints, limit hits and runtime errors; not calls, returns or jumps,
  which a translation may restructure;
- **positions** after scaling the source's steps by `output steps_per_rev / source steps_per_rev`,
  within `POSITION_TOLERANCE` output steps (a converted position rounds to a whole step);
- **times** within a `Tolerance` derived from the arithmetic of the two dialects: what the writer
  must round (a speed to the target's resolution, a delay or a ramp time to its tick), never a flat
  percentage, so a speed 2 % off is a difference;
- **why and when each run stopped**: a run that ends, waits or hits a limit differently from the
  other, or at another time, is a difference (an output that spins at t = 0 matches nothing); then
  the final positions and outputs.

The default scenarios come from the program: every input it reads low, high, and toggling around
the points where the program waits. The first difference is returned as a `Divergence` naming its
time, source line and what differs.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from fractions import Fraction

from mcc.compiler import dialects, ir, ir_verify, units
from mcc.compiler.dialects import Resolution
from mcc.sim.interpreter import ContractError, Options, simulate
from mcc.sim.scenario import AxisSwitches, InputEvent, Scenario
from mcc.sim.trace import Event, Trace

POSITION_TOLERANCE = 1.0  # output steps
OBSERVABLE = ("move", "arc", "slew", "stop", "home", "home_end", "set_position", "output", "print", "limit",
              "error", "move_end", "pause", "resume", "step")
# A stricter comparison for transformations that keep the program's structure of device commands
# (the optimizer, a backend reading back its own dialect): also the native commands in order, the
# handlers installed and removed, the drive switched on and off.
STRICT = OBSERVABLE + ("native", "handler_on", "handler_off", "drive")
LIMITS = ("time-limit", "step-limit")
MOTIONS = ("move", "arc", "slew", "home")  # events that start a motion profile (a ramp each)
VERIFY_UNTIL = 30.0
VERIFY_STEPS = 200_000
MAX_DRIVEN_INPUTS = 16
MAX_TOGGLES = 10  # input changes of a toggling scenario
TOGGLE_AFTER = 0.1  # s after a point where the program waits that a toggling input changes
STEP_BUDGETS = 3  # a run stopped by the step limit before the other's stop is run again, x8 each time


POLL = 0.001  # s: the simulator's scan of a polling loop while an axis moves (interpreter.Options.poll)


@dataclass(frozen=True)
class Tolerance:
    """How far apart in time two runs may do the same thing: `absolute` (one tick of either side
    and one scan of a polling loop), plus `per_motion` for each motion started so far (a ramp time
    rounded to a tick), plus `relative` times the event's time (the largest rounding, as a share, of
    a speed, an acceleration or a delay the writer converted)."""

    absolute: float = POLL + 0.001
    per_motion: float = 0.0
    relative: float = 0.0

    def at(self, t: float, motions: int = 0) -> float:
        return self.absolute + self.per_motion * motions + self.relative * abs(t) + 1e-9


EXACT = Tolerance()


def resolution(dialect: str, profile=None) -> Resolution:
    """The dialect's `Resolution`, with the profile's `[sim]` overrides."""
    known = dialects.DIALECTS.get(dialect)
    found = known.resolution if known is not None else Resolution()
    if profile is None or not hasattr(profile, "get"):
        return found
    rate = profile.get("sim.rate_resolution", found.rate)
    tick = profile.get("sim.time_resolution", found.tick)
    return dataclasses.replace(found, rate=float(rate), tick=float(tick))


def tolerance(source: ir.Module, output: ir.Module, source_profile=None, output_profile=None) -> Tolerance:
    """The time tolerance of comparing `source` with `output`, from what the writer had to round.

    The same dialect at the same steps per revolution writes every number as it is: one tick and
    one polling scan. Across dialects or step sizes, each constant speed, acceleration, delay and
    ramp time of the source is converted to the output's units and rounded to its resolution; the
    largest rounding, as a share of the value, is how far late or early a run may drift; a target
    that writes ramp times (Arcus ACC) may make each ramp one tick longer or shorter."""
    src, out = resolution(source.dialect, source_profile), resolution(output.dialect, output_profile)
    tick = max(src.tick, out.tick)
    factor = units.ratio(source.steps_per_rev, output.steps_per_rev)
    if source.dialect == output.dialect and factor == 1:
        return Tolerance(POLL + tick)
    spr = output.steps_per_rev or source.steps_per_rev or 1000
    rate_step = out.rate * (spr if out.per_rev else 1)
    relative = 0.0
    for value, kind in _timing_constants(source):
        if kind == "rate":
            relative = max(relative, _rounding(value * float(factor), rate_step))
        elif kind == "accel" and not out.ramp_times:
            relative = max(relative, _rounding(value * float(factor), rate_step))
        elif kind == "time":
            relative = max(relative, _rounding(value, out.tick))
    per_motion = tick if (src.ramp_times or out.ramp_times) else 0.0
    return Tolerance(POLL + tick, per_motion, relative)


RATES = (ir.MotionParam.INITIAL_SPEED, ir.MotionParam.MAX_SPEED)
ACCELS = (ir.MotionParam.ACCEL, ir.MotionParam.DECEL)
RAMP_TIMES = (ir.MotionParam.ACCEL_TIME, ir.MotionParam.DECEL_TIME)


def _timing_constants(module: ir.Module):
    """(value, kind) of every constant that decides timing: a speed ("rate", steps/s), an
    acceleration ("accel", steps/s²), a delay or ramp time ("time", s)."""
    for _, block in module.blocks():
        for op in block.ops:
            if isinstance(op, ir.SetMotion) and isinstance(op.value, ir.Const):
                if op.param in RATES:
                    yield float(op.value.value), "rate"
                elif op.param in ACCELS:
                    yield float(op.value.value), "accel"
                elif op.param in RAMP_TIMES:
                    yield float(op.value.value), "time"
            elif isinstance(op, ir.Delay) and isinstance(op.duration, ir.Const):
                yield float(op.duration.value), "time"
            elif isinstance(op, ir.Slew) and isinstance(op.velocity, ir.Const):
                yield float(op.velocity.value), "rate"
            elif isinstance(op, ir.Home) and isinstance(getattr(op, "speed", None), ir.Const):
                yield float(op.speed.value), "rate"


def _rounding(value: float, step: float) -> float:
    """The share by which `value` changes when written on a grid of `step`."""
    if not value or step <= 0:
        return 0.0
    rounded = units.round_to(abs(value), step) or step  # a writer never writes a non-zero rate as 0
    return abs(rounded - abs(value)) / min(rounded, abs(value))


@dataclass(frozen=True)
class Divergence:
    scenario: str
    time: float
    line: int | None  # the source's line
    message: str

    def __str__(self) -> str:
        where = f"line {self.line}, " if self.line is not None else ""
        return f"{where}t = {self.time:.3f} s, scenario '{self.scenario}': {self.message}"


def inputs_read(module: ir.Module) -> list[int]:
    """Every digital input the program reads (conditions, readings, input handlers)."""
    found: set[int] = set()
    for _, block in module.blocks():
        exprs = [e for op in block.ops for e in ir.op_exprs(op)] + list(ir.term_exprs(block.terminator))
        for op in block.ops:
            if isinstance(op, ir.SetHandler) and op.event == "input" and op.args \
                    and isinstance(op.args[0], ir.Const):
                found.add(int(op.args[0].value))
        for expr in exprs:
            for node in ir.walk_expr(expr):
                if isinstance(node, ir.Status) and node.meaning == "input" and node.index:
                    found.add(node.index)
                elif isinstance(node, ir.InputMatch):
                    found.update(n for n, bit in enumerate(node.pattern.bits, 1) if bit in "01")
    return sorted(found)[:MAX_DRIVEN_INPUTS]


MASK_INPUTS = 8  # the inputs a reading of all inputs at once (MCode IN, Arcus DI) is given levels for


def inputs_seen(module: ir.Module) -> list[int]:
    """The inputs whose level the program can see: those it reads one by one and, when it reads
    all inputs at once as a mask, the first MASK_INPUTS too (their levels must be stated, or an
    undriven input reads its product's idle level, which differs between products)."""
    found = set(inputs_read(module))
    for _, block in module.blocks():
        exprs = [e for op in block.ops for e in ir.op_exprs(op)] + list(ir.term_exprs(block.terminator))
        if any(isinstance(node, ir.Status) and node.meaning == "inputs" for expr in exprs for node in ir.walk_expr(expr)):
            found.update(range(1, MASK_INPUTS + 1))
            break
    return sorted(found)


def with_idle_levels(scenario: Scenario, source: ir.Module, profile, also: list[int]) -> Scenario:
    """The scenario with the level of every input it leaves undriven stated: the source's idle
    level (inactive for the polarity the source sets first, else its product's), so that the output,
    on a product whose inputs idle at the other level, runs on the same machine (docs/SIMULATOR.md,
    "Inputs")."""
    from mcc.compiler.in_force import active_high
    from mcc.sim.interpreter import profile_of

    undriven = [n for n in sorted(set(inputs_read(source)) | set(also)) if n not in scenario.inputs]
    if not undriven:
        return scenario
    default = active_high(profile if profile is not None else profile_of(source))
    polarity: dict[int, bool] = {}
    for _, block in source.blocks():
        for op in block.ops:
            if isinstance(op, ir.Setting) and op.name == "input_active_high" and op.index is not None \
                    and isinstance(op.value, ir.Const):
                polarity.setdefault(op.index, bool(op.value.value))
    idle = {n: 0 if polarity.get(n, default) else 1 for n in undriven}
    return dataclasses.replace(scenario, inputs={**idle, **scenario.inputs})


def default_options(scenario: Scenario | None = None) -> Options:
    return Options(until=(scenario.until if scenario is not None else None) or VERIFY_UNTIL,
                   max_steps=VERIFY_STEPS, samples=False)


def default_scenarios(module: ir.Module, profile=None, low: Trace | None = None,
                      options: Options | None = None) -> list[Scenario]:
    """Scenarios generated from the program: all inputs it reads low, all high, and for each input
    one scenario with it high on its own and one with it toggling around the program's waits.

    The toggling times come from the run with every input low (`low`, simulated here when not
    given; run with `options`, else the defaults): the input changes `TOGGLE_AFTER` after each point where that run let time pass (a wait
    started or ended, a move ended, the run stopped waiting), then every second, `MAX_TOGGLES`
    changes at least, so a wait for the input's rise and one for its fall are both released."""
    read = inputs_seen(module)  # a reading of every input at once (Arcus DI, MCode IN) sees the first eight
    # levels stated, not left to each product's idle state: an input no scenario drives is inactive
    # for the polarity in force, which is another level on another product (docs/SIMULATOR.md)
    lows = Scenario(inputs={n: 0 for n in read}, name="inputs low")
    out = [lows]
    if not read:
        return out
    if low is None:
        low = simulate(module, lows, _copy(options) if options is not None else default_options(), profile)
    times = toggle_times(low)
    out.append(Scenario(inputs={n: 1 for n in read}, name="inputs high"))
    for n in read:
        if len(read) > 1:  # with one input, "inputs high" is this one
            out.append(Scenario(inputs={m: int(m == n) for m in read}, name=f"input {n} high"))
        events = [InputEvent(n, 1 - k % 2, at=t) for k, t in enumerate(times)]
        out.append(Scenario(inputs={m: 0 for m in read}, events=events,
                            name=f"input {n} toggles at {', '.join(f'{t:g}' for t in times)} s"))
    return out


def toggle_times(low: Trace) -> list[float]:
    """When a toggling input changes: just after each point where the all-low run waited."""
    points = sorted({round(e.t, 6) for e in low.events if e.t < low.time} | {0.0, round(low.time, 6)})
    half = MAX_TOGGLES // 2
    if len(points) > MAX_TOGGLES:  # the first waits, and the last ones (where the run stopped waiting)
        points = points[:half] + points[-half:]
    times = [round(p + TOGGLE_AFTER, 6) for p in points]
    while len(times) < MAX_TOGGLES and times[-1] + 1.0 < VERIFY_UNTIL:
        times.append(round(times[-1] + 1.0, 6))
    return [t for t in times if t < VERIFY_UNTIL]


def compare(source: ir.Module, output: ir.Module, scenarios: list[Scenario] | None = None,
            options: Options | None = None, source_profile=None, output_profile=None,
            kinds: tuple[str, ...] = OBSERVABLE, by_count: bool = False,
            within: Tolerance | None = None, source_runs: "Runs | None" = None) -> Divergence | None:
    """The first divergence between `source` and `output` on the scenarios, or None.

    `source_runs`: the runs of `source` made by earlier comparisons with other outputs (`Runs`),
    used when they are runs of this very module and profile, so that one source compared with
    many outputs (every optimization level) is simulated once per scenario.

    Both runs of a scenario go to the same horizon (its `until`, else `VERIFY_UNTIL`, and the same
    step limit); a run stopped by the step limit before the other stopped is run again with a
    larger step budget, so a loop that takes more operations per round is not a difference while
    one that never lets time pass is. Both modules must keep the IR contract
    (`interpreter.ContractError` otherwise)."""
    source, output = _stated_steps(source, output), _stated_steps(output, source)
    for module in (source, output):  # once here, not at each of the runs below
        problems = ir_verify.verify(module)
        if problems:
            raise ContractError(problems[0])
    tol = within or tolerance(source, output, source_profile, output_profile)
    ratio = units.ratio(source.steps_per_rev, output.steps_per_rev)
    shared = shared_outputs(source_profile, output_profile)
    known: dict[int, Trace] = {}
    if source_runs is None or source_runs.module is not source or source_runs.profile is not source_profile:
        source_runs = Runs(source, source_profile)
    output_runs = Runs(output, output_profile)
    idle = sorted(set(inputs_seen(source)) | set(inputs_seen(output)))  # stated at the source's idle level
    if scenarios is None:
        lows = with_idle_levels(Scenario(inputs={n: 0 for n in inputs_read(source)}, name="inputs low"), source,
                                source_profile, idle)
        known[id(lows)] = source_runs.run(lows, options or default_options(lows))
        scenarios = [lows] + default_scenarios(source, source_profile, known[id(lows)])[1:]
        scenarios += _analog_scenarios(source, source_profile, output_profile)
    for scenario in scenarios:
        if id(scenario) not in known:
            scenario = with_idle_levels(scenario, source, source_profile, idle)
        opts = options or default_options(scenario)
        a = known.get(id(scenario)) or source_runs.run(scenario, opts)
        scenario_out = _analog_scaled(scenario, source_profile, output_profile)
        b = output_runs.run(scenario_out, opts)
        moved = _translated(scenario_out, _axis_map(a, b), ratio)
        if moved is not scenario_out:  # the switches and positions of the output's axes, in its steps
            b = output_runs.run(moved, opts)
        runs = [_Run(source, scenario, source_profile, a, opts.max_steps),
                _Run(output, moved, output_profile, b, opts.max_steps)]
        horizon = _same_horizon(runs, opts, tol, kinds)
        a, b = (_within_outputs(run.trace, shared) for run in runs)
        found = compare_traces(a, b, ratio, scenario.name, kinds, by_count, tol, horizon)
        if found is not None and not _another_interleaving(source, scenario, opts, source_profile, b, ratio,
                                                            kinds, by_count, tol, horizon):
            return found
    return None


def output_count(profile) -> int:
    """The outputs the product has (`[machine.outputs] count`; 0: not known)."""
    count = profile.get("machine.outputs.count", 0) if profile is not None and hasattr(profile, "get") else 0
    return count if isinstance(count, int) and not isinstance(count, bool) and count > 0 else 0


def shared_outputs(source_profile, output_profile) -> int:
    """The outputs both products have (0: no limit). A value for every output at once (Arcus DO=1,
    MCode OT=1, X150 O100000) sets each product's own outputs (docs/CROSS.md, "Output banks"): the
    outputs only one product has are not compared. A program that turns one of them on is refused
    by the backend, which knows the target's outputs."""
    counts = [c for c in (output_count(source_profile), output_count(output_profile)) if c]
    return min(counts) if len(counts) == 2 and counts[0] != counts[1] else 0


def _within_outputs(trace: Trace, shared: int) -> Trace:
    """`trace` without what it did to outputs above `shared` (the trace itself when 0)."""
    if not shared:
        return trace
    events = [e for e in trace.events if not (e.kind == "output" and e.data.get("output", 0) > shared)]
    outputs = {n: v for n, v in trace.outputs.items() if n <= shared}
    return dataclasses.replace(trace, events=events, outputs=outputs)


def _analog_counts(profile) -> int:
    return int(profile.get("machine.analog.counts", 0) or 0) if profile is not None else 0


def _analog_scenarios(source: ir.Module, source_profile, output_profile) -> list[Scenario]:
    """Between two products whose analog inputs count differently (a migration from an MDrivePlus
    to a Lexium drive), a program that reads an analog input is also run with each read input at a
    reading that no scale factor leaves alone (a third of the source's full scale, plus one), so a
    conversion that forgets the scale is found: with no analog values both read 0."""
    src, out = _analog_counts(source_profile), _analog_counts(output_profile)
    if not src or not out or src == out:
        return []
    read = sorted({node.index or 1 for _, block in source.blocks()
                   for expr in [e for op in block.ops for e in ir.op_exprs(op)] + list(ir.term_exprs(block.terminator))
                   for node in ir.walk_expr(expr) if isinstance(node, ir.Status) and node.meaning == "analog"})
    if not read:
        return []
    value = src // 3 + 1
    return [Scenario(analog={n: value for n in read}, name=f"analog input{'s' if len(read) > 1 else ''} at {value}")]


def _analog_scaled(scenario: Scenario, source_profile, output_profile) -> Scenario:
    """The scenario's analog values (the source device's counts) in the output device's counts, the
    same voltage: profiles give `machine.analog.counts` (1024 on an MDrivePlus, 4096 on a Lexium
    drive, docs/dialects/mcode.md); without both, or when equal, the scenario itself."""
    src, out = _analog_counts(source_profile), _analog_counts(output_profile)
    if not scenario.analog or not src or not out or src == out:
        return scenario
    import dataclasses

    return dataclasses.replace(scenario, analog={k: v * out / src for k, v in scenario.analog.items()})


@dataclass
class _Run:
    module: ir.Module
    scenario: Scenario
    profile: object
    trace: Trace
    budget: int
    tries: int = 0
    stuck: bool = False  # more steps did not let its time advance: a loop that never waits


def _same_horizon(runs: list[_Run], opts: Options, tol: Tolerance, kinds: tuple[str, ...]) -> float | None:
    """Bring two runs to the same horizon: while the one that stopped earlier was stopped by the
    step limit, run it again with 4 times the budget (`STEP_BUDGETS` times at most), since a rewrite
    may take more operations per round of a loop. Answers the time up to which both runs are
    complete when both still end at the step limit, each having let time pass (their loops wait,
    just not as far), else None: how they stopped is then compared."""
    for _ in range(2 * STEP_BUDGETS):
        behind, ahead = sorted(runs, key=lambda r: r.trace.time)
        if behind.trace.stopped != "step-limit" or behind.tries >= STEP_BUDGETS or behind.stuck or \
                behind.trace.time >= ahead.trace.time - tol.at(ahead.trace.time, _motions(ahead.trace)):
            break
        _rerun(behind, opts)
    for run, other in (runs, runs[::-1]):
        if run.trace.stopped == "step-limit" and other.trace.stopped == "waiting" and \
                abs(run.trace.time - other.trace.time) <= tol.at(other.trace.time, _motions(other.trace)):
            if not run.tries:
                _rerun(run, opts)
            if run.stuck:  # spinning where the other waits for nothing: neither can do anything more
                run.trace = dataclasses.replace(run.trace, stopped="waiting", reason=run.trace.reason +
                                                "; with more steps its time does not advance: it can do nothing more")
    if all(r.trace.stopped == "step-limit" for r in runs):
        if not any(r.stuck for r in runs):
            return min(r.trace.time for r in runs)
        # a run whose time no longer advances can do nothing more: the two are alike when the other
        # does nothing observable after that time either (both are then compared on everything)
        if all(not _acts_after(other.trace, run.trace.time + tol.at(run.trace.time), kinds)
               for run, other in (runs, runs[::-1]) if run.stuck):
            return ALL
    return None


ALL = float("inf")  # a horizon: both runs are complete, compare every event they made


def _acts_after(trace: Trace, t: float, kinds: tuple[str, ...]) -> bool:
    return any(e.t > t for e in _observable(trace, None, kinds))


def _rerun(run: _Run, opts: Options) -> None:
    """Run again with 4 times the step budget; `stuck` when its time does not advance."""
    before = run.trace.time
    run.budget *= 4
    run.tries += 1
    run.trace = simulate(run.module, run.scenario, dataclasses.replace(_copy(opts), max_steps=run.budget),
                         run.profile, checked=True)
    run.stuck = run.trace.stopped == "step-limit" and run.trace.time <= before


RACE_POINTS = 24  # the points of a polling round tried (rounds of random programs are shorter)


def _another_interleaving(source: ir.Module, scenario: Scenario, opts: Options, profile, output: Trace,
                          ratio: Fraction, kinds: tuple[str, ...], by_count: bool, tol: Tolerance,
                          horizon: float | None) -> bool:
    """Whether the source does what the output did when its polling loops let time pass at another
    point of their rounds. A loop that reads an input twice per round and leaves only when it
    changes between the reads is a race on a real controller; a rewrite that rotates the loop may
    take the other way, which the source could take too. Asked only after a divergence, so a
    scenario costs no more otherwise."""
    for offset in range(1, RACE_POINTS + 1):
        other = simulate(source, scenario, dataclasses.replace(_copy(opts), poll_offset=offset), profile, checked=True)
        if compare_traces(other, output, ratio, scenario.name, kinds, by_count, tol, horizon) is None:
            return True
    return False


def _translated(scenario: Scenario, axis_map: dict[str, str], ratio: Fraction) -> Scenario:
    """The scenario as the output sees it: the source's axis names and steps turned into the
    output's (a home switch on MCode axis 1 is on Arcus axis X), or the scenario itself."""
    if all(axis_map.get(a, a) == a for a in scenario.axes) and ratio == 1 and \
            all(axis_map.get(e.axis, e.axis) == e.axis for e in scenario.events if e.axis):
        return scenario
    scale = float(ratio)

    def at(value):
        return None if value is None else value * scale

    axes = {axis_map.get(name, name): AxisSwitches(sw.home * scale, at(sw.limit_plus), at(sw.limit_minus))
            for name, sw in scenario.axes.items()}
    events = [dataclasses.replace(e, axis=axis_map.get(e.axis, e.axis), passes=e.passes * scale) if e.axis else e
              for e in scenario.events]
    return dataclasses.replace(scenario, axes=axes, events=events)


def _stated_steps(module: ir.Module, other: ir.Module) -> ir.Module:
    """`module`, with the other side's steps per revolution when it does not state its own.

    A program that does not say how many steps a revolution has (an Arcus profile without
    `steps_per_rev`) is written one step per source step (`units.ratio` is 1), so its machine is
    the other side's: the simulator's default speeds, which are in revolutions, must be too."""
    if module.steps_per_rev or not other.steps_per_rev:
        return module
    return dataclasses.replace(module, steps_per_rev=other.steps_per_rev)


class Runs:
    """The runs of one module in one comparison, so that a scenario that cannot differ from an
    earlier one before that run stopped is not simulated again.

    A run is a deterministic function of the module and of what the scenario does up to the time
    the run stopped: inputs, analog values, switches and incidents at the start, and its events and
    incidents up to then (an input change at 5 s cannot matter to a run that stopped at 0.3 s). The
    scenarios of a validation share their start and differ later (all inputs low, and each input
    toggling after the program's first wait), so a program that stops, or loops at one instant up to
    the step limit, before the first toggle has one run for all of them. A run that stopped
    `waiting` is reused only for the same scenario: a later input change would have woken it. The
    traces are never changed by the comparison (it replaces them when it runs again)."""

    REUSED_STOPS = ("end", "error", "step-limit", "time-limit")

    def __init__(self, module: ir.Module, profile) -> None:
        self.module, self.profile = module, profile
        self.done: list[tuple[Scenario, Options, Trace]] = []

    def run(self, scenario: Scenario, options: Options) -> Trace:
        for earlier, opts, trace in self.done:
            if opts == options and (earlier == scenario or trace.stopped in self.REUSED_STOPS
                                    and same_until(earlier, scenario, trace.time)):
                return trace
        trace = simulate(self.module, scenario, _copy(options), self.profile, checked=True)
        self.done.append((scenario, options, trace))
        return trace


def same_until(a: Scenario, b: Scenario, t: float) -> bool:
    """Whether two scenarios do the same up to time `t` (inclusive): the same start, the same
    events and incidents up to `t`, and none of either's others before it. Position-triggered
    events (no time) count as early ones."""
    if (a.inputs, a.analog, a.axes, a.until, a.capture) != (b.inputs, b.analog, b.axes, b.until, b.capture):
        return False

    def early(items) -> list:
        return [item for item in items if item.at is None or item.at <= t]

    return early(a.events) == early(b.events) and early(a.incidents) == early(b.incidents)


def _copy(options: Options) -> Options:
    return Options(options.until, options.max_steps, options.nesting, options.spin, options.poll, False)




def compare_traces(a: Trace, b: Trace, ratio: Fraction = Fraction(1), scenario: str = "",
                   kinds: tuple[str, ...] = OBSERVABLE, by_count: bool = False,
                   within: Tolerance = EXACT, horizon: float | None = None) -> Divergence | None:
    """Compare two traces; positions of `a` are multiplied by `ratio` to be in `b`'s steps.

    `kinds` are the events compared (OBSERVABLE, or STRICT). The runs must stop for the same reason
    at the same time (within the tolerance); two runs cut by a limit then are compared up to the
    cut, or with `by_count`, when both were cut by the step limit, on the events both made (a loop
    that never waits stops at the step limit at time 0, and a transformation may change the steps
    per round). The first event that differs is reported before a difference in how they stopped,
    since it names a source line. `horizon`: both runs were stopped by the step limit after letting
    time pass, and are complete up to that time (`_same_horizon`; `ALL`: complete)."""
    stop = None if horizon is not None else _stop_difference(a, b, scenario, within)
    limited = a.stopped in LIMITS and b.stopped in LIMITS
    cut = None
    if stop is None and limited and horizon != ALL:  # both reached the horizon: what happens within the
        end = min(a.time, b.time) if horizon is None else horizon  # tolerance of it may or may not
        cut = end - within.at(end, _motions(a))
    repeating = _repeating(a, b, ratio, scenario, kinds, within) if stop is None else None
    if isinstance(repeating, Divergence):
        return repeating
    if repeating is not None:  # both repeat for ever: compared up to where they began to repeat
        a, b = repeating
    ea, eb = _observable(a, None, kinds), _observable(b, None, kinds)
    counted = by_count and a.stopped == b.stopped == "step-limit" and stop is None
    if counted:
        if (not ea) != (not eb):
            return stop or Divergence(scenario, a.time, _last_line(a),
                                      f"one run does nothing observable before the step limit: the source "
                                      f"{len(ea)} events, the output {len(eb)}")
        ea, eb = ea[:min(len(ea), len(eb))], eb[:min(len(ea), len(eb))]
    elif cut is not None:
        ea, eb = [e for e in ea if e.t <= cut], [e for e in eb if e.t <= cut]
    axis_map = _axis_map(a, b)
    scale = float(ratio)
    motions = 0
    for n in range(max(len(ea), len(eb))):
        if n >= len(ea):
            extra = eb[n]
            return Divergence(scenario, extra.t, None, f"the output does more: {_show(extra)} at {extra.t:.3f} s")
        if n >= len(eb):
            missing = ea[n]
            return Divergence(scenario, missing.t, missing.line, f"the output does not {_show(missing)}")
        x, y = ea[n], eb[n]
        problem = _differ(x, y, axis_map, scale, within.at(max(x.t, y.t), motions), within.relative)
        if problem:
            return Divergence(scenario, x.t, x.line, problem)
        motions += x.kind in MOTIONS
    if stop is not None:
        return stop
    if not limited:
        for axis, pos in a.axes.items():
            other = b.axes.get(axis_map.get(axis, axis))
            if other is not None and abs(pos * scale - other) > POSITION_TOLERANCE + 1e-6:
                return Divergence(scenario, a.time, None, f"axis {axis} ends at {pos * scale:g} steps in the source, "
                                                          f"{other:g} in the output")
        on_a = {n for n, v in a.outputs.items() if v}
        on_b = {n for n, v in b.outputs.items() if v}
        if on_a != on_b:
            return Divergence(scenario, a.time, None, f"outputs on at the end: {sorted(on_a)} in the source, "
                                                      f"{sorted(on_b)} in the output")
    return None


def _repeating(a: Trace, b: Trace, ratio: Fraction, scenario: str, kinds: tuple[str, ...],
               within: Tolerance) -> Divergence | tuple[Trace, Trace] | None:
    """Two runs stopped polling at the same time, one or both making the same events round after
    round for ever (`Trace.repeats_from`): how many rounds each made before the poll detector
    stopped it depends on its steps per round, which a rewrite may change. They are alike when
    both repeat the same round (up to where it starts) after the same events; then the answer is
    both traces cut where their repeating began, for the caller to compare those events. None: not
    both repeat (a run that repeats where the other does not is a difference)."""
    if a.repeats_from is None and b.repeats_from is None:
        return None
    if a.stopped != "waiting" or b.stopped != "waiting":
        return None
    parts = [_repeated_round(t, kinds) for t in (a, b)]
    (before_a, period_a), (before_b, period_b) = parts
    if not period_a or not period_b:
        if not period_a and not period_b:
            return None  # its repeated rounds hold nothing compared here
        which, period = ("output", period_b) if period_b else ("source", period_a)
        return Divergence(scenario, a.time, _last_line(a),
                          f"the {which} does {_show(period[0])} over and over at {a.time:.3f} s, the other "
                          f"does not")
    axis_map = _axis_map(a, b)
    slack = within.at(a.time, _motions(a))
    if len(period_a) != len(period_b) or not any(
            all(not _differ(x, period_b[(i + shift) % len(period_b)], axis_map, float(ratio), slack, within.relative)
                for i, x in enumerate(period_a)) for shift in range(len(period_b))):
        return Divergence(scenario, a.time, period_a[0].line,
                          f"the source repeats {', '.join(_show(e) for e in period_a[:4])} for ever at "
                          f"{a.time:.3f} s, the output {', '.join(_show(e) for e in period_b[:4])}")
    return dataclasses.replace(a, events=before_a), dataclasses.replace(b, events=before_b)


def _repeated_round(trace: Trace, kinds: tuple[str, ...]) -> tuple[list[Event], list[Event]]:
    """The observable events of a run before its rounds began to repeat, and one round. The round
    is taken back over the events before the stretch without a change that showed it (a change
    made during the first round starts that stretch after it), so two runs whose stretches began
    at other points of the same rounds give the same events before them."""
    if trace.repeats_from is None:
        return _observable(trace, None, kinds), []
    before = _observable(dataclasses.replace(trace, events=trace.events[:trace.repeats_from]), None, kinds)
    rounds = _observable(dataclasses.replace(trace, events=trace.events[trace.repeats_from:]), None, kinds)
    period = rounds[:_period(rounds)]
    while before and period and _key(before[-1]) == _key(period[-1]):
        before.pop()
        period = [period[-1]] + period[:-1]
    return before, period


def _key(event: Event) -> tuple[str, str]:
    """What an event does, not where or when."""
    return event.kind, repr(sorted(event.data.items()))


def _period(events: list[Event]) -> int:
    """The shortest round the events repeat (the whole list when they do not), by the prefix
    function of string matching, on what each event does (not where or when)."""
    if not events:
        return 0
    keys = [_key(e) for e in events]
    fail = [0] * len(keys)
    for i in range(1, len(keys)):
        k = fail[i - 1]
        while k and keys[i] != keys[k]:
            k = fail[k - 1]
        fail[i] = k + (keys[i] == keys[k])
    period = len(keys) - fail[-1]
    return period if period < len(keys) else len(keys)


def _stop_difference(a: Trace, b: Trace, scenario: str, within: Tolerance) -> Divergence | None:
    """A difference in how the runs stopped: another reason (ended, waiting, an error, a limit) or
    another time. A time limit and a step limit reached at the same time are the same horizon."""
    same_reason = a.stopped == b.stopped or (a.stopped in LIMITS and b.stopped in LIMITS)
    late = max(a.time, b.time)
    if same_reason and abs(a.time - b.time) <= within.at(late, _motions(a)):
        return None
    return Divergence(scenario, min(a.time, b.time), _last_line(a),
                      f"the source stopped with '{a.stopped}' at {a.time:.3f} s ({a.reason}), the output with "
                      f"'{b.stopped}' at {b.time:.3f} s ({b.reason})")


def _motions(trace: Trace) -> int:
    return sum(1 for e in trace.events if e.kind in MOTIONS)


def _observable(trace: Trace, cut: float | None, kinds: tuple[str, ...] = OBSERVABLE) -> list[Event]:
    out = []
    for event in trace.events:
        if event.kind not in kinds or (cut is not None and event.t > cut):
            continue
        if event.kind == "move" and event.data["from"] == event.data["to"]:
            continue  # a move to where the axis already is does nothing
        if event.kind in ("stop", "home", "home_end") and event.data.get("idle"):
            continue  # nor does a stop of an axis at standstill (a target's STOP of every axis), nor
            # a homing on the switch the axis stands on that leaves its position and zero as they were
        out.append(event)
    return out


def _axis_map(a: Trace, b: Trace) -> dict[str, str]:
    """Source axis -> output axis: the same name, else paired in order of first use."""
    def order(trace: Trace) -> list[str]:
        seen: list[str] = []
        for event in trace.events:
            if len(seen) >= len(trace.axes) and trace.axes:
                break  # every axis named: the order is known
            if event.kind == "drive":
                continue  # an enable (Arcus EO2) of an axis a one-axis target leaves out does not pair it
            data = event.data
            if "to" not in data and "axis" not in data and "axes" not in data:
                continue  # names no axis (a print, an output): a print loop makes 200,000 of them
            names = list(data.get("to", ())) + ([data["axis"]] if "axis" in data else []) + list(data.get("axes", ()))
            seen += [n for n in names if n not in seen]
        return seen + [n for n in trace.axes if n not in seen]

    first, second = order(a), order(b)
    if set(first) <= set(second):
        return {n: n for n in first}
    return dict(zip(first, second))


def _differ(x: Event, y: Event, axis_map: dict[str, str], scale: float, slack: float, share: float = 0.0) -> str:
    """What differs between two events at the same place of both runs; `slack` is the time
    tolerance there, `share` the rounding of a converted rate."""
    if x.kind != y.kind:
        return f"the source does {_show(x)}, the output {_show(y)} at {y.t:.3f} s"
    if abs(x.t - y.t) > slack:
        return f"{_show(x)} happens at {x.t:.3f} s in the source, at {y.t:.3f} s in the output"
    dx, dy = x.data, y.data
    if x.kind == "move":
        for axis, target in dx["to"].items():
            other = dy["to"].get(axis_map.get(axis, axis))
            if other is None or abs(target * scale - other) > POSITION_TOLERANCE + 1e-6:
                return f"the move on axis {axis} goes to {target * scale:g} steps in the source, to " \
                       f"{'nothing' if other is None else format(other, 'g')} in the output"
        return ""
    if x.kind in ("move_end", "set_position"):
        if abs(dx["position"] * scale - dy["position"]) > POSITION_TOLERANCE + 1e-6:
            return f"axis {dx['axis']} is at {dx['position'] * scale:g} steps in the source, at " \
                   f"{dy['position']:g} in the output"
        return ""
    if x.kind == "home_end":  # where the homing left the axis and the machine's zero (docs/SIMULATOR.md)
        for key, what in (("machine", "stops at machine position"), ("zero", "has its zero at machine position"),
                          ("position", "reads")):
            if key in dx and abs(dx[key] * scale - dy.get(key, float("inf"))) > POSITION_TOLERANCE + 1e-6:
                return f"after homing, axis {dx['axis']} {what} {dx[key] * scale:g} steps in the source, " \
                       f"{dy.get(key, float('nan')):g} in the output"
        return ""
    if x.kind == "slew":
        if abs(dx["velocity"] * scale - dy["velocity"]) > max(1.0, share * abs(dy["velocity"])) + 1e-6:
            return f"axis {dx['axis']} slews at {dx['velocity'] * scale:g} steps/s in the source, at " \
                   f"{dy['velocity']:g} in the output"
        return ""
    if x.kind == "print":
        # exactly: the characters and whether the line ends. The trace's "\n" is the IR's line end,
        # which each device sends in its own convention (MCode CR/LF, lexium-mcode.txt L4895, L4906;
        # X150 CR, parker-x150.md L3141): that convention is the only thing not compared
        # (docs/CROSS.md, "Prints")
        if dx["text"] != dy["text"]:
            return f"the source prints {dx['text']!r}, the output {dy['text']!r}"
        return ""
    if x.kind == "native":
        if (dx["mnemonic"], dx["args"]) != (dy["mnemonic"], dy["args"]):
            return f"{_show(x)} in the source, {_show(y)} in the output"
        return ""
    for key in ("output", "value", "code", "ramp", "switch", "event", "on"):
        if key in dx and dx[key] != dy.get(key):
            return f"{_show(x)} in the source, {_show(y)} in the output"
    return ""


def _show(event: Event) -> str:
    d = event.data
    if event.kind == "move":
        return "move " + ", ".join(f"{a} to {t:g}" for a, t in d["to"].items())
    if event.kind == "output":
        return f"set output {d['output']} to {d['value']}"
    if event.kind == "print":
        return f"print {d['text']!r}"
    if event.kind == "error":
        return f"stop with error {d['code']}"
    details = ", ".join(f"{k} {v}" for k, v in d.items())
    return f"{event.kind.replace('_', ' ')}" + (f" ({details})" if details else "")


def _last_line(trace: Trace) -> int | None:
    for event in reversed(trace.events):
        if event.line is not None:
            return event.line
    return None


def check_translation(path: str, dialect: str, before: str | ir.Module, after_text: str, after_dialect: str | None = None,
                      profile=None, scenarios: list[Scenario] | None = None, source_profile=None) -> str:
    """Why the translation of `path` into `after_text` cannot be trusted, or "" when it verifies.

    `before` is the source text (or its module, already lowered); the translation is lowered as
    `after_dialect` (default: the same dialect). Used by `mcc compile --verify`, `mcc fmt --verify`
    and `mcc lint --fix --verify`: a non-empty answer means nothing is written. `source_profile`
    is the source's product when it is not `profile`'s (a migration between MCode families)."""
    from mcc.compiler import dialects, driver
    from mcc.sim.interpreter import ContractError

    target = after_dialect or dialect
    if isinstance(before, ir.Module):
        source = before
    else:
        checked = driver.check_file(path, dialect, source_profile or profile, before)
        if checked.analysis is None or checked.analysis.module is None or checked.has_errors:
            return "the source has errors, so it cannot be simulated"
        source = checked.analysis.module
    out_profile = profile if profile is not None and profile.dialect == target else None
    written = driver.check_file(path, target, out_profile, after_text, memory=False)
    if written.analysis is None or written.analysis.module is None or written.has_errors:
        return "the written program has errors, so it cannot be simulated"
    if source_profile is None and source.dialect == target and same_program(source, written.analysis.module):
        return ""  # the same operations in the same order: nothing a run could tell apart
    # (not between two products: the same operations may read other numbers there, I5 on an
    # MDrivePlus and on a Lexium drive, Arcus DI = 255 and MCode IN = 255 on 8 and 4 inputs)
    src_profile = source_profile or (profile if profile is not None and profile.dialect == source.dialect else None)
    try:
        src_profile = src_profile or driver.profile_for(dialects.get(source.dialect), None)
        out_profile = out_profile or driver.profile_for(dialects.get(target), None)
        found = compare(source, written.analysis.module, scenarios, None, src_profile, out_profile)
    except ContractError as exc:
        return f"cannot verify: {exc} (the frontend does not keep the IR contract yet)"
    return str(found) if found is not None else ""


def same_program(a: ir.Module, b: ir.Module) -> bool:
    """Whether two modules are the same program, source lines aside, in the code that can run: a
    rewrite that only re-spells the text (spacing, case, comments) or drops blocks no path reaches
    lowers to the same IR there, and needs no simulation."""
    from mcc.compiler.opt.manager import fingerprint

    return fingerprint(a) == fingerprint(b)


def explain(problem: str) -> str:
    """A `check_translation` answer as a sentence for the user: a divergence, or why none could be
    looked for (either way nothing is written)."""
    if problem.startswith(("cannot verify", "the source has errors", "the written program has errors")):
        return f"cannot check the new program: {problem.removeprefix('cannot verify: ')}"
    return f"the new program does not behave like the original: {problem}"

