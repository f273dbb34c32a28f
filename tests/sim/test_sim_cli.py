"""`mcc sim` and the --verify options, run as a user runs them."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

FIXTURES = Path(__file__).parent / "fixtures"
JSON_KEYS = {"path", "dialect", "stopped", "time", "axes", "outputs", "variables", "events", "diagnostics"}


def contract_kept(path: Path) -> None:
    from mcc.compiler import driver
    from mcc.compiler.ir_verify import verify

    module = driver.check_file(str(path)).analysis.module
    problems = verify(module)
    if problems:
        pytest.skip(f"{path.name}: its frontend does not keep the IR contract yet ({problems[0]})")


def test_text_report_says_why_it_stopped_and_shows_prints(mcc):
    contract_kept(FIXTURES / "counter.mxt")
    out = mcc("sim", str(FIXTURES / "counter.mxt"))
    assert out.returncode == 0, out.stderr
    first = out.stdout.splitlines()[0]
    assert "stopped: end at 0.000 s" in first and "the program ended" in first
    assert "n=5" in out.stdout and "timeline:" in out.stdout


def test_json_has_the_documented_shape(mcc):
    contract_kept(FIXTURES / "counter.mxt")
    out = mcc("sim", str(FIXTURES / "counter.mxt"), "--format", "json")
    entry = json.loads(out.stdout)["files"][0]
    assert JSON_KEYS <= set(entry)
    assert entry["stopped"] == "end" and entry["variables"] == {"N1": 5}
    prints = [e["text"] for e in entry["events"] if e["kind"] == "print"]
    assert prints == [f"n={n}\n" for n in range(1, 6)]
    assert all({"t", "kind", "line"} <= set(e) for e in entry["events"])


def test_a_runtime_error_is_reported_with_its_line_and_exit_1(mcc):
    contract_kept(FIXTURES / "divide.mxt")
    out = mcc("sim", str(FIXTURES / "divide.mxt"), "--format", "json")
    assert out.returncode == 1
    entry = json.loads(out.stdout)["files"][0]
    assert entry["stopped"] == "error"
    (diag,) = entry["diagnostics"]
    assert diag["code"] == "S002" and diag["line"] == 7


def test_stack_overflow_uses_the_nesting_limit(mcc):
    contract_kept(FIXTURES / "recurse.mxt")
    out = mcc("sim", str(FIXTURES / "recurse.mxt"))
    assert out.returncode == 1 and "S003" in out.stdout and "16 calls deep" in out.stdout


def test_csv_and_trace_files(mcc, tmp_path):
    contract_kept(FIXTURES / "counter.mxt")
    trace = tmp_path / "run.json"
    out = mcc("sim", str(FIXTURES / "counter.mxt"), "--format", "csv", "--trace", str(trace))
    header = out.stdout.splitlines()[0]
    assert header == "path,t,record,kind,line,axis,position,speed,detail"
    assert json.loads(trace.read_text())["files"][0]["stopped"] == "end"


def test_ir_that_breaks_the_contract_is_refused_with_s001_not_a_traceback():
    """No frontend writes IR that breaks the contract any more, so the refusal is shown on IR built
    by hand: a delay in a dialect unit the simulator cannot convert is S001 on its line."""
    from mcc.compiler import ir
    from mcc.sim.files import simulate_module

    span = ir.Span("delay.prg", 3, 1, 3, 10)
    module = ir.Module("arcus", "pmx-4ex-sa")
    module.routines.append(ir.Routine("main", ir.RoutineKind.MAIN, [
        ir.Block("b0", [ir.Delay(ir.Const(250, ir.Unit.MS), span=span)],
                 ir.End())]))
    trace, diags = simulate_module(module, "delay.prg", None, None)
    assert trace is None
    [diag] = list(diags)
    assert diag.code == "S001" and diag.span.line == 3 and "contract" in diag.message


def test_a_bad_scenario_is_a_usage_error(mcc, tmp_path):
    scen = tmp_path / "s.toml"
    scen.write_text("[[events]]\nat = 1\n")
    out = mcc("sim", str(FIXTURES / "counter.mxt"), "--inputs", str(scen))
    assert out.returncode == 2 and "needs 'input' and 'value'" in out.stderr


def test_plot_writes_an_image(mcc, tmp_path):
    pytest.importorskip("matplotlib")
    contract_kept(FIXTURES / "counter.mxt")
    png = tmp_path / "run.png"
    out = mcc("sim", str(FIXTURES / "counter.mxt"), "--plot", str(png))
    assert out.returncode == 0, out.stderr
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_compile_verify_writes_when_the_traces_agree(mcc, tmp_path):
    contract_kept(FIXTURES / "counter.mxt")
    out_file = tmp_path / "out.mxt"
    out = mcc("compile", str(FIXTURES / "counter.mxt"), "--verify", "-o", str(out_file))
    assert out.returncode == 0, out.stderr
    assert out_file.exists()


def test_verify_names_the_first_divergence():
    from mcc.sim.verify import check_translation

    path = FIXTURES / "counter.mxt"
    contract_kept(path)
    text = path.read_text()
    changed = text.replace("N1<5", "N1<4")
    problem = check_translation(str(path), "mcode", text, changed)
    assert problem.startswith("line 6, t = 0.000 s") and "the output does not print 'n=5" in problem
    assert check_translation(str(path), "mcode", text, text) == ""


def test_fmt_and_lint_fix_with_verify_keep_a_program_that_behaves_the_same(mcc, tmp_path):
    contract_kept(FIXTURES / "counter.mxt")
    copy = tmp_path / "counter.mxt"
    copy.write_text((FIXTURES / "counter.mxt").read_text().replace("  CL AD", "     CL   AD"))
    out = mcc("fmt", "--verify", str(copy))
    assert out.returncode == 0, out.stderr
    assert "  CL AD" in copy.read_text()  # formatted, and written because it verified
    fixed = mcc("lint", "--fix", "--verify", str(copy))
    assert "S010" not in fixed.stdout


def test_sim_help_names_the_options(mcc):
    out = mcc("sim", "--help")
    for option in ("--inputs", "--until", "--profile", "--format", "--trace", "--plot"):
        assert option in out.stdout


def test_a_divergent_translation_gets_s010_on_the_diverging_line_and_is_not_written():
    from mcc.cli.sim import verify_result
    from mcc.compiler import driver

    path = FIXTURES / "counter.mxt"
    contract_kept(path)
    result = driver.compile_file(str(path))
    changed = result.listing.text.replace("N1<5", "N1<4")
    assert changed != result.listing.text
    assert verify_result(result, result.analysis.module, changed, "mcode", None, ()) is False
    (diag,) = [d for d in result.diagnostics if d.code == "S010"]
    assert diag.span.line == 6 and "nothing was written" in diag.message


def test_default_scenarios_drive_every_input_read_both_ways():
    """Every input read: all low, all high, each high alone, each toggling from 0.1 s after each
    point where the all-low run waited (here it waits at once on input 3), then every second."""
    from mcc.compiler import ir
    from mcc.sim.verify import MAX_TOGGLES, default_scenarios

    from sim_helpers import eq, inp, module

    m = module(("a", [ir.WaitInput(eq(inp(3), 1))], ir.Branch(eq(inp(5), 0), "b", "b")), ("b", [], ir.End()))
    scenarios = default_scenarios(m)
    names = [s.name.split(" at ")[0] for s in scenarios]
    assert names == ["inputs low", "inputs high", "input 3 high", "input 3 toggles", "input 5 high", "input 5 toggles"]
    toggles = scenarios[3].events
    assert [(e.input, e.value, e.at) for e in toggles[:3]] == [(3, 1, 0.1), (3, 0, 1.1), (3, 1, 2.1)]
    assert len(toggles) == MAX_TOGGLES


def _trace(t_end, pos, stopped="end", time=None):
    from mcc.sim.trace import Event, Trace

    tr = Trace("p", "arcus", 4000, axes={"X": pos}, stopped=stopped, time=t_end if time is None else time)
    tr.events = [Event(0, "move", 1, {"mode": "absolute", "from": {"X": 0}, "to": {"X": pos}}),
                 Event(t_end, "move_end", 1, {"axis": "X", "position": pos})]
    return tr


def test_time_and_position_tolerances():
    """The time tolerance is what the writer rounds (docs/SIMULATOR.md, "Tolerance"): exact
    arithmetic allows one tick and one polling scan, nothing proportional, so a move 0.5 % late is
    a difference; one output step of position is allowed."""
    from mcc.sim.verify import Tolerance, compare_traces

    assert compare_traces(_trace(10.0, 4000), _trace(10.001, 4001)) is None  # one tick late, 1 step off
    late = compare_traces(_trace(10.0, 4000), _trace(10.05, 4000))
    assert late is not None and "10.050 s in the output" in late.message
    assert compare_traces(_trace(10.0, 4000), _trace(10.05, 4000), within=Tolerance(relative=0.01)) is None
    assert compare_traces(_trace(10.0, 4000), _trace(10.0, 4002)) is not None


def test_a_speed_two_percent_off_is_a_difference():
    """A converted speed may differ by the target's rounding only: 0.1 rev/s is 5120 steps/s on
    MCode (exact), so an output at 2 % less arrives 2 % late and is caught (lexium-mcode.txt VM)."""
    from mcc.compiler import ir
    from mcc.sim.verify import compare, tolerance

    from sim_helpers import module, move, speed

    def prog(value):
        return module([speed("1", value), move("1", 51200), ir.WaitMotion(("1",))], dialect="mcode",
                      steps_per_rev=51200)

    source, slow = prog(5120), prog(5120 * 0.98)
    assert tolerance(source, slow).relative == 0
    found = compare(source, slow)
    assert found is not None and "happens at" in found.message


def test_a_run_that_stops_otherwise_is_a_difference():
    """An output that ends early, or spins where the source runs to the horizon, is a difference
    even when every event it made matches (the comparison is not cut at the earlier stop)."""
    from mcc.sim.verify import compare_traces

    ends_early = compare_traces(_trace(10.0, 4000, stopped="time-limit", time=30.0), _trace(10.0, 4000, time=10.0))
    assert ends_early is not None and "'time-limit' at 30.000 s" in ends_early.message
    spins = compare_traces(_trace(10.0, 4000, stopped="time-limit", time=30.0),
                           _trace(0.0, 0, stopped="step-limit", time=0.0))
    assert spins is not None
    waits_later = compare_traces(_trace(1.0, 4000, stopped="waiting", time=2.0),
                                 _trace(1.0, 4000, stopped="waiting", time=3.0))
    assert waits_later is not None and "'waiting' at 3.000 s" in waits_later.message


def test_the_readme_plot_command_places_two_parts(mcc, tmp_path):
    from conftest import ROOT

    sample = ROOT / "samples" / "mcode" / "pick_and_place.mxt"
    contract_kept(sample)
    out = mcc("sim", str(sample), "--inputs", str(ROOT / "docs" / "examples" / "pick_and_place.toml"),
              "--format", "json")
    entry = json.loads(out.stdout)["files"][0]
    assert [e["text"] for e in entry["events"] if e["kind"] == "print"] == ["Parts placed: 1\n",
                                                                            "Parts placed: 2\n"]
    assert entry["stopped"] == "waiting" and entry["axes"]["1"]["position"] == 0


def test_an_output_that_spins_at_time_zero_matches_nothing():
    """Issue 23: both runs go to the same horizon; an output stuck in a loop that never lets time
    pass (more steps do not advance it) is a difference from a source that moves, while two
    programs that both can do nothing more (one spinning, one waiting) are alike."""
    from mcc.compiler import ir
    from mcc.sim import Options
    from mcc.sim.scenario import Scenario
    from mcc.sim.verify import compare

    from sim_helpers import c, module, move, speed

    options = Options(until=30, max_steps=5_000, samples=False)
    moves = module([speed("X", 4000), move("X", 4000), ir.WaitMotion(("X",))])
    counter = ir.Var("V1")  # a loop that counts for ever: every round changes V1, no time passes
    spins = module(("a", [ir.Assign(counter, ir.BinOp("+", counter, c(1)))], ir.Jump("a")))
    found = compare(moves, spins, [Scenario()], options)
    assert found is not None and found.message == "the output does not move X to 4000"
    waits = module([ir.WaitInput(ir.Compare("=", ir.Status("input", index=1), c(1)))])
    assert compare(waits, spins, [Scenario()], options) is None
