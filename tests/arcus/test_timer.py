"""The Arcus timer register TR: once written it counts down to 0, in milliseconds
(arcus-pmx-4ex-sa.txt L789-L793; TR reads 0..1,000,000, L1701-L1702; the TR keyword L2633-L2649)."""

from __future__ import annotations

import pytest

from mcc.compiler import driver
from mcc.link.device.arcus import ArcusDevice
from mcc.sim import Options, simulate


def run(text: str):
    result = driver.check_file("p.prg", "arcus", text=text)
    assert not result.has_errors, [(d.code, d.message) for d in result.diagnostics]
    return simulate(result.analysis.module)


def test_tr_counts_down_in_milliseconds_and_stops_at_zero() -> None:
    """L791: "Once timer register is set, it begins to count down to 0 ... The units are in
    milliseconds." By hand: TR=1000; after 1 ms it reads 999; after 333 ms more 666; after
    1000 ms more it has stopped at 0 (not -334)."""
    trace = run("TR=1000\nDELAY=1\nV1=TR\nDELAY=333\nV2=TR\nDELAY=1000\nV3=TR\nEND\n")
    assert (trace.variables["V1"], trace.variables["V2"], trace.variables["V3"]) == (999, 666, 0)


def test_a_loop_waiting_for_tr_ends_when_it_reaches_zero() -> None:
    """`WHILE TR>0 ENDWHILE` polls the timer: TR=500 lets the program go on after 500 ms."""
    trace = run("TR=500\nWHILE TR>0\nENDWHILE\nV1=TR\nEND\n")
    assert trace.stopped == "end" and trace.time == pytest.approx(0.5) and trace.variables["V1"] == 0


def test_the_manuals_tr_example_moves_at_the_thresholds() -> None:
    """The TR example (L2647-L2649), loaded with 10000 ms: X0 while TR>8000, then X3000 while
    TR>5000, then X8000. By hand: TR reaches 8000 at 2.000 s, so the move to 3000 starts then;
    at HS 1000, LS 100, ACC 100 ms it takes 0.1 + 2.89 + 0.1 = 3.09 s (55 pulses per ramp), and
    at 5.09 s TR reads 4910, not above 5000: the move to 8000 starts at once and takes
    0.1 + 4.89 + 0.1 = 5.09 s, ending at 10.18 s."""
    text = ("HSPD=1000\nLSPD=100\nACC=100\nTR=10000\nWHILE 1=1\nIF TR>8000\nX0\nELSEIF TR>5000\nX3000\n"
            "ELSE\nX8000\nENDIF\nENDWHILE\n")
    result = driver.check_file("p.prg", "arcus", text=text)
    trace = simulate(result.analysis.module, options=Options(until=12))
    starts = [(e.t, e.data["to"]["X"]) for e in trace.events if e.kind == "move" and e.data["to"]["X"] != e.data["from"]["X"]]
    assert starts == [(pytest.approx(2.0), 3000), (pytest.approx(5.09), 8000)]
    assert trace.axes["X"] == 8000


def test_the_virtual_device_counts_tr_down_while_it_runs() -> None:
    """The host writes and reads TR (L1701-L1702); it counts down in ms on the device's clock
    (L789-L793), which runs between commands (docs/LINK.md, "Virtual time"): TR=1000 read at
    once (`execute` takes no time on the line) is 1000, and 250 ms later, while a program waits
    out its DELAY=250, it reads 750; it stops at 0."""
    device = ArcusDevice()
    device.load_program("DELAY=250\nEND\n")
    assert device.execute("TR=1000") == "OK"
    assert device.execute("TR") == "1000"
    assert device.execute("SR=1") == "OK" and device.execute("SASTAT") == "1"
    device.elapse(0.25)
    assert device.execute("TR") == "750" and device.execute("SASTAT") == "0"
    device.elapse(2.0)
    assert device.execute("TR") == "0"
    assert device.execute("TR=2000000") == "?Invalid Command"
