"""`--plot`: position and speed against time per axis, with input and output events marked.

matplotlib is an optional extra (`pip install 'mcc[plot]'`): mcc itself never needs it, so it is
imported only here, and its absence is a clear message rather than a traceback.
"""

from __future__ import annotations

from mcc.sim.trace import Trace

INSTALL_HINT = "plotting needs matplotlib: install it with `pip install 'mcc[plot]'` (or `pip install matplotlib`)"


class PlotUnavailable(Exception):
    """matplotlib is not installed."""


def plot(trace: Trace, out: str) -> None:
    """Draw the trace into `out` (.png or .svg, chosen by the extension)."""
    try:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        raise PlotUnavailable(INSTALL_HINT) from None
    axes_names = sorted(trace.samples) or ["-"]
    fig, rows = plt.subplots(len(axes_names), 2, figsize=(11, 2.6 * len(axes_names) + 0.6), squeeze=False,
                             sharex=True)
    for row, name in zip(rows, axes_names):
        points = trace.samples.get(name, [])
        times = [p[0] for p in points]
        row[0].plot(times, [p[1] for p in points], color="tab:blue")
        row[0].set_ylabel(f"axis {name}\nposition (steps)")
        row[1].plot(times, [p[2] for p in points], color="tab:orange")
        row[1].set_ylabel("speed (steps/s)")
        for cell in row:
            cell.grid(True, alpha=0.3)
            _mark_events(cell, trace)
    for cell in rows[-1]:
        cell.set_xlabel("time (s)")
    title = f"{trace.path or 'program'} ({trace.dialect}): stopped: {trace.stopped} at {trace.time:.3f} s"
    fig.suptitle(title, fontsize=10)
    fig.tight_layout()
    fig.savefig(out, format="svg" if out.lower().endswith(".svg") else "png", dpi=100,
                metadata={"Date": None} if out.lower().endswith(".svg") else None)
    plt.close(fig)


def _mark_events(cell, trace: Trace) -> None:
    for event in trace.events:
        if event.kind == "input":
            cell.axvline(event.t, color="tab:green", linestyle="--", linewidth=0.8, alpha=0.7)
        elif event.kind == "output":
            cell.axvline(event.t, color="tab:red", linestyle=":", linewidth=0.8, alpha=0.7)
