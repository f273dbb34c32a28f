"""The X150 as its manual describes it (issues 22 and 23): the simulator runs the stream in the
order the device receives it, reports positions in the device's format, and the X150 writer and
the download keep what the program means. Each test cites the line of parker-x150.md it follows."""

from __future__ import annotations

import math

import pytest

from mcc.sim.interpreter import simulate

from x150_helpers import module, output


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


def test_a_position_report_is_a_star_and_a_signed_number():
    """parker-x150.md L3141-L3143: PR answers "a number preceded by a sign ... *(s)n[CR]", e.g.
    `*-25600`. Decision (docs/dialects/x150.md): the sign always, `+` for zero and positive
    positions, no spaces (L2216's `* - 140000` is typesetting). 1D-25600 G from 0 is at -25600;
    then MPA D4000 G at +4000; then D0 G at 0."""
    trace = run("1A10\n1V5\n1D-25600\n1G\n1PR\n1MPA\n1D4000\n1G\n1PR\n1D0\n1G\n1PR\n")
    assert [text for _, text in trace.prints] == ["*-25600\n", "*+4000\n", "*+0\n"]


def test_the_report_is_written_back_as_pr_and_other_position_prints_are_refused():
    """parker-x150.md L3141: X150 sends a position only as `*(s)n`. Its own PR round-trips; MCode
    cannot write the `+` (refused, G003), and an MCode `PR P` (which sends `4000`) has no X150
    form (refused, G003) rather than becoming a PR whose text the host would read as `*+4000`."""
    from mcc.compiler import driver

    assert output("1PR\n2PR\n") == ["1PR", "2PR"]
    to_mcode = driver.compile_file("p.x150", "x150", target="mcode", text="1PR\n")
    assert to_mcode.has_errors and [(d.code, d.span.line) for d in to_mcode.diagnostics
                                    if d.severity == "error"] == [("G003", 1)]
    from_mcode = driver.compile_file("p.mxt", "mcode", target="x150", text="PG 1\nPR P\nE\nPG\n")
    assert [(d.code, d.span.line) for d in from_mcode.diagnostics if d.code == "G003"] == [("G003", 2)]


def test_the_virtual_device_answers_pr_as_the_simulator_prints_it():
    """parker-x150.md L3141-L3143: the virtual device's `1PR` answer is the simulator's print of
    `1PR` (one format, compiler/x150/neutral.py): `*-2000` after 1D-2000 G, `*+0` for a device
    that has not moved."""
    from mcc.link.device.x150 import X150Device

    device = X150Device()
    for command in (b"1A10\r", b"1V1\r", b"1D-2000\r", b"1G\r"):
        device.feed(command)
    assert device.feed(b"1PR\r") == b"1PR\r*-2000\r>"
    assert device.feed(b"2PR\r") == b"2PR\r*+0\r>"
