"""`--plot OUT`: what a run did, drawn for people (docs/SIMULATOR.md, "Plots").

The suffix of OUT says what is written: `.png`, `.svg`, `.pdf` (drawn with matplotlib) or `.html`
(an interactive page drawn by `sim.plot_html`, which needs no plotting library). Any other suffix
is refused before the program runs. Per moving axis, in natural order (X Y Z U, 1 2 3): position
and speed against time, in revolutions and rpm (or millimetres) where the scale is known; axes
that never move are left out and named in the title. Each input and output change is a vertical
line with a legend entry, and the lanes of the I/O row show each signal's level; moves that drive
two axes at once are drawn as the XY path of the tool.

matplotlib is an optional extra (`pip install 'mcc[plot]'`): mcc itself never needs it, so it is
imported only here, and its absence is a clear message rather than a traceback.
"""

from __future__ import annotations

import io
import os

from mcc.sim.plotdata import PlotData, build
from mcc.sim.trace import Trace

INSTALL_HINT = "plotting needs matplotlib: install it with `pip install 'mcc[plot]'` (or `pip install matplotlib`)"
IMAGE_FORMATS = ("png", "svg", "pdf")  # drawn by matplotlib
FORMATS = (*IMAGE_FORMATS, "html")
LEGEND_MAX = 24  # changes listed one by one in the legend; the rest are counted
# matplotlib's tab10 as CSS colours, so the images and the HTML page colour each signal alike
SIGNAL_COLOURS = ["#2ca02c", "#d62728", "#9467bd", "#8c564b", "#e377c2", "#bcbd22", "#17becf", "#7f7f7f",
                  "#1f77b4", "#ff7f0e"]


class PlotUnavailable(Exception):
    """matplotlib is not installed."""


class PlotError(Exception):
    """OUT has a suffix mcc cannot draw."""


def plot_format(out: str) -> str:
    """The format OUT's suffix asks for, or PlotError with what is possible."""
    suffix = os.path.splitext(out)[1].lower().lstrip(".")
    if suffix not in FORMATS:
        shown = f"'.{suffix}'" if suffix else "no suffix"
        raise PlotError(f"cannot plot to {out}: {shown} is not a plot format; name the file .png, .svg, .pdf "
                        "(images) or .html (an interactive page)")
    return suffix


def needs_matplotlib(out: str) -> bool:
    return plot_format(out) in IMAGE_FORMATS


def plot(trace: Trace, out: str, profile=None) -> None:
    """Draw the run into `out`, in the format its suffix names."""
    fmt = plot_format(out)
    data = build(trace, profile)
    if fmt == "html":
        from mcc.sim.plot_html import render
        from mcc.compiler.lint.files import write_atomic

        write_atomic(out, render(data))
        return
    draw(data, out, fmt)


def signal_colours(data: PlotData) -> dict[str, str]:
    return {name: SIGNAL_COLOURS[i % len(SIGNAL_COLOURS)] for i, name in enumerate(data.signals())}


def draw(data: PlotData, out: str, fmt: str) -> None:
    try:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        raise PlotUnavailable(INSTALL_HINT) from None
    matplotlib.rcParams["svg.hashsalt"] = "mcc"  # the same run gives the same file
    matplotlib.rcParams["svg.fonttype"] = "none"  # text stays text in an SVG: searchable, selectable
    colours = signal_colours(data)
    rows = len(data.axes) + (1 if data.changes else 0)
    heights = [2.4] * len(data.axes) + ([1.0 + 0.35 * len(colours)] if data.changes else [])
    if data.xy:
        heights.append(4.5)
    if not heights:
        heights = [1.5]
    fig = plt.figure(figsize=(12, sum(heights) + 1.2))
    grid = fig.add_gridspec(len(heights), 2, height_ratios=heights)
    first = None
    for row, series in enumerate(data.axes):
        pos = fig.add_subplot(grid[row, 0], sharex=first)
        first = first or pos
        speed = fig.add_subplot(grid[row, 1], sharex=first)
        pos.plot(series.times, series.positions, color="tab:blue", linewidth=1.2)
        pos.set_ylabel(f"axis {series.name}\nposition ({series.scale.unit})")
        speed.plot(series.times, series.speeds, color="tab:orange", linewidth=1.2)
        speed.set_ylabel(f"speed ({series.scale.speed_unit})")
        for cell in (pos, speed):
            cell.grid(True, alpha=0.3)
            mark_changes(cell, data, colours)
    if data.changes:
        lanes = fig.add_subplot(grid[rows - 1, :], sharex=first)
        draw_lanes(lanes, data, colours)
    elif data.axes:
        for cell in fig.axes[-2:]:
            cell.set_xlabel("time (s)")
    if data.xy:
        xy = fig.add_subplot(grid[len(heights) - 1, :])
        draw_xy(xy, data)
    if not data.axes and not data.changes:
        cell = fig.add_subplot(grid[0, :])
        cell.axis("off")
        cell.text(0.5, 0.5, "no axis moved and no input or output changed", ha="center", va="center")
    title = data.title + "\n" + data.subtitle
    if data.still:
        title += f"\naxes that never move (not shown): {', '.join(data.still)}"
    fig.suptitle(title, fontsize=10)
    fig.tight_layout()
    metadata = {"svg": {"Date": None}, "pdf": {"CreationDate": None}, "png": None}[fmt]
    image = io.BytesIO()
    fig.savefig(image, format=fmt, dpi=100, metadata=metadata)
    plt.close(fig)
    from mcc.compiler.files import write_many

    write_many([(out, image.getvalue())])  # atomically, as every file mcc writes (docs/CLI.md, "Files")


def mark_changes(cell, data: PlotData, colours: dict[str, str]) -> None:
    for change in data.changes:
        cell.axvline(change.t, color=colours[change.signal], linestyle="-" if change.value else "--",
                     linewidth=0.8, alpha=0.6)


def draw_lanes(cell, data: PlotData, colours: dict[str, str]) -> None:
    """One lane per signal: its level as a step line from its first change, and one legend entry
    per change (listed up to LEGEND_MAX, the rest counted)."""
    signals = data.signals()
    end = max(data.duration, max(c.t for c in data.changes))
    for lane, name in enumerate(reversed(signals)):
        mine = [c for c in data.changes if c.signal == name]
        times = [c.t for c in mine] + [end]
        levels = [c.value for c in mine] + [mine[-1].value]
        cell.step(times, [lane + 0.8 * v for v in levels], where="post", color=colours[name], linewidth=1.4)
    for n, change in enumerate(data.changes):
        lane = len(signals) - 1 - signals.index(change.signal)
        label = change.label if n < LEGEND_MAX else None
        cell.plot([change.t], [lane + 0.8 * change.value], marker="^" if change.value else "v",
                  color=colours[change.signal], linestyle="none", label=label)
    if len(data.changes) > LEGEND_MAX:
        cell.plot([], [], linestyle="none", label=f"... {len(data.changes) - LEGEND_MAX} more changes")
    cell.set_yticks([lane + 0.4 for lane in range(len(signals))], list(reversed(signals)))
    cell.set_ylim(-0.3, len(signals))
    cell.set_xlabel("time (s)")
    cell.set_ylabel("inputs and outputs")
    cell.grid(True, axis="x", alpha=0.3)
    cell.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=7, frameon=False,
                title="changes (\u25b2 on, \u25bc off)", title_fontsize=8)


def draw_xy(cell, data: PlotData) -> None:
    first, second = data.xy
    units = {s.name: s.scale.unit for s in data.axes}
    if data.xy_track:
        cell.plot([p[0] for p in data.xy_track], [p[1] for p in data.xy_track], color="0.7", linewidth=0.8,
                  linestyle="--", label=f"{first} and {second} over the whole run")
    for n, points in enumerate(data.xy_paths):
        xs, ys = [p[0] for p in points], [p[1] for p in points]
        cell.plot(xs, ys, color="tab:blue", linewidth=1.2, label="interpolated moves" if n == 0 else None)
        cell.plot([xs[0]], [ys[0]], marker="o", color="tab:green", markersize=4)
        cell.plot([xs[-1]], [ys[-1]], marker="s", color="tab:red", markersize=4)
    cell.set_xlabel(f"{first} ({units[first]})")
    cell.set_ylabel(f"{second} ({units[second]})")
    cell.set_aspect("equal", adjustable="datalim")
    cell.grid(True, alpha=0.3)
    cell.set_title(f"XY path of the moves that drive {first} and {second} together (\u25cf start, \u25a0 end)",
                   fontsize=9)
    cell.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=7, frameon=False)
