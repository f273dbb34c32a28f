"""The simulator and the machine's envelope (issue 27): the limit switch at each end of the travel
stops the run (S017), `--sweep` reports the worst position per axis over generated scenarios, and
the cycle time of the main loop and of each call.

A device stops an axis at its limit switch: lexium-mcode.txt L3935 (LM), parker-x150.md L2382,
L2400, arcus-pmx-4ex-sa.txt L333 (+limit, -limit inputs per axis).
"""

from __future__ import annotations

import subprocess
import sys
import textwrap

import pytest

from mcc.sim.cycles import timing, worst_positions
from mcc.sim.files import simulate_file, sweep_file
from mcc.sim.interpreter import Options

TRAVEL = (("1", 0.0, 10000.0), ("X", 0.0, 10000.0))


def run(text: str, path: str, travel=TRAVEL, until: float = 20.0):
    done = simulate_file(path, None, None, None, Options(until=until, travel=travel), textwrap.dedent(text).lstrip())
    assert done.trace is not None, [d.message for d in done.result.diagnostics]
    return done.trace


@pytest.mark.parametrize("path, text, line", [
    ("a.mxt", "PG 100\nMA 5000\nH\nMR 7000\nH\nMA 0\nH\nE\nPG\n", 4),
    ("a.x150", "MPA\nA10\nV1\nD5000\nG\nMPI\nD7000\nG\nMPA\nD0\nG\n", 7),  # the move is D7000 .. G
    ("a.prg", "ABS\nHSPD=1000\nLSPD=100\nACC=100\nX5000\nWAITX\nINC\nX7000\nWAITX\nABS\nX0\nWAITX\nEND\n", 8),
])
def test_run_stops_at_the_end_of_travel(path: str, text: str, line: int) -> None:
    """From 5000, +7000 asks for 12000 on a travel of 0..10000: the axis runs to 10000 and the run
    stops there with S017 at the move's line; the move back to 0 never runs."""
    trace = run(text, path)
    assert trace.stopped == "travel"
    s017 = [d for d in trace.diagnostics if d.code == "S017"]
    assert len(s017) == 1 and s017[0].span.line == line
    assert trace.axes["X" if path.endswith(".prg") else "1"] == 10000
    travel = [e for e in trace.events if e.kind == "travel"]
    assert travel and travel[0].data["target"] == 12000 and travel[0].data["position"] == 10000


def test_no_envelope_no_stop() -> None:
    trace = run("PG 100\nMA 50000\nH\nE\nPG\n", "a.mxt", travel=())
    assert trace.stopped == "end" and trace.axes == {"1": 50000}


def test_sweep_reports_the_worst_position_and_its_scenario() -> None:
    """Input 1 high sends the axis to 12000 (MCode BR on I1, lexium-mcode.txt L3935 is what stops
    it): the sweep finds the scenario and reports the highest target, 12000."""
    text = "PG 100\nMA 5000\nH\nBR K2, I1=0\nMA 12000\nH\nLB K2\nE\nPG\n"
    result, runs = sweep_file("a.mxt", None, None, Options(until=10, travel=TRAVEL), text)
    assert len(runs) >= 2
    (worst,) = worst_positions(runs)
    assert (worst.axis, worst.low, worst.high) == ("1", 5000, 12000)
    high_runs = dict(runs)[worst.high_scenario]
    assert high_runs.stopped == "travel"
    assert any(t.stopped == "end" for _, t in runs)


def test_cycle_time_against_the_manuals_motion_rules() -> None:
    """X150: A10 = 10 rev/s² (parker-x150.md L195), V1 = 1 rev/s (L4540), D4000 = 1 rev at 4000
    steps/rev (L810, L837), T0.5 = half a second (L4101), L0 repeats forever (L2318). A trapezoidal
    move from standstill (X150 has no start speed): ramp up 1/10 = 0.1 s over 0.5*10*0.1² = 0.05 rev,
    ramp down the same, the remaining 1 - 0.1 = 0.9 rev at 1 rev/s take 0.9 s: 1.1 s a move, plus
    the 0.5 s delay: 1.6 s a cycle."""
    trace = run("MPI\nA10\nV1\nL0\nD4000\nG\nT0.5\nN\n", "a.x150", travel=(), until=10)
    found = timing(trace)
    assert found.cycles and all(c == pytest.approx(1.6, abs=1e-6) for c in found.cycles)
    assert found.moves_per_cycle == 1
    assert "cycle 1.600 s, 1 moves" in found.summary()[0]


def test_call_time() -> None:
    """MCode CL to a subroutine that waits 250 ms (H 250, lexium-mcode.txt: H takes milliseconds):
    each call lasts 0.25 s; the main loop (a BR back to K1) passes once per call."""
    text = "PG 100\nLB K1\nCL K9\nBR K1\nLB K9\nH 250\nRT\nPG\n"
    trace = run(text, "a.mxt", travel=(), until=2)
    found = timing(trace)
    assert found.calls["K9"] and all(t == pytest.approx(0.25) for t in found.calls["K9"])
    assert found.cycles and found.cycles[0] == pytest.approx(0.25)


def test_cli_sim_sweep_and_compile_print_them(tmp_path) -> None:
    """`mcc sim` reads [tool.mcc.axes] from pyproject.toml, `--sweep` names the scenario, `mcc compile`
    prints the cycle beside the size."""
    (tmp_path / "pyproject.toml").write_text("[tool.mcc.axes.1]\nmin = 0\nmax = 10000\n", encoding="utf-8")
    program = tmp_path / "p.mxt"
    program.write_text("PG 100\nMA 5000\nH\nBR K2, I1=0\nMA 12000\nH\nLB K2\nE\nPG\n", encoding="utf-8")
    mcc = [sys.executable, "-m", "mcc"]
    sweep = subprocess.run([*mcc, "sim", "--sweep", str(program)], capture_output=True, text=True, cwd=tmp_path)
    assert "axis 1: lowest" in sweep.stdout and "highest 12000" in sweep.stdout, sweep.stdout + sweep.stderr
    assert "end of travel reached in" in sweep.stdout
    cyc = tmp_path / "c.x150"
    cyc.write_text("MPI\nA10\nV1\nL0\nD4000\nG\nT0.5\nN\n", encoding="utf-8")
    sim = subprocess.run([*mcc, "sim", str(cyc), "--until", "5"], capture_output=True, text=True, cwd=tmp_path)
    assert "cycle 1.600 s, 1 moves" in sim.stdout, sim.stdout
    out = subprocess.run([*mcc, "compile", str(cyc), "-o", str(tmp_path / "o.x150")], capture_output=True, text=True,
                         cwd=tmp_path)
    assert "cycle 1.600 s, 1 moves" in out.stderr, out.stderr


def test_slew_stops_at_the_end_of_travel() -> None:
    """MCode SL 20000 (lexium-mcode.txt: slew at a constant velocity) runs until something stops it:
    with a travel of 0..10000 the limit switch does, at 10000, about half a second in."""
    trace = run("PG 100\nSL 20000\nH 2000\nSL 0\nE\nPG\n", "a.mxt")
    assert trace.stopped == "travel" and trace.axes["1"] == pytest.approx(10000)
    assert [d.span.line for d in trace.diagnostics if d.code == "S017"] == [2]
    assert 0.5 < trace.time < 1.0


def test_cli_sim_json_has_the_cycles(tmp_path) -> None:
    """The JSON report carries the cycle and call times (same X150 program as above: 1.6 s a cycle)."""
    import json

    cyc = tmp_path / "c.x150"
    cyc.write_text("MPI\nA10\nV1\nL0\nD4000\nG\nT0.5\nN\n", encoding="utf-8")
    out = subprocess.run([sys.executable, "-m", "mcc", "sim", str(cyc), "--until", "5", "--format", "json"],
                         capture_output=True, text=True, cwd=tmp_path)
    entry = json.loads(out.stdout)["files"][0]
    assert entry["cycles"] and all(c == pytest.approx(1.6) for c in entry["cycles"]) and entry["calls"] == {}
