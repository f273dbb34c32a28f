"""`mcc sim`: run a program on a virtual machine and show what it does (docs/SIMULATOR.md)."""

from __future__ import annotations

import sys

import click

from mcc.cli.commands import DIALECT_NAMES, check_profile_dialect, cli, load_profile, use_color
from mcc.cli.main import EXIT_ERRORS, EXIT_OK

SIM_FORMATS = ["text", "json", "csv"]
TIMELINE_MAX = 200  # events shown in the text timeline (the JSON has them all)


def load_scenario(path: str | None):
    """The --inputs option: a scenario TOML file (usage error when it is malformed)."""
    if not path:
        return None
    from mcc.sim import scenario

    try:
        return scenario.load(path)
    except scenario.ScenarioError as exc:
        raise click.BadParameter(str(exc), param_hint="--inputs") from None


@cli.command(name="sim")
@click.argument("file", type=click.Path(exists=True, dir_okay=False))
@click.option("--inputs", "inputs", type=click.Path(exists=True, dir_okay=False), metavar="SCENARIO.toml",
              help="What the world does while the program runs: input levels over time, inputs set when an "
                   "axis passes a position, home and limit switches (format: docs/SIMULATOR.md).")
@click.option("--until", type=click.FloatRange(min=0), metavar="SECONDS",
              help="Stop after this much virtual time (default: the scenario's `until`, else 60).")
@click.option("--max-steps", type=click.IntRange(min=1), default=1_000_000, show_default=True,
              help="Stop after this many executed operations (catches loops that never wait).")
@click.option("--dialect", type=DIALECT_NAMES, help="Dialect of FILE (default: from the extension).")
@click.option("--profile", help="Target profile: a built-in name or a path to a TOML file.")
@click.option("--format", "fmt", type=click.Choice(SIM_FORMATS), default="text", show_default=True,
              help="text: a summary and a timeline; json: the run as one JSON object; csv: the trace as CSV.")
@click.option("--trace", "trace_out", type=click.Path(dir_okay=False), metavar="OUT",
              help="Also write the full trace: OUT.csv a wide table for a spreadsheet (time, each axis's position "
                   "and speed, each input and output), else JSON (events and sampled motion).")
@click.option("--plot", "plot_out", type=click.Path(dir_okay=False), metavar="OUT.html|OUT.svg|OUT.pdf|OUT.png",
              help="Draw the run: position and speed per moving axis, input and output changes with a legend, the "
                   "XY path. .html is an interactive page (zoom, hover); .svg .pdf .png images need "
                   "`pip install 'mcc[plot]'`.")
@click.option("--sweep", is_flag=True,
              help="Run the program over generated input scenarios (every input it reads low, high, and toggling at "
                   "the times its waits need) and report the worst position each axis reaches, and the scenario.")
def sim_cmd(file: str, inputs: str | None, until: float | None, max_steps: int, dialect: str | None,
            profile: str | None, fmt: str, trace_out: str | None, plot_out: str | None, sweep: bool) -> None:
    """Run FILE on a virtual machine and report what it does.

    The simulator interprets the program's IR in virtual time: moves follow trapezoidal or S-curve
    profiles, inputs change as the scenario says, and nothing waits in real time. A run stops at
    the program's end, at the time or step limit, when the program waits for something the
    scenario never does ("waiting"), or on a runtime error (division by zero, stack overflow, a
    limit switch hit), which is reported with its source line.

    \b
    Examples:
      mcc sim program.prg
      mcc sim program.mxt --inputs start_button.toml --until 30
      mcc sim program.x150 --format json --trace run.csv --plot run.png
      mcc sim program.prg --plot run.html       an interactive page: zoom, hover

    Exit codes: 0 the program ran (to its end, a limit, or a wait), 1 errors (in the program or at
    run time), 2 usage error.
    """
    from mcc.cli import render
    from mcc.sim import Options
    from mcc.sim.files import simulate_file

    prof = load_profile(profile)
    scen = load_scenario(inputs)
    if plot_out:
        from mcc.sim.plot import INSTALL_HINT, PlotError, needs_matplotlib

        try:
            if needs_matplotlib(plot_out) and not _has_matplotlib():
                raise click.UsageError(INSTALL_HINT)
        except PlotError as exc:
            raise click.BadParameter(str(exc), param_hint="--plot") from None
    limit = until if until is not None else (scen.until if scen is not None and scen.until is not None else 60.0)
    options = Options(until=limit, max_steps=max_steps, travel=travel_of(file, dialect, prof))
    if sweep:
        _sweep(file, dialect, prof, options, fmt)
    done = simulate_file(file, dialect, prof, scen, options)
    check_profile_dialect(prof, {done.result.dialect})
    result, trace = done.result, done.trace
    failed = result.has_errors

    if trace is not None:
        from mcc.sim import trace as trace_mod
        from mcc.sim.files import _default_profile

        scale_profile = prof if prof is not None and prof.dialect == result.dialect else _default_profile(result)
        if trace_out:
            if trace_out.lower().endswith(".csv"):
                from mcc.sim.widecsv import to_wide_csv

                text = to_wide_csv(trace, scale_profile)
            else:
                text = trace_mod.to_json_text([trace])
            _write(trace_out, text)
        if plot_out:
            from mcc.sim.plot import PlotUnavailable, plot

            try:
                plot(trace, plot_out, scale_profile)
            except PlotUnavailable as exc:  # installed but broken: said, not a traceback
                raise click.UsageError(str(exc)) from None
            except OSError as exc:
                raise click.FileError(plot_out, hint=str(exc.strerror or exc)) from None

    if fmt == "json":
        if trace is not None:
            from mcc.sim.cycles import timing

            entry = trace.to_json()
            found = timing(trace)  # seconds: each pass of the main loop, each call (docs/SIMULATOR.md, "Envelope")
            entry["cycles"] = found.cycles
            entry["calls"] = found.calls
        else:  # the program could not run: the same shape, stopped with "error" before it started
            entry = {"path": result.path, "dialect": result.dialect, "stopped": "error",
                     "reason": "the program was not simulated (see diagnostics)", "time": 0, "steps": 0,
                     "axes": {}, "outputs": {}, "variables": {}, "events": []}
        entry["diagnostics"] = [d.to_json() for d in sorted(result.diagnostics, key=lambda d: d.sort_key())]
        click.echo(render.dump_json({"files": [entry]}))
    elif fmt == "csv" and trace is not None:
        from mcc.sim import trace as trace_mod

        sys.stdout.write(trace_mod.to_csv_text([trace]))
        _diagnostics(result, sys.stderr)
    else:
        _diagnostics(result, sys.stderr if fmt == "csv" else sys.stdout)
        if trace is not None and fmt == "text":
            writer = render.TextWriter(sys.stdout, use_color(fmt))
            for line, style in summary_lines(trace):
                writer.line(line, style)
    sys.exit(EXIT_ERRORS if failed else EXIT_OK)


def travel_of(file: str, dialect: str | None, prof) -> tuple:
    """The envelope's travel of each axis, in steps, for the simulator's limit switches: the
    project's `[tool.mcc.axes]` over the profile's `[envelope]` (docs/CONFIGURATION.md)."""
    from mcc.compiler import config, dialects
    from mcc.compiler.envelope.axes import envelopes

    settings = config.Resolver().for_path(file)
    if prof is None:
        found = dialects.get(dialect) if dialect else dialects.from_path(file)
        spec = settings.profile_spec(found.name) if found is not None else None
        try:
            prof = config.load_profile(spec or found.default_profile) if found is not None else None
        except Exception:  # noqa: BLE001 - a broken profile is reported by the check itself
            prof = None
    return tuple((axis, env.min, env.max) for axis, env in sorted(envelopes(prof, settings.axes).items())
                 if env.min is not None or env.max is not None)


def _sweep(file: str, dialect: str | None, prof, options, fmt: str) -> None:
    """`--sweep`: the worst position per axis over the generated scenarios."""
    from mcc.cli import render
    from mcc.sim.cycles import worst_positions
    from mcc.sim.files import sweep_file

    result, runs = sweep_file(file, dialect, prof, options)
    worst = worst_positions(runs)
    stops = [(name, trace) for name, trace in runs if trace.stopped == "travel"]
    if fmt == "json":
        click.echo(render.dump_json({"files": [{
            "path": result.path, "scenarios": [{"name": n, "stopped": t.stopped, "reason": t.reason} for n, t in runs],
            "worst": [{"axis": w.axis, "low": w.low, "low_scenario": w.low_scenario, "high": w.high,
                       "high_scenario": w.high_scenario} for w in worst],
            "diagnostics": [d.to_json() for d in sorted(result.diagnostics, key=lambda d: d.sort_key())]}]}))
    else:
        _diagnostics(result, sys.stdout)
        click.echo(f"{result.path}: {len(runs)} scenarios")
        for name, trace in runs:
            click.echo(f"  {name}: stopped: {trace.stopped} at {trace.time:.3f} s")
        for w in worst:
            click.echo(f"  axis {w.axis}: lowest {_n(w.low)} ({w.low_scenario}), highest {_n(w.high)} "
                       f"({w.high_scenario})")
        if stops:
            click.echo(f"  end of travel reached in {len(stops)} scenario(s): {', '.join(n for n, _ in stops)}")
    sys.exit(EXIT_ERRORS if result.has_errors else EXIT_OK)


def _has_matplotlib() -> bool:
    import importlib.util

    return importlib.util.find_spec("matplotlib") is not None


def _write(path: str, text: str) -> None:
    from mcc.compiler.lint.files import write_atomic

    try:
        write_atomic(path, text)
    except OSError as exc:
        raise click.FileError(path, hint=str(exc.strerror or exc)) from None


def _diagnostics(result, stream) -> None:
    from mcc.cli import render

    writer = render.TextWriter(stream, stream.isatty() and use_color("text"))
    diags = sorted(result.diagnostics, key=lambda d: d.sort_key())
    render.write_text(writer, diags, {result.path: result.source} if result.source else {})


def summary_lines(trace) -> list[tuple[str, str]]:
    """The text report: why the run stopped, when, where the axes are, outputs, prints, timeline."""
    out = [(f"{trace.path} ({trace.dialect}): stopped: {trace.stopped} at {trace.time:.3f} s after "
            f"{trace.steps} steps: {trace.reason}", "bold")]
    axes = ", ".join(f"{name}={_n(pos)}" for name, pos in sorted(trace.axes.items())) or "none"
    out.append((f"  positions (steps): {axes}", ""))
    on = ", ".join(f"{n}={v}" for n, v in sorted(trace.outputs.items())) or "none written"
    out.append((f"  outputs: {on}", ""))
    from mcc.sim.cycles import timing

    for line in timing(trace).summary():
        out.append((f"  {line}", ""))
    if trace.prints:
        out.append(("  prints:", ""))
        for t, text in trace.prints:
            out.append((f"    {t:9.3f} s  {text.rstrip(chr(10))}", ""))
    out.append(("timeline:", "bold"))
    shown = [e for e in trace.events if e.kind != "stopped"]
    for event in shown[:TIMELINE_MAX]:
        where = f"L{event.line}" if event.line is not None else ""
        out.append((f"  {event.t:9.3f} s  {where:6} {describe(event)}", ""))
    if len(shown) > TIMELINE_MAX:
        out.append((f"  ... {len(shown) - TIMELINE_MAX} more events (see --format json or --trace)", "dim"))
    return out


def describe(event) -> str:
    d = event.data
    kind = event.kind
    if kind == "move":
        moves = ", ".join(f"{a} {_n(d['from'].get(a, 0))} -> {_n(t)}" for a, t in d["to"].items())
        return f"move {d['mode']}: {moves}"
    if kind in ("move_end", "set_position"):
        return f"{kind.replace('_', ' ')} {d['axis']} at {_n(d['position'])}"
    if kind == "output":
        return f"output {d['output']} = {d['value']}"
    if kind == "input":
        cause = f" (axis {d['axis']} passed {_n(d['passes'])})" if "passes" in d else ""
        return f"input {d['input']} = {d['value']}{cause}"
    if kind == "print":
        return f"print {d['text'].rstrip(chr(10))!r}"
    if kind == "error":
        return f"error [{d['code']}] {d['message']}"
    parts = " ".join(f"{k}={_n(v) if isinstance(v, float) else v}" for k, v in d.items())
    return f"{kind.replace('_', ' ')} {parts}".rstrip()


def _n(value) -> str:
    value = float(value)
    return str(int(value)) if value.is_integer() else f"{value:.3f}"


def load_scenarios(paths) -> list | None:
    """--inputs given to --verify (several allowed): None means the default scenarios."""
    return [load_scenario(p) for p in paths] if paths else None


def verify_result(result, before, after_text: str, after_dialect: str, profile, inputs) -> bool:
    """`--verify` for compile, fmt and lint --fix: simulate the source and what would be written;
    on a divergence add S010 to `result` and answer False (the caller then writes nothing)."""
    from mcc.compiler.diagnostics import Diagnostics
    from mcc.compiler.span import Span
    from mcc.sim.verify import check_translation, explain

    problem = check_translation(result.path, result.dialect, before, after_text, after_dialect, profile,
                                load_scenarios(inputs))
    if not problem:
        return True
    line = _divergence_line(problem)
    text = result.source.line_text(line) if result.source is not None and line else ""
    span = Span(result.path, line or 1, 1, line or 1, max(2, len(text) + 1))
    diags = Diagnostics(result.diagnostics)
    diags.add("S010", span, f"--verify: {explain(problem)}; nothing was written")
    result.diagnostics = diags.items
    return False


def _divergence_line(problem: str) -> int | None:
    import re

    found = re.match(r"line (\d+), ", problem)
    return int(found.group(1)) if found else None
