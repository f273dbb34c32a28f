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


def test_a_program_whose_ir_breaks_the_contract_is_refused_with_s001(mcc, tmp_path):
    bad = tmp_path / "delay.prg"
    bad.write_text("DELAY=250\nEND\n")
    from mcc.compiler import driver
    from mcc.compiler.ir_verify import verify

    if not verify(driver.check_file(str(bad)).analysis.module):
        pytest.skip("the arcus frontend keeps the contract now; no file of it breaks it")
    out = mcc("sim", str(bad), "--format", "json")
    assert out.returncode == 1
    entry = json.loads(out.stdout)["files"][0]
    assert entry["stopped"] == "error" and entry["diagnostics"][0]["code"] == "S001"
    assert "contract" in entry["diagnostics"][0]["message"]


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
    from mcc.compiler import ir
    from mcc.sim.verify import default_scenarios

    from sim_helpers import eq, inp, module

    m = module(("a", [ir.WaitInput(eq(inp(3), 1))], ir.Branch(eq(inp(5), 0), "b", "b")), ("b", [], ir.End()))
    names = [s.name for s in default_scenarios(m)]
    assert names == ["inputs low", "inputs high", "input 3 pulses high at 0.5 s", "input 5 pulses high at 0.5 s"]


def test_time_and_position_tolerances():
    from mcc.sim.trace import Event, Trace
    from mcc.sim.verify import compare_traces

    def trace(t_end, pos):
        tr = Trace("p", "arcus", 4000, axes={"X": pos})
        tr.events = [Event(0, "move", 1, {"mode": "absolute", "from": {"X": 0}, "to": {"X": pos}}),
                     Event(t_end, "move_end", 1, {"axis": "X", "position": pos})]
        return tr

    assert compare_traces(trace(10.0, 4000), trace(10.05, 4001)) is None  # 0.5 % late, 1 step off
    late = compare_traces(trace(10.0, 4000), trace(10.5, 4000))
    assert late is not None and "10.500 s in the output" in late.message
    assert compare_traces(trace(10.0, 4000), trace(10.0, 4002)) is not None


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
