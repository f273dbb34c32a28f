"""The X150 as its manual describes it (issues 22 and 23): the simulator runs the stream in the
order the device receives it, reports positions in the device's format, and the X150 writer and
the download keep what the program means. Each test cites the line of parker-x150.md it follows."""

from __future__ import annotations

import math

import pytest

from mcc.sim.interpreter import simulate

from x150_helpers import module


def run(text: str):
    return simulate(module(text))


def test_set_up_sent_before_a_definition_is_in_force_when_the_sequence_runs():
    """parker-x150.md L177: buffered commands are "executed in sequential order", so V5 and A10
    sent before `XD1 .. XT` hold when the XR after it runs the sequence. At CUR 4000 (the profile's
    resolution) V5 is 20000 steps/s and A10 40000 steps/s^2; 4000 steps never reach V5
    (20000^2 / 40000 = 10000 steps would be needed), so the move is a triangle of
    2 * sqrt(4000 / 40000) = 0.632 s, not the 1.100 s of the factory speeds."""
    trace = run("1V5\n1A10\n1XE1\n1XD1\n1D4000\n1G\n1XT\n1XR1\n1PR\n")
    assert trace.stopped == "end"
    assert trace.time == pytest.approx(2 * math.sqrt(4000 / 40000), abs=1e-6)
    assert trace.axes == {"1": 4000}


def test_variables_set_before_a_definition_are_read_by_the_sequence_run_after_it():
    """parker-x150.md L177 (sequential order): VAR1=2000 sent before the definition is what
    `D(VAR1)` reads when XR1 runs the sequence; the sequence's own VAR1=VAR1+1000 runs after the
    move, and the VAR1=5 sent after XR1 runs last. Triangle: 2 * sqrt(2000 / 40000) = 0.447 s."""
    trace = run("1CUR4000\nVAR1=2000\n1V5\n1A10\n1XE1\n1XD1\n1D(VAR1)\n1G\n1VAR1=VAR1+1000\n1XT\n"
                "1XR1\n1PR\nVAR1=5\n")
    assert trace.axes == {"1": 2000}
    assert trace.time == pytest.approx(2 * math.sqrt(2000 / 40000), abs=1e-6)
    assert trace.variables["VAR1"] == 5


def test_every_stretch_of_the_stream_runs_once_in_the_order_sent():
    """parker-x150.md L177: three stretches around two definitions run first to last: the move of
    the first (1000 steps), the sequence the second runs (a further 1000), then the third (to 3000
    in all, then sequence 2 for 500 more); each position report comes after the moves sent before
    it."""
    trace = run("1V1\n1A10\n1D1000\n1G\n1PR\n1XE1\n1XD1\n1D1000\n1G\n1XT\n1XR1\n1PR\n"
                "1XE2\n1XD2\n1D500\n1G\n1XT\n1D1000\n1G\n1PR\n1XR2\n")
    positions = [text for _, text in trace.prints]
    assert [int(p.lstrip("*+")) for p in positions] == [1000, 2000, 3000]
    assert trace.axes == {"1": 3500}
