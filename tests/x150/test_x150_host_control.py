"""X150's host controls and setting reports are neutral operations: PS/C are Pause/Resume (MCode
PS/RS), #n is Step, and the queries 1FOL, 1INL and 1OUTL print a reading of the setting."""

from __future__ import annotations

from mcc.compiler import driver, ir, profiles
from mcc.sim import verify
from mcc.sim.interpreter import simulate

from x150_helpers import module, output


def ops_of(text: str) -> list:
    return [op for _, block in module(text).blocks() for op in block.ops]


def test_pause_continue_and_single_steps_are_neutral_and_written_back_as_written():
    text = "1XST1\nPS\n1C\n#\n#3\n2#2\n"
    pause, resume, *steps = ops_of(text)[1:]
    assert isinstance(pause, ir.Pause) and (pause.axis, pause.stop_motion) == ("*", False)
    assert isinstance(resume, ir.Resume) and resume.axis == "1"
    assert [(type(s), s.axis, s.count.value) for s in steps] == [(ir.Step, "*", 1), (ir.Step, "*", 3),
                                                                 (ir.Step, "2", 2)]
    assert output(text) == text.splitlines()


def test_setting_queries_print_a_reading_of_the_setting_and_are_written_back():
    text = "1FOL\n1INL\n1OUTL\n1PR\n"
    # the reading is the last item: PR's print starts with the report's `*` (parker-x150.md L3141)
    meanings = [(type(op), op.items[-1].meaning) for op in ops_of(text)]
    assert meanings == [(ir.Print, "following_ratio"), (ir.Print, "input_levels"), (ir.Print, "output_levels"),
                        (ir.Print, "position")]
    assert output(text) == text.splitlines()


def test_continue_and_step_stay_with_the_host_a_sequence_cannot_hold_them():
    source = "PG 1\nMR 51200\nH\nPS\nRS\nE\nPG\n"  # MCode: a program that resumes itself
    result = driver.compile_file("p.mxt", "mcode", target="x150", text=source)
    # the move on line 2 is refused too: it starts at MCode's power-up VI (X216, lexium-mcode.txt L662-L666)
    [refusal] = [d for d in result.diagnostics if d.severity.value == "error" and d.code != "X216"]
    assert refusal.code == "G003" and "C (continue" in refusal.message and refusal.span.line == 5


def test_a_pause_converts_where_no_move_runs_and_is_refused_where_one_may():
    """X150's PS lets a move run on; MCode's ramps it down and restarts it. Only a pause no move
    can reach means the same in both."""
    settled = driver.compile_file("p.x150", "x150", target="mcode", text="1A10\n1V1\n1D4000\n1G\nPS\n1G\nC\n")
    assert not settled.has_errors, [(d.code, d.message) for d in settled.diagnostics]
    lines = settled.listing.text.splitlines()
    assert lines.index("PS") == lines.index("H") + 1 and "RS" in lines
    running = driver.compile_file("p.x150", "x150", target="mcode", text="1A10\n1V1\n1MC\n1G\nPS\n")
    [refusal] = [d for d in running.diagnostics if d.severity.value == "error"]
    assert refusal.code == "G003" and "run on" in refusal.message and refusal.span.line == 5
    back = driver.compile_file("p.mxt", "mcode", target="x150", text="PG 1\nMR 51200\nPS\nE\nPG\n")
    assert any(d.code == "G003" and "PS pauses command execution" in d.message and d.span.line == 3
               for d in back.diagnostics)


def test_other_dialects_refuse_single_steps_and_arcus_refuses_pauses():
    for target, words in (("mcode", "single step"), ("arcus", "single step")):
        result = driver.compile_file("s.x150", "x150", target=target, text="1A10\n1V1\n#2\n")
        assert any(d.code == "G003" and words in d.message and d.span.line == 3 for d in result.diagnostics)
    result = driver.compile_file("s.x150", "x150", target="arcus", text="1A10\n1V1\nPS\n1D4000\n1G\nC\n")
    assert any(d.code == "G003" and "SR=2" in d.message and d.span.line == 3 for d in result.diagnostics)


def test_the_simulator_records_pauses_and_steps_and_resumes_at_once():
    trace = simulate(module("1A10\n1V1\nPS\n1D4000\n1G\nC\n#2\n"))
    kinds = [(e.kind, e.line) for e in trace.events if e.kind in ("pause", "move", "resume", "step")]
    assert kinds == [("pause", 3), ("move", 4), ("resume", 6), ("step", 7)]  # a move is told at its D
    assert [e.data["value"] for e in trace.events if e.kind == "step"] == [2]
    assert [d.code for d in trace.diagnostics] == ["S015"]


def test_the_simulator_says_when_a_stopping_pause_catches_a_move():
    result = driver.check_file("p.mxt", "mcode", text="PG 1\nVM=51200\nMR 51200\nPS\nH\nE\nPG\n")
    trace = simulate(result.analysis.module)
    [note] = [d for d in trace.diagnostics if d.code == "S015"]
    assert "runs on" in note.message and note.span.line == 4


def test_setting_reports_print_the_value_in_force_or_the_factory_default():
    """1INL reports the header and `*` the dedicated inputs' levels `_` the user inputs', input 1
    first (parker-x150.md L2131-L2141); INL_X1 makes input 2 active high."""
    trace = simulate(module("1FOL\n1FOL50\n1FOL\n1INL\n1INL_X1\n1INL\n"))
    lines = [text.strip().splitlines()[-1] for _, text in trace.prints]
    assert lines == ["100", "50", "*0000000_0000000000", "*0000000_0100000000"]
    assert trace.prints[2][1].startswith("Input active levels are:\nLMT+ LMT- HOME AUX-IN STOP ENG INDEX_I1")


def test_an_unaddressed_jog_moves_the_device_not_a_phantom_axis():
    trace = simulate(module("1A10\n1V1\nMC\nG\nT1\nSB\n"), profile=profiles.load("x150-pdhx"))
    assert set(trace.axes) == {"1"} and trace.axes["1"] > 0


def test_a_pause_keeps_its_place_in_the_behaviour_oracle():
    source = module("1A10\n1V1\nPS\n1D4000\n1G\nC\n")
    moved = module("1A10\n1V1\n1D4000\n1G\nPS\nC\n")
    assert verify.compare(source, moved) is not None
    assert verify.compare(source, module("1A10\n1V1\nPS\n1D4000\n1G\nC\n")) is None


def test_settled_operations_are_those_no_move_can_reach():
    mod = module("PS\n1A10\n1V1\n1D4000\n1G\nPS\n1MC\n1G\nPS\n")
    pauses = [op for _, block in mod.blocks() for op in block.ops if isinstance(op, ir.Pause)]
    settled = ir.settled_ops(mod)
    assert [id(p) in settled for p in pauses] == [True, True, False]


def test_setting_reports_are_per_device():
    trace = simulate(module("FOL50\n2FOL20\n1FOL\n2FOL\nFOL70\n2FOL\n2INL_1\n1INL\n2INL\n"))
    assert [text.strip().splitlines()[-1] for _, text in trace.prints] == [
        "50", "20", "70", "*0000000_0000000000", "*0000000_1000000000"]


TRACED = "XE1\nXD1\nA10\nV5\nD25000\nL2\nG\nN\nXT\n1XTR{on}\nXR1\n"


def test_trace_mode_reports_each_command_with_the_loop_count():
    """XTR1: "commands will be echoed to the host ... if you have a loop (L) ... it will display
    the iteration count" (parker-x150.md L5400-L5433, the example's output L5421-L5431)."""
    trace = simulate(module(TRACED.format(on=1)))
    assert [text.rstrip("\n") for _, text in trace.prints] == [
        ";SEQUENCE: 1 COMMAND: A10", ";SEQUENCE: 1 COMMAND: V5", ";SEQUENCE: 1 COMMAND: D25000",
        ";SEQUENCE: 1 COMMAND: L2", ";SEQUENCE: 1 COMMAND: G      LOOP COUNT: 1",
        ";SEQUENCE: 1 COMMAND: N      LOOP COUNT: 1", ";SEQUENCE: 1 COMMAND: G      LOOP COUNT: 2",
        ";SEQUENCE: 1 COMMAND: N      LOOP COUNT: 2", ";SEQUENCE: 1 COMMAND: XT"]
    assert {e.kind for e in trace.events if e.data.get("text")} == {"trace"}


def test_without_the_trace_on_nothing_is_reported_and_no_program_carries_trace_reports():
    """XTR0 (the default, L5384) reports nothing; a program without XTR has no trace report."""
    assert simulate(module(TRACED.format(on=0))).prints == []
    mod = module("XE1\nXD1\nA10\nG\nXT\nXR1\n")
    assert not any(isinstance(op, ir.Print) for _, block in mod.blocks() for op in block.ops)


def test_the_x150_writer_leaves_trace_reports_to_the_device_and_verify_passes():
    """The device reports by itself (L5400): the written program is the commands alone, and a
    rewrite that changes the commands' text still behaves like its source."""
    lines = output(TRACED.format(on=1))
    assert not any("SEQUENCE" in line for line in lines) and "1XTR1" in lines
    result = driver.compile_file("p.x150", "x150", text=TRACED.format(on=1), verify=True)
    assert not result.has_errors, [d.message for d in result.diagnostics]
