"""`--verify`: run a source and its translation on the same scenarios and compare what they do.

A translation (compile to the same or another dialect, fmt, lint --fix, an optimizer pass) must
not change what the machine does. `compare(source, output, scenarios)` simulates both modules on
each scenario and compares their traces in the IR's units (docs/SIMULATOR.md, "Verification"):

- the **observable events** in order: moves (their end positions), arcs, slews, stops, homing,
  position changes, outputs, prints, limit hits and runtime errors; not calls, returns or jumps,
  which a translation may restructure;
- **positions** after scaling the source's steps by `output steps_per_rev / source steps_per_rev`,
  within `POSITION_TOLERANCE` output steps (a converted position rounds to a whole step);
- **times** within `TIME_ABS + TIME_REL * t`: converted speeds and ramps are rounded to the
  target's resolution, so a move may end a little earlier or later;
- why the run **stopped**, and the final positions and outputs. A run cut by the time or the step
  limit is compared up to the earlier of the two cut-off times only.

The first difference is returned as a `Divergence` naming its time, source line and what differs.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from fractions import Fraction

from mcc.compiler import ir, units
from mcc.sim.interpreter import Options, simulate
from mcc.sim.scenario import AxisSwitches, InputEvent, Scenario
from mcc.sim.trace import Event, Trace

TIME_ABS = 0.01  # seconds
TIME_REL = 0.01  # share of the event's time
POSITION_TOLERANCE = 1.0  # output steps
OBSERVABLE = ("move", "arc", "slew", "stop", "home", "home_end", "set_position", "output", "print", "limit",
              "error", "move_end", "pause", "resume", "step")
# A stricter comparison for transformations that keep the program's structure of device commands
# (the optimizer, a backend reading back its own dialect): also the native commands in order, the
# handlers installed and removed, the drive switched on and off.
STRICT = OBSERVABLE + ("native", "handler_on", "handler_off", "drive")
LIMITS = ("time-limit", "step-limit")
VERIFY_UNTIL = 30.0
VERIFY_STEPS = 200_000
MAX_DRIVEN_INPUTS = 16


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


def default_scenarios(module: ir.Module) -> list[Scenario]:
    """Every input the program reads driven both ways: all low, all high, and each one rising
    then falling on its own."""
    read = inputs_read(module)
    # levels stated, not left to each product's idle state: an input no scenario drives is inactive
    # for the polarity in force, which is another level on another product (docs/SIMULATOR.md)
    out = [Scenario(inputs={n: 0 for n in read}, name="inputs low")]
    if not read:
        return out
    out.append(Scenario(inputs={n: 1 for n in read}, name="inputs high"))
    for n in read:
        out.append(Scenario(inputs={m: 0 for m in read}, events=[InputEvent(n, 1, at=0.5), InputEvent(n, 0, at=2.5)],
                            name=f"input {n} pulses high at 0.5 s"))
    return out


def compare(source: ir.Module, output: ir.Module, scenarios: list[Scenario] | None = None,
            options: Options | None = None, source_profile=None, output_profile=None,
            kinds: tuple[str, ...] = OBSERVABLE, by_count: bool = False) -> Divergence | None:
    """The first divergence between `source` and `output` on the scenarios, or None.

    Both modules must keep the IR contract (`interpreter.ContractError` otherwise)."""
    source, output = _stated_steps(source, output), _stated_steps(output, source)
    for scenario in scenarios or default_scenarios(source):
        scenario = with_idle_levels(scenario, source, source_profile, inputs_read(output))
        opts = options or Options(until=scenario.until or VERIFY_UNTIL, max_steps=VERIFY_STEPS)
        opts.samples = False
        ratio = units.ratio(source.steps_per_rev, output.steps_per_rev)
        a = simulate(source, scenario, _copy(opts), source_profile)
        b = simulate(output, scenario, _copy(opts), output_profile)
        moved = _translated(scenario, _axis_map(a, b), ratio)
        if moved is not scenario:  # the switches and positions of the output's axes, in its steps
            b = simulate(output, moved, _copy(opts), output_profile)
        found = compare_traces(a, b, ratio, scenario.name, kinds, by_count)
        if found is not None and not _another_interleaving(source, scenario, opts, source_profile, b, ratio,
                                                            kinds, by_count):
            return found
    return None


RACE_POINTS = 24  # the points of a polling round tried (rounds of random programs are shorter)


def _another_interleaving(source: ir.Module, scenario: Scenario, opts: Options, profile, output: Trace,
                          ratio: Fraction, kinds: tuple[str, ...], by_count: bool) -> bool:
    """Whether the source does what the output did when its polling loops let time pass at another
    point of their rounds. A loop that reads an input twice per round and leaves only when it
    changes between the reads is a race on a real controller; a rewrite that rotates the loop may
    take the other way, which the source could take too. Asked only after a divergence, so a
    scenario costs no more otherwise."""
    for offset in range(1, RACE_POINTS + 1):
        other = simulate(source, scenario, dataclasses.replace(_copy(opts), poll_offset=offset), profile)
        if compare_traces(other, output, ratio, scenario.name, kinds, by_count) is None:
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


def _copy(options: Options) -> Options:
    return Options(options.until, options.max_steps, options.nesting, options.spin, options.poll, False)


def compare_traces(a: Trace, b: Trace, ratio: Fraction = Fraction(1), scenario: str = "",
                   kinds: tuple[str, ...] = OBSERVABLE, by_count: bool = False) -> Divergence | None:
    """Compare two traces; positions of `a` are multiplied by `ratio` to be in `b`'s steps.

    `kinds` are the events compared (OBSERVABLE, or STRICT). A run cut by a limit is compared up to
    the earlier cut-off time, or with `by_count` on the events both made (a loop that never waits
    stops at the step limit at time 0, and a transformation may change the steps per round)."""
    cut = None
    limited = a.stopped in LIMITS or b.stopped in LIMITS
    if limited and not by_count:
        cut = min(a.time, b.time) - TIME_ABS
    elif not limited and a.stopped != b.stopped:
        return Divergence(scenario, min(a.time, b.time), _last_line(a),
                          f"the source stopped with '{a.stopped}' ({a.reason}), the output with '{b.stopped}' "
                          f"({b.reason})")
    axis_map = _axis_map(a, b)
    ea, eb = _observable(a, cut, kinds), _observable(b, cut, kinds)
    if limited and by_count:
        ea, eb = ea[:min(len(ea), len(eb))], eb[:min(len(ea), len(eb))]
    scale = float(ratio)
    for n in range(max(len(ea), len(eb))):
        if n >= len(ea):
            extra = eb[n]
            return Divergence(scenario, extra.t, None, f"the output does more: {_show(extra)} at {extra.t:.3f} s")
        if n >= len(eb):
            missing = ea[n]
            return Divergence(scenario, missing.t, missing.line, f"the output does not {_show(missing)}")
        x, y = ea[n], eb[n]
        problem = _differ(x, y, axis_map, scale)
        if problem:
            return Divergence(scenario, x.t, x.line, problem)
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


def _observable(trace: Trace, cut: float | None, kinds: tuple[str, ...] = OBSERVABLE) -> list[Event]:
    out = []
    for event in trace.events:
        if event.kind not in kinds or (cut is not None and event.t > cut):
            continue
        if event.kind == "move" and event.data["from"] == event.data["to"]:
            continue  # a move to where the axis already is does nothing
        if event.kind == "stop" and event.data.get("idle"):
            continue  # nor does a stop of an axis at standstill (a target's STOP of every axis)
        out.append(event)
    return out


def _axis_map(a: Trace, b: Trace) -> dict[str, str]:
    """Source axis -> output axis: the same name, else paired in order of first use."""
    def order(trace: Trace) -> list[str]:
        seen: list[str] = []
        for event in trace.events:
            names = list(event.data.get("to", {})) + ([event.data["axis"]] if "axis" in event.data else [])
            names += list(event.data.get("axes", []))
            seen += [n for n in names if n not in seen]
        return seen + [n for n in trace.axes if n not in seen]

    first, second = order(a), order(b)
    if set(first) <= set(second):
        return {n: n for n in first}
    return dict(zip(first, second))


def _close_time(x: float, y: float) -> bool:
    return abs(x - y) <= TIME_ABS + TIME_REL * max(abs(x), abs(y))


def _differ(x: Event, y: Event, axis_map: dict[str, str], scale: float) -> str:
    if x.kind != y.kind:
        return f"the source does {_show(x)}, the output {_show(y)} at {y.t:.3f} s"
    if not _close_time(x.t, y.t):
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
        if abs(dx["velocity"] * scale - dy["velocity"]) > max(1.0, abs(dy["velocity"]) * TIME_REL):
            return f"axis {dx['axis']} slews at {dx['velocity'] * scale:g} steps/s in the source, at " \
                   f"{dy['velocity']:g} in the output"
        return ""
    if x.kind == "print":
        if dx["text"].strip() != dy["text"].strip():
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
                      profile=None, scenarios: list[Scenario] | None = None) -> str:
    """Why the translation of `path` into `after_text` cannot be trusted, or "" when it verifies.

    `before` is the source text (or its module, already lowered); the translation is lowered as
    `after_dialect` (default: the same dialect). Used by `mcc compile --verify`, `mcc fmt --verify`
    and `mcc lint --fix --verify`: a non-empty answer means nothing is written."""
    from mcc.compiler import dialects, driver
    from mcc.sim.interpreter import ContractError

    target = after_dialect or dialect
    if isinstance(before, ir.Module):
        source = before
    else:
        checked = driver.check_file(path, dialect, profile, before)
        if checked.analysis is None or checked.analysis.module is None or checked.has_errors:
            return "the source has errors, so it cannot be simulated"
        source = checked.analysis.module
    out_profile = profile if profile is not None and profile.dialect == target else None
    written = driver.check_file(path, target, out_profile, after_text)
    if written.analysis is None or written.analysis.module is None or written.has_errors:
        return "the written program has errors, so it cannot be simulated"
    src_profile = profile if profile is not None and profile.dialect == source.dialect else None
    try:
        src_profile = src_profile or driver.profile_for(dialects.get(source.dialect), None)
        out_profile = out_profile or driver.profile_for(dialects.get(target), None)
        found = compare(source, written.analysis.module, scenarios, None, src_profile, out_profile)
    except ContractError as exc:
        return f"cannot verify: {exc} (the frontend does not keep the IR contract yet)"
    return str(found) if found is not None else ""


def explain(problem: str) -> str:
    """A `check_translation` answer as a sentence for the user: a divergence, or why none could be
    looked for (either way nothing is written)."""
    if problem.startswith(("cannot verify", "the source has errors", "the written program has errors")):
        return f"cannot check the new program: {problem.removeprefix('cannot verify: ')}"
    return f"the new program does not behave like the original: {problem}"

