"""What `mcc sim --plot` and `--trace x.csv` show, worked out once from a trace, with no drawing
library: the axes that move, in their natural order, in the units the profile knows; each input
and output change with a label; the XY path of interpolated moves; the title.

The renderers (`sim.plot` through matplotlib for PNG/SVG/PDF, `sim.plot_html` for the interactive
page) and the wide CSV table (`sim.widecsv`) draw from this, so they agree on every number.
"""

from __future__ import annotations

import math
import os
from bisect import bisect_right
from dataclasses import dataclass, field

from mcc.sim.trace import Trace

AXIS_LETTERS = "XYZUVWABC"  # the order a machinist reads axes in


def axis_order(name: str) -> tuple:
    """X Y Z U V W A B C, then numbered axes 1 2 3 ... by number, then any other name."""
    upper = name.upper()
    if len(upper) == 1 and upper in AXIS_LETTERS:
        return (0, AXIS_LETTERS.index(upper), 0, name)
    if name.isdigit():
        return (1, 0, int(name), name)
    return (2, 0, 0, name)


@dataclass(frozen=True)
class Scale:
    """How steps become the units shown: steps (no scale known), revolutions (the profile's or the
    program's steps per revolution) or millimetres (also the profile's `machine.mm_per_rev`)."""

    per_step: float = 1.0  # shown units per step
    unit: str = "steps"
    speed_unit: str = "steps/s"
    speed_factor: float = 1.0  # speed in shown units per (steps/s)

    def position(self, steps: float) -> float:
        return steps * self.per_step

    def speed(self, steps_per_s: float) -> float:
        return steps_per_s * self.speed_factor


def scale_for(steps_per_rev: float, mm_per_rev: float | None = None) -> Scale:
    if steps_per_rev and steps_per_rev > 0:
        if mm_per_rev and mm_per_rev > 0:
            per_step = mm_per_rev / steps_per_rev
            return Scale(per_step, "mm", "mm/s", per_step)
        return Scale(1.0 / steps_per_rev, "rev", "rpm", 60.0 / steps_per_rev)
    return Scale()


def mm_per_rev(profile, axis: str) -> float | None:
    """The profile's `[machine] mm_per_rev`: one number for every axis, or a table per axis."""
    if profile is None:
        return None
    value = profile.get("machine.mm_per_rev")
    if isinstance(value, dict):
        value = value.get(axis)
    return float(value) if isinstance(value, (int, float)) and not isinstance(value, bool) and value > 0 else None


@dataclass
class AxisSeries:
    name: str
    scale: Scale
    times: list[float]
    positions: list[float]  # in scale.unit
    speeds: list[float]  # in scale.speed_unit
    steps: list[float]  # positions in steps (the CSV keeps them)
    steps_per_s: list[float]

    def at(self, t: float) -> tuple[float, float]:
        """(position in steps, speed in steps/s) at time t: linear between samples, the last
        sample at a time when there are several (a speed that jumps)."""
        if not self.times:
            return 0.0, 0.0
        i = bisect_right(self.times, t) - 1
        if i < 0:
            return self.steps[0], 0.0
        if i >= len(self.times) - 1 or self.times[i] == t:
            return self.steps[i], self.steps_per_s[i]
        t0, t1 = self.times[i], self.times[i + 1]
        f = (t - t0) / (t1 - t0) if t1 > t0 else 1.0
        return (self.steps[i] + (self.steps[i + 1] - self.steps[i]) * f,
                self.steps_per_s[i] + (self.steps_per_s[i + 1] - self.steps_per_s[i]) * f)


@dataclass(frozen=True)
class Change:
    """One input or output change."""

    t: float
    kind: str  # "input" or "output"
    index: int
    value: int
    line: int | None
    cause: str = ""  # "axis X passed 2000" for an input set by a position

    @property
    def signal(self) -> str:
        return f"{'in' if self.kind == 'input' else 'out'} {self.index}"

    @property
    def label(self) -> str:
        where = f" (line {self.line})" if self.line is not None else ""
        cause = f" ({self.cause})" if self.cause else ""
        return f"{self.kind} {self.index} \u2192 {self.value} at {self.t:.3f} s{where}{cause}"


@dataclass
class PlotData:
    title: str
    subtitle: str
    duration: float
    axes: list[AxisSeries] = field(default_factory=list)  # the axes that move, in natural order
    still: list[str] = field(default_factory=list)  # the axes left out: they never move
    changes: list[Change] = field(default_factory=list)
    xy: tuple[str, str] | None = None  # the two axes of interpolated moves
    xy_paths: list[list[tuple[float, float]]] = field(default_factory=list)  # in the axes' units
    xy_track: list[tuple[float, float]] = field(default_factory=list)  # where the two axes were, all run long
    prints: list[tuple[float, str]] = field(default_factory=list)

    def signals(self) -> list[str]:
        """Each input and output that changes, inputs first, by number."""
        seen = {(c.kind != "input", c.index): c.signal for c in self.changes}
        return [seen[key] for key in sorted(seen)]


def relative_name(path: str) -> str:
    """The file's name relative to the current directory (absolute when it lies elsewhere)."""
    if not path or path.startswith("<") or not os.path.exists(path):
        return path or "program"
    rel = os.path.relpath(path)
    return path if rel.startswith("..") else rel


def build(trace: Trace, profile=None) -> PlotData:
    shown = relative_name(trace.path)
    subtitle = f"{trace.dialect}: stopped: {trace.stopped} at {trace.time:.3f} s ({trace.reason})" \
        if trace.reason else f"{trace.dialect}: stopped: {trace.stopped} at {trace.time:.3f} s"
    data = PlotData(shown, subtitle, trace.time, prints=list(trace.prints))
    for name in sorted(trace.samples, key=axis_order):
        points = trace.samples[name]
        scale = scale_for(trace.steps_per_rev, mm_per_rev(profile, name))
        series = AxisSeries(name, scale, [p[0] for p in points], [scale.position(p[1]) for p in points],
                            [scale.speed(p[2]) for p in points], [p[1] for p in points], [p[2] for p in points])
        moves = any(abs(p[2]) > 0 for p in points) or len({round(p[1], 9) for p in points}) > 1
        (data.axes.append(series) if moves else data.still.append(name))
    for event in trace.events:
        if event.kind in ("input", "output"):
            d = event.data
            cause = f"axis {d['axis']} passed {d['passes']:g}" if "passes" in d and "axis" in d else ""
            data.changes.append(Change(event.t, event.kind, int(d[event.kind]), int(d["value"]), event.line, cause))
    xy_paths(trace, data)
    return data


XY_SAMPLES_PER_MOVE = 64  # points along one interpolated move (a line needs 2; an arc gets them all)


def xy_paths(trace: Trace, data: PlotData) -> None:
    """The tool path in the plane of the first two moving axes, from the moves that drive both at
    once (linear or circular interpolation); one polyline per run of connected moves."""
    if len(data.axes) < 2:
        return
    first, second = data.axes[0], data.axes[1]
    done: set[int] = set()
    for axis, motion, until in trace.motion_log:
        ident = id(motion)
        if ident in done or not motion.segments:
            continue
        path = motion.path
        names = set(path.direction) if path.arc is None else {path.arc[0], path.arc[1]}
        if path.arc is None:
            names = {n for n in names if path.direction[n] != 0}
        if not {first.name, second.name} <= names:
            continue
        done.add(ident)
        end_s = motion.distance(min(until, motion.t_end))
        if not math.isfinite(end_s):
            continue
        n = XY_SAMPLES_PER_MOVE if path.arc is not None else 1
        points = []
        for k in range(n + 1):
            at = path.at(end_s * k / n)
            points.append((first.scale.position(at[first.name]), second.scale.position(at[second.name])))
        if data.xy_paths and data.xy_paths[-1][-1] == points[0]:
            data.xy_paths[-1].extend(points[1:])
        else:
            data.xy_paths.append(points)
    if data.xy_paths:
        data.xy = (first.name, second.name)
        times = sorted(set(first.times) | set(second.times))
        step = max(1, len(times) // 5000)
        for t in times[::step] + times[-1:]:
            x, y = first.at(t)[0], second.at(t)[0]
            data.xy_track.append((first.scale.position(x), second.scale.position(y)))
