"""Handlers the scenario drives: capture inputs, stalls, drive faults and power loss, and MCode's
trip enable mask (docs/SIMULATOR.md, "Incidents"), each run from a program in its own dialect."""

from __future__ import annotations

import pytest

from mcc.compiler import driver
from mcc.sim import simulate
from mcc.sim.scenario import ScenarioError, parse

EXTENSIONS = {"mcode": ".mxt", "arcus": ".prg", "x150": ".x150"}


def run(dialect: str, text: str, scenario: str = "", until: float = 20.0):
    checked = driver.check_file(f"prog{EXTENSIONS[dialect]}", dialect, None, text)
    assert not checked.has_errors, [d.message for d in checked.diagnostics if d.severity.value == "error"]
    return simulate(checked.analysis.module, parse(f"until = {until}\n" + scenario))


def kinds(trace, *wanted):
    return [e for e in trace.events if e.kind in wanted]


def handlers(trace) -> list[str]:
    return [e.data["routine"] for e in kinds(trace, "handler")]


# -- MCode: trips fire only while their TE bit is set; a fired trip clears it ---------------------

MCODE_INPUT_TRIP = """VA N1
PG 1
  TI 1,K1
  {enable}
LB G2
  H 100
  BR G2,N1<3
  E
LB K1
  IC N1
  {again}
  RT
PG
"""
# Input 1 is low-active by default (IS, lexium-mcode.txt L3500) and a scenario gives levels, so a
# press pulls the line low: TI fires "when input 1 is active" (L5716), at 1, 2 and 3 s.
PULSES = "".join(f"[[events]]\nat = {t}\ninput = 1\nvalue = {v}\n" for t, v in
                 ((1, 0), (1.5, 1), (2, 0), (2.5, 1), (3, 0), (3.5, 1)))


def test_mcode_a_trip_without_its_te_bit_never_fires():
    trace = run("mcode", MCODE_INPUT_TRIP.format(enable="", again=""), PULSES, until=5)
    assert handlers(trace) == [] and trace.stopped == "time-limit"


def test_mcode_a_fired_trip_clears_its_te_bit_until_the_handler_sets_it_again():
    once = run("mcode", MCODE_INPUT_TRIP.format(enable="TE=1", again=""), PULSES, until=5)
    assert handlers(once) == ["K1"] and once.variables["N1"] == 1
    every = run("mcode", MCODE_INPUT_TRIP.format(enable="TE=1", again="TE=1"), PULSES, until=5)
    assert [e.t for e in kinds(every, "handler")] == [1, 2, 3] and every.stopped == "end"


def test_mcode_capture_trip_runs_on_the_capture_input_and_records_the_position():
    text = """IS=1,12,1
VM=20000
A=100000
D=100000
PG 1
  TC=K1
  TE=4
  MA 40000
  H
  E
LB K1
  O1=1
  RT
PG
"""
    trace = run("mcode", text, "[[events]]\nat = 0.5\ninput = 1\nvalue = 1\n")
    (capture,) = kinds(trace, "capture")
    assert capture.t == 0.5 and 0 < capture.data["positions"]["1"] < 40000
    assert handlers(trace) == ["K1"] and trace.outputs[1] == 1


def test_the_scenario_names_the_capture_input():
    text = "PG 1\n  TC=K1\n  TE=4\n  H 2000\n  E\nLB K1\n  O2=1\n  RT\nPG\n"
    # low-active by default (L3500): the capture input becomes active when its level goes low
    on_two = "capture = 2\n[[events]]\nat = 0.5\ninput = 2\nvalue = 0\n"
    assert handlers(run("mcode", text, on_two)) == ["K1"]
    assert handlers(run("mcode", text, "[[events]]\nat = 0.5\ninput = 2\nvalue = 0\n")) == []  # input 1 captures


def test_mcode_power_loss_runs_the_tm_trip_else_stops_the_run():
    text = "PG 1\n  {trip}\n  SL 10000\nLB G1\n  BR G1\n  E\nLB Q1\n  O3=1\n  E\nPG\n"
    power = "[[power]]\nat = 1.5\n"
    handled = run("mcode", text.format(trip="TM=Q1\n  TE=64"), power)
    assert handlers(handled) == ["Q1"] and handled.outputs[3] == 1 and handled.stopped == "end"
    assert kinds(handled, "power_loss")[0].t == 1.5
    lost = run("mcode", text.format(trip=""), power)
    assert lost.stopped == "error" and lost.diagnostics[-1].code == "S013" and lost.time == 1.5


def test_mcode_a_stall_stops_the_axis_and_runs_the_oe_handler():
    text = "VM=10000\nPG 1\n  OE K9\n  MA 51200\n  H\n  O1=1\n  E\nLB K9\n  O2=1\n  RT\nPG\n"
    trace = run("mcode", text, '[[stall]]\nat = 1.0\naxis = "1"\n')
    (stall,) = kinds(trace, "stall")
    assert stall.t == 1.0 and trace.axes["1"] == stall.data["position"] < 51200  # it stopped where it stalled
    assert handlers(trace) == ["K9"] and trace.outputs == {2: 1, 1: 1}


def test_mcode_a_stall_without_a_handler_stops_the_run_with_s011():
    """MA 512000 at the power-up VI 1000, A = D 1e6 steps/s² (lexium-mcode.txt L662-L687) takes
    2·(sqrt(1000² + 1e6·512000) - 1000) / 1e6 = 1.43 s, so the stall at 0.5 s is mid-move."""
    trace = run("mcode", "PG 1\n  MA 512000\n  H\n  E\nPG\n", '[[stall]]\nat = 0.5\naxis = "1"\n')
    assert trace.stopped == "error" and trace.diagnostics[-1].code == "S011"


def test_mcode_reads_the_stall_flag():
    text = "VA K2\nPG 1\n  OE K9\n  MA 51200\n  H\n  K2=ST\n  E\nLB K9\n  RT\nPG\n"
    assert run("mcode", text, '[[stall]]\nat = 0.2\naxis = "1"\n').variables["K2"] == 1


# -- X150: a fault or a stall passes control to the fault sequence (XFK) --------------------------

X150_FAULT = """1XE5
1XD5
1O1
1XT
1XE1
1XD1
{xfk}
1V1
1A10
1MPI
1L
1D4000
1G
1T0.5
1N
1XT
1XR1
"""


@pytest.mark.parametrize("incident", ['[[fault]]\nat = 2.0\naxis = "1"\n', '[[stall]]\nat = 2.0\naxis = "1"\n'])
def test_x150_a_fault_or_stall_runs_the_fault_sequence_instead_of_the_program(incident):
    trace = run("x150", X150_FAULT.format(xfk="1XFK5"), incident, until=10)
    assert handlers(trace) == ["SEQ5@1"] and trace.outputs[1] == 1
    # the loop does not resume: the fault sequence ends the program
    assert trace.stopped == "end" and trace.time == 2.0
    assert not [e for e in kinds(trace, "move") if e.t > 2.0]


def test_x150_without_a_fault_sequence_a_fault_stops_the_run_with_s012():
    trace = run("x150", X150_FAULT.format(xfk=""), "[[fault]]\nat = 2.0\n", until=10)
    assert trace.stopped == "error" and trace.diagnostics[-1].code == "S012"


def test_x150_a_power_up_sequence_is_not_a_power_loss_handler():
    trace = run("x150", X150_FAULT.format(xfk="1XP5"), "[[power]]\nat = 1.0\n", until=10)
    assert handlers(trace) == [] and trace.stopped == "error" and trace.diagnostics[-1].code == "S013"


# -- Arcus: an alarm (a drive fault) stops the axis; the program goes to its error state ----------

def test_arcus_an_alarm_stops_the_axis_and_the_program_in_error():
    text = "HSPD=1000\nLSPD=100\nACC=100\nINC\nX50000\nWAITX\nDO=1\nEND\n"
    trace = run("arcus", text, '[[fault]]\nat = 1.0\naxis = "X"\n')
    (fault,) = kinds(trace, "fault")
    assert trace.stopped == "error" and trace.diagnostics[-1].code == "S012"
    assert trace.axes["X"] == fault.data["position"] < 50000 and trace.outputs.get(1, 0) == 0


def test_arcus_a_stall_is_an_error_too():
    text = "HSPD=1000\nLSPD=100\nACC=100\nX50000\nWAITX\nEND\n"
    trace = run("arcus", text, '[[stall]]\nat = 1.0\naxis = "X"\n')
    assert trace.stopped == "error" and trace.diagnostics[-1].code == "S011"


# -- the scenario format --------------------------------------------------------------------------

@pytest.mark.parametrize("text, word", [
    ("[[stall]]\nat = 1\n", "axis"),
    ("[[power]]\naxis = \"X\"\nat = 1\n", "axis"),
    ("[[fault]]\n", "at"),
    ("[[fault]]\nat = -1\n", ">= 0"),
    ("capture = 0\n", "start at 1"),
])
def test_a_malformed_incident_names_what_is_wrong(text, word):
    with pytest.raises(ScenarioError, match=word):
        parse(text)
