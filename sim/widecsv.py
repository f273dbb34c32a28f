"""`--trace run.csv`: the run as one wide table a spreadsheet opens as it is.

One row per moment something happens (a motion sample or an event), by time; the columns are
`time (s)`, then for each axis in natural order (X Y Z U, 1 2 3) its position and speed in steps
(and in revolutions and rpm, or millimetres and mm/s, where the profile knows the scale), then
each input and output that changes, holding its level from its first change on (empty before:
the run has not told), then `events`: what happened at that row's time, in words. Positions
between two samples are interpolated (motion between samples is a straight line or a ramp
sampled finely enough to draw). `mcc sim --format csv` keeps the long form (one row per record).
"""

from __future__ import annotations

import csv
import io
import json

from mcc.sim.plotdata import axis_order, build
from mcc.sim.trace import Trace, _num


def header_and_rows(trace: Trace, profile=None) -> tuple[list[str], list[list]]:
    data = build(trace, profile)
    series = sorted(data.axes + [s for s in _still_series(trace, profile, data)], key=lambda s: axis_order(s.name))
    header = ["time (s)"]
    for s in series:
        header += [f"{s.name} position (steps)", f"{s.name} speed (steps/s)"]
        if s.scale.unit != "steps":
            header += [f"{s.name} position ({s.scale.unit})", f"{s.name} speed ({s.scale.speed_unit})"]
    signals = data.signals()
    header += [("input " if name.startswith("in ") else "output ") + name.split(" ", 1)[1] for name in signals]
    header.append("events")

    times = sorted({round(t, 9) for s in series for t in s.times} | {round(e.t, 9) for e in trace.events})
    happened: dict[float, list[str]] = {}
    for event in trace.events:
        happened.setdefault(round(event.t, 9), []).append(describe(event))
    changes = sorted(data.changes, key=lambda c: c.t)
    level: dict[str, int] = {}
    rows = []
    k = 0
    for t in times:
        while k < len(changes) and round(changes[k].t, 9) <= t:
            level[changes[k].signal] = changes[k].value
            k += 1
        row: list = [_num(t)]
        for s in series:
            steps, speed = s.at(t)
            row += [_num(steps), _num(speed)]
            if s.scale.unit != "steps":
                row += [_num(s.scale.position(steps)), _num(s.scale.speed(speed))]
        row += [level.get(name, "") for name in signals]
        row.append("; ".join(happened.get(t, [])))
        rows.append(row)
    return header, rows


def _still_series(trace: Trace, profile, data):
    """The axes the plot leaves out (they never move) still get their columns in the table."""
    from mcc.sim.plotdata import AxisSeries, mm_per_rev, scale_for

    for name in data.still:
        points = trace.samples.get(name, [])
        scale = scale_for(trace.steps_per_rev, mm_per_rev(profile, name))
        yield AxisSeries(name, scale, [p[0] for p in points], [scale.position(p[1]) for p in points],
                         [scale.speed(p[2]) for p in points], [p[1] for p in points], [p[2] for p in points])


def describe(event) -> str:
    d = event.data
    where = f" (line {event.line})" if event.line is not None else ""
    if event.kind in ("input", "output"):
        return f"{event.kind} {d[event.kind]} = {d['value']}{where}"
    if event.kind == "move" and "to" in d:
        start = d.get("from", {})
        moves = ", ".join(f"{a} {_num(start.get(a, 0))} -> {_num(t)}" for a, t in d["to"].items())
        return f"move {d.get('mode', '')}: {moves}{where}"
    if event.kind in ("move_end", "set_position") and "axis" in d:
        return f"{event.kind.replace('_', ' ')} {d['axis']} at {_num(d.get('position', 0))}{where}"
    if event.kind == "print":
        return f"print {d.get('text', '').rstrip(chr(10))!r}{where}"
    detail = json.dumps({k: v for k, v in d.items()}, sort_keys=True, default=str) if d else ""
    return f"{event.kind}{' ' + detail if detail else ''}{where}"


def to_wide_csv(trace: Trace, profile=None) -> str:
    header, rows = header_and_rows(trace, profile)
    buffer = io.StringIO()
    writer = csv.writer(buffer)  # RFC 4180: comma, quotes where needed, CRLF line ends
    writer.writerow(header)
    writer.writerows(rows)
    return buffer.getvalue()
