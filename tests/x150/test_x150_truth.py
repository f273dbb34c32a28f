"""The X150 as its manual describes it (issues 22 and 23): the simulator runs the stream in the
order the device receives it, reports positions in the device's format, and the X150 writer and
the download keep what the program means. Each test cites the line of parker-x150.md it follows."""

from __future__ import annotations

import math

import pytest

from mcc.compiler import profiles
from mcc.sim.interpreter import simulate

from conftest import SAMPLES
from x150_helpers import module, output, src


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
    writes the `+` by a branch on the value (its PR sends a positive number bare and a negative one
    with `-`, lexium-mcode.txt L4880-L4906: `PR "*+",Z0` or `PR "*",Z0`; tests/test_cross_from_x150.py),
    and an MCode `PR P` (which sends `4000`) has no X150 form (refused, G003) rather than becoming
    a PR whose text the host would read as `*+4000`."""
    from mcc.compiler import driver

    assert output("1PR\n2PR\n") == ["1PR", "2PR"]
    to_mcode = driver.compile_file("p.x150", "x150", target="mcode", text="1PR\n")
    assert not to_mcode.has_errors and 'PR "*+",' in to_mcode.listing.text
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


# -- issue 23: X150 to X150 keeps what the program means, and the output is a fixed point ---------

# An unaddressed sequence run on the one device of the profile (x150-pdhx: axes = ["1"]), whose
# position mode is set with the device's address: `1MPA` holds for the unaddressed `D0 G` after it.
ADDRESSED_MODE = "XE1\nXD1\n1MPA\nD0\nG\nVAR1=12000\nL4\nD(VAR1)\nG\nVAR1=VAR1+12000\nN\nXT\nXR1\n"

# Programs from the manual's examples (the moves, H, MC and the loop they show), in this project's
# own words, and the shapes whose second compile differed (issue 23).
ROUND_TRIP = {
    "addressed_mode": ADDRESSED_MODE,
    "h_reverse": "D8000\nG\nH\nG\n",                                     # H, L1828
    "xd_download": "XE1\nXD1\nA10\nV10\nD8000\nG\nD4000\nH\nG\nXT\nXR1\n",  # XD, L4904-L4918
    "continuous": "MC\nA10\nV10\nG\nT1\nSB\n",                            # MC, L2498
    "loop_h_minus": "MN\nA10\nV10\nL3\nD8000\nG\nH-\nG\nN\n",             # L, H-, L1864
    "dead_distance": "1VAR1=12000\n1XE39\n1XD39\n1D4000\n1L2\n1A0.5\n1H+\n1D-400\n1G\n1N\n1A10\n1G\n1D0\n1XT\n"
                     "1XR39\n",
    "d_before_go": "1D4000\n1L2\n1N\n1XE24\n1XD24\n1MPI\n1G\n1XT\n1V5\n1G\n1XR24\n",
}


def move_ends(text: str) -> list[tuple[str, float]]:
    """Where each move goes, in order, on the default profile's device (an unaddressed command
    drives every device of the profile)."""
    trace = simulate(module(text), profile=profiles.load("x150-pdhx"))
    return [(axis, to) for e in trace.events if e.kind == "move" for axis, to in e.data["to"].items()]


def test_an_absolute_move_after_an_addressed_mpa_stays_absolute():
    """parker-x150.md L2608 (MPA: "positions relative to zero"), L181 (an unaddressed command is
    run by every device): on the profile's one device, `1MPA` makes the unaddressed `D0 G` a move
    to 0 and every `D(VAR1) G` a move to VAR1: 0, 12000, 24000, 36000, 48000, not 12000, 36000,
    72000, 120000 (issue 23). The X150 output at -O0 moves the same, and is written in MPA."""
    assert [p for _, p in move_ends(ADDRESSED_MODE)] == [0, 12000, 24000, 36000, 48000]
    written = compiled(ADDRESSED_MODE, "O0")
    assert "MPI" not in written.splitlines()
    assert move_ends(written) == move_ends(ADDRESSED_MODE)


def compiled(text: str, level: str) -> str:
    from mcc.compiler import driver

    result = driver.compile_file("p.x150", "x150", text=src(text), opt_level=level)
    assert not result.has_errors, [(d.code, d.span.line, d.message) for d in result.diagnostics]
    return result.listing.text


@pytest.mark.parametrize("level", ["O0", "O1", "O2"])
@pytest.mark.parametrize("name", sorted(ROUND_TRIP))
def test_compiling_the_x150_output_again_gives_it_back_and_it_moves_the_same(name, level):
    """Issue 23: X150 to X150, compile(compile(p)) == compile(p), and the output's moves end where
    the source's do (the simulator, L177 stream order). A D that H, H+ or H- (L1828, L1864) makes
    dead, a D the optimizer leaves set twice, and a D written just before its G are written where
    the second compile writes them."""
    first = compiled(ROUND_TRIP[name], level)
    assert compiled(first, level) == first
    assert move_ends(first) == move_ends(ROUND_TRIP[name])


@pytest.mark.parametrize("level", ["O0", "O1", "O2"])
@pytest.mark.parametrize("path", sorted(SAMPLES.glob("x150/*.x150")), ids=lambda p: p.name)
def test_every_x150_sample_compiles_to_a_fixed_point_that_moves_the_same(path, level):
    """Issue 23 on the project's samples, at every -O level: the output compiled again is the same
    text, and its moves end where the source's do."""
    text = path.read_text()
    first = compiled(text, level)
    assert compiled(first, level) == first
    assert move_ends(first) == move_ends(text)


def test_save_keeps_its_device_address():
    """parker-x150.md L181: SV is device specific ("require a device address for execution"; the
    checker's X117 without one). `1SV` after unaddressed commands is written `1SV`, not `SV`, and the
    output compiles again without X117 (issue 23)."""
    from mcc.compiler import driver

    written = compiled("A10\nV1\nD4000\nG\n1SV\n", "O0")
    assert written.splitlines()[-1] == "1SV"
    again = driver.check_file("o.x150", "x150", text=written)
    assert "X117" not in [d.code for d in again.diagnostics]


def test_a_ramp_time_is_converted_again_after_a_speed_change():
    """parker-x150.md L199: X150's A is an acceleration in rev/s^2; an Arcus ACC is a ramp time
    (arcus-pmx-4ex-sa ACC: ms from low to high speed). With ACC=100 (0.1 s) the move at HSPD=1000
    (0.25 rev/s at 4000 steps/rev) ramps at 0.25/0.1 = A2.5; after HSPD=4000 (V1) the same 0.1 s
    is A10, written after the V (issue 23: the A2.5 was kept, so the second move ramped 4 times
    too slowly and --verify refused it, S010)."""
    from mcc.compiler import driver

    source = "HSPD=1000\nACC=100\nX1000\nWAITX\nHSPD=4000\nX5000\nWAITX\nEND\n"
    result = driver.compile_file("p.prg", "arcus", target="x150", text=source)
    assert not result.has_errors, [(d.code, d.message) for d in result.diagnostics]
    lines = [line for line in result.listing.text.splitlines() if not line.startswith(";")]
    assert lines[lines.index("V0.25") + 1] == "A2.5"
    assert lines[lines.index("V1") + 1] == "A10"
    # an acceleration (MCode A, steps/s^2) does not change with the speed: no A after the second VM
    mcode = driver.compile_file("p.mxt", "mcode", target="x150",
                                text="PG 1\nVM=4000\nA=40000\nD=40000\nMA 4000\nH\nVM=8000\nMA 0\nH\nE\nPG\n",
                                profile=profiles.load("x150-pdhx"))
    written = [line for line in mcode.listing.text.splitlines() if not line.startswith(";")]
    assert len([w for w in written if w.lstrip("0123456789").startswith("A")]) == 1, written


# -- a quoted command string sent to another device ---------------------------------------------

REMOTE = "1XE5\n1XD5\n1A10\n1V1\n1D4000\n1G\n1\"2XR3\"\n1XT\n2XE3\n2XD3\n2A10\n2V1\n2D2000\n2G\n2XT\n1XR5\n"


def test_a_quoted_run_command_starts_the_sequence_on_the_other_device():
    """parker-x150.md L5593: the quote command is used "to command other devices to move"; L5614:
    `1"2XR1"`: "Once the move is done, Go Sequence 1 is commanded on a unit with device address 2".
    `1"2XR3"` is a call of SEQ3@2, not a print: device 1 moves 4000 (1.1 s at V1 A10: 0.1 s ramps
    of 200 steps each and 3600 steps at 4000 steps/s), then device 2 runs sequence 3 (2000 steps)."""
    trace = simulate(module(REMOTE), profile=profiles.load("x150-pdhx"))
    assert trace.prints == []
    assert [e.data["routine"] for e in trace.events if e.kind == "call"] == ["SEQ5@1", "SEQ3@2"]
    assert trace.axes == {"1": 4000, "2": 2000}


def test_a_quoted_run_command_is_written_back_as_a_quote_and_refused_where_it_cannot_be():
    """parker-x150.md L5593, L5614: inside device 1's sequence only the quote can start device 2's
    sequence, so the writer writes `1"2XR3"` (and the output compiles to itself); MCode, one drive,
    refuses device 2's moves, and a sequence stored on the controller is refused by MCode and Arcus
    with the quote's line."""
    from mcc.compiler import driver

    written = compiled(REMOTE, "O0")
    assert '1"2XR3"' in written.splitlines() and compiled(written, "O0") == written
    for target in ("mcode", "arcus"):
        result = driver.compile_file("p.x150", "x150", target=target, text='MN\nA10\nV5\nD12500\nG\n1"2XR1"\n')
        assert [(d.code, d.span.line) for d in result.diagnostics if d.severity == "error"] == [("G003", 6)]


def test_a_message_is_still_a_print():
    """parker-x150.md L5593-L5605: any other quoted text is transmitted to the host (`1"MOVE_DONE"`,
    '_' sent as a space), and a command string for the sender itself is text too."""
    trace = simulate(module('1"MOVE_DONE"\n1"1XR3"\n'))
    assert [text for _, text in trace.prints] == ["MOVE DONE", "1XR3"]


def test_the_virtual_chain_relays_a_quoted_command_to_the_other_device():
    """parker-x150.md L5614: device 1 sends `2XR3` to device 2, which runs its sequence 3, whether
    the quote is sent by the host or stored in device 1's sequence 5."""
    from mcc.link.device.x150 import X150Device

    device = X150Device()
    for line in REMOTE.splitlines()[:-1]:
        device.feed((line + "\r").encode())
    device.feed(b'1"2XR3"\r')
    assert device.feed(b"2PR\r") == b"2PR\r*+2000\r>"
    device.feed(b"1XR5\r")
    assert (device.feed(b"1PR\r"), device.feed(b"2PR\r")) == (b"1PR\r*+4000\r>", b"2PR\r*+4000\r>")
