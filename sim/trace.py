"""What a simulation run leaves behind: its events, sampled motion and final state.

The trace is the simulator's one output: `mcc sim` prints it, `--trace` writes it as JSON or CSV,
`--plot` draws it, and `sim.verify` compares two of them. Its shape is documented in
docs/SIMULATOR.md ("Trace").
"""

from __future__ import annotations

import csv
import io
import json
from dataclasses import dataclass, field
from typing import Any

from mcc.compiler.diagnostics import Diagnostic

STOP_REASONS = ("end", "time-limit", "step-limit", "waiting", "error")


@dataclass(slots=True)
class Event:
    t: float
    kind: str
    line: int | None
    data: dict[str, Any] = field(default_factory=dict)

    def to_json(self) -> dict[str, Any]:
        out: dict[str, Any] = {"t": round(self.t, 6), "kind": self.kind, "line": self.line}
        out.update({key: _plain(value) for key, value in self.data.items()})
        return out


def _plain(value: Any) -> Any:
    """Numbers as the trace shows them (whole floats as integers), inside dicts and lists too."""
    if isinstance(value, float):
        return _num(value)
    if isinstance(value, dict):
        return {k: _plain(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_plain(v) for v in value]
    return value


@dataclass
class Trace:
    path: str
    dialect: str
    steps_per_rev: int
    stopped: str = "end"
    reason: str = ""  # one sentence: why the run stopped
    time: float = 0.0
    steps: int = 0
    axes: dict[str, float] = field(default_factory=dict)
    outputs: dict[int, int] = field(default_factory=dict)
    variables: dict[str, int | float] = field(default_factory=dict)
    events: list[Event] = field(default_factory=list)
    prints: list[tuple[float, str]] = field(default_factory=list)
    diagnostics: list[Diagnostic] = field(default_factory=list)
    # what the axes did, recorded cheaply while running: (axis, motion, until) and (axis, t, position)
    motion_log: list[tuple[str, Any, float]] = field(default_factory=list)
    points: list[tuple[str, float, float]] = field(default_factory=list)
    # (loop header, time) each time the main routine enters a loop header: sim/cycles.py
    cycle_marks: list[tuple[str, float]] = field(default_factory=list)
    # a run stopped polling ("waiting") while its loop still made events each round (a HOME on a
    # switch that is already active, over and over at one instant): the index of the first event of
    # that stretch without a change, whose rounds repeat for ever; None otherwise (sim/verify.py)
    repeats_from: int | None = None
    _samples: dict | None = None

    @property
    def samples(self) -> dict[str, list[tuple[float, float, float]]]:
        """Sampled motion per axis: (t, position in steps, signed speed in steps/s), by time.

        Computed on first use from the motions the run recorded, so a run that nobody plots or
        writes out does not pay for it."""
        if self._samples is None:
            out: dict[str, list[tuple[float, float, float]]] = {}
            for axis, motion, until in self.motion_log:
                out.setdefault(axis, []).extend(sample_motion(axis, motion, until))
            for axis, t, pos in self.points:
                out.setdefault(axis, []).append((t, pos, 0.0))
            for points in out.values():
                points.sort(key=lambda p: p[0])
            self._samples = out
        return self._samples

    def to_json(self, motion: bool = False) -> dict[str, Any]:
        """The file entry of `mcc sim --format json` (and, with motion, of `--trace x.json`)."""
        out: dict[str, Any] = {
            "path": self.path,
            "dialect": self.dialect,
            "stopped": self.stopped,
            "reason": self.reason,
            "time": round(self.time, 6),
            "steps": self.steps,
            "axes": {axis: {"position": _num(pos)} for axis, pos in sorted(self.axes.items())},
            "outputs": {str(n): v for n, v in sorted(self.outputs.items())},
            "variables": {name: _num(v) for name, v in sorted(self.variables.items())},
            "events": [e.to_json() for e in self.events],
            "diagnostics": [d.to_json() for d in sorted(self.diagnostics, key=Diagnostic.sort_key)],
        }
        if motion:
            out["motion"] = {axis: [[round(t, 6), _num(p), round(v, 6)] for t, p, v in points]
                             for axis, points in sorted(self.samples.items())}
        return out


SAMPLES_PER_RAMP = 6
SAMPLES_PER_ARC_SEGMENT = 24  # a segment of an arc: each axis follows a sine, drawn as 24 chords


def sample_motion(axis: str, motion, until: float) -> list[tuple[float, float, float]]:
    """Points of one axis along a motion up to `until`: the ends of each segment, and
    SAMPLES_PER_RAMP steps inside each ramp (a cruise along a line is a straight line; along an arc
    each segment gets SAMPLES_PER_ARC_SEGMENT steps)."""
    path = motion.path
    if not motion.segments:
        return []
    out = [(motion.segments[0].t0, path.at(motion.segments[0].s0)[axis], 0.0)]  # at rest before it starts
    for seg in motion.segments:
        if seg.t0 >= until:
            break
        end = min(seg.t1, until)
        n = SAMPLES_PER_RAMP if seg.v0 != seg.v1 else 1
        if path.arc is not None:  # along an arc no axis moves in a straight line, even at constant speed
            n = max(n, SAMPLES_PER_ARC_SEGMENT)
        for k in range(n + 1):
            t = seg.t0 + (end - seg.t0) * k / n
            s = seg.distance(t)
            out.append((t, path.at(s)[axis], seg.speed(t) * path.axis_rate(axis, s)))
    last_t, last_pos, _ = out[-1]
    out.append((last_t, last_pos, 0.0))  # at rest once it ends (a step from the initial speed), or is cut
    return out


def _num(value: float) -> int | float:
    rounded = round(float(value), 6)
    return int(rounded) if rounded.is_integer() else rounded


def to_json_text(traces: list[Trace], motion: bool = True) -> str:
    return json.dumps({"files": [t.to_json(motion) for t in traces]}, indent=2) + "\n"


CSV_COLUMNS = ["path", "t", "record", "kind", "line", "axis", "position", "speed", "detail"]


def to_csv_text(traces: list[Trace]) -> str:
    """One row per event (record "event") and per motion sample (record "motion"), by time."""
    buffer = io.StringIO()
    writer = csv.writer(buffer, lineterminator="\n")
    writer.writerow(CSV_COLUMNS)
    for trace in traces:
        rows: list[tuple[float, int, list]] = []
        for n, event in enumerate(trace.events):
            detail = json.dumps(event.data, sort_keys=True) if event.data else ""
            axis = event.data.get("axis", "")
            rows.append((event.t, n, [trace.path, round(event.t, 6), "event", event.kind,
                                      event.line if event.line is not None else "", axis, "", "", detail]))
        for axis, points in sorted(trace.samples.items()):
            for t, pos, speed in points:
                rows.append((t, 1 << 30, [trace.path, round(t, 6), "motion", "", "", axis, _num(pos),
                                          round(speed, 6), ""]))
        rows.sort(key=lambda r: (r[0], r[1]))
        for _, _, row in rows:
            writer.writerow(row)
    return buffer.getvalue()
