"""Immediate commands on a virtual device run on the simulator's machine: sent one at a time, they
leave the device, once the host has waited for the moves to end, where `mcc sim` leaves the same
commands written as one file (the same final positions; the device's moves end no earlier, since
each command also takes its time on the line and in the device, lexium-mcode.txt L6821), and the
device's queries read that machine at the device's clock."""

from __future__ import annotations

from hypothesis import assume, given, settings
from hypothesis import strategies as st

from mcc.link.device.arcus import ArcusDevice
from mcc.link.device.machine import RUN_LIMIT
from mcc.link.device.mcode import MCodeDevice
from mcc.link.device.x150 import X150Device
from mcc.sim.files import simulate_file


def simulated(tmp_dir, name: str, text: str):
    path = tmp_dir / name
    path.write_text(text)
    trace = simulate_file(str(path)).trace
    assert trace is not None
    # Only runs whose every move finishes within the time limit: the device gives each command
    # the whole limit, the file shares one limit between all its moves.
    moves = sum(1 for e in trace.events if e.kind == "move" and e.data["from"] != e.data["to"])
    assume(trace.stopped == "end" and moves == sum(1 for e in trace.events if e.kind == "move_end"))
    return trace


def waited(device) -> float:
    """The host waits until every move has ended; how long the device was busy from its first run."""
    device.elapse(RUN_LIMIT)
    start = device.sim.first_start
    return 0.0 if start is None else max(device.sim.busy_until, start) - start


def reply_lines(device, command: bytes) -> list[bytes]:
    return [line for line in device.feed(command).replace(b"\r\n", b"\r").split(b"\r") if line]


MCODE_COMMAND = st.one_of(
    st.tuples(st.sampled_from(["MA", "MR"]), st.integers(-200_000, 200_000)).map(lambda c: f"{c[0]} {c[1]}"),
    st.integers(2000, 800_000).map(lambda v: f"VM={v}"),   # above VI (1000 by default)
    st.integers(10_000, 2_000_000).map(lambda a: f"A={a}"),
)


@given(st.lists(MCODE_COMMAND, min_size=1, max_size=8))
@settings(max_examples=20, deadline=None)
def test_mcode_commands_one_at_a_time_end_where_the_simulator_says(tmp_path_factory, commands):
    trace = simulated(tmp_path_factory.mktemp("mcode"), "cmds.mxt", "\n".join(commands) + "\n")
    device = MCodeDevice()
    for command in commands:
        assert device.feed(f"{command}\r".encode()).endswith(b">"), command
    busy = waited(device)
    assert reply_lines(device, b"PR P\r")[1] == str(round(trace.axes.get("1", 0))).encode()
    assert busy >= trace.time - 1e-6


X150_COMMAND = st.one_of(
    st.sampled_from(["1MPA", "1MPI", "1G"]),
    st.integers(-40_000, 40_000).map(lambda d: f"1D{d}"),
    st.integers(1, 20).map(lambda v: f"1V{v}"),
)


@given(st.lists(X150_COMMAND, min_size=1, max_size=8))
@settings(max_examples=20, deadline=None)
def test_x150_commands_one_at_a_time_end_where_the_simulator_says(tmp_path_factory, commands):
    trace = simulated(tmp_path_factory.mktemp("x150"), "cmds.x150", "\n".join(commands) + "\n")
    device = X150Device()
    for command in commands:
        device.feed(f"{command}\r".encode())
    busy = waited(device)
    # PR: "a number preceded by a sign" (parker-x150.md L3141), + included: *+4000, *-25600
    assert reply_lines(device, b"1PR\r")[1] == f"*{round(trace.axes.get('1', 0)):+d}".encode()
    assert busy >= trace.time - 1e-6


ARCUS_COMMAND = st.one_of(
    st.sampled_from(["ABS", "INC"]),
    st.tuples(st.sampled_from("XY"), st.integers(-30_000, 30_000)).map(lambda m: f"{m[0]}{m[1]}"),
    st.integers(100, 20_000).map(lambda v: f"HSPD={v}"),
)


@given(st.lists(ARCUS_COMMAND, min_size=1, max_size=8))
@settings(max_examples=20, deadline=None)
def test_arcus_host_commands_end_where_the_simulator_says(tmp_path_factory, commands):
    # The host spells the speed HS=; the standalone program HSPD= (the same setting, L1552).
    trace = simulated(tmp_path_factory.mktemp("arcus"), "cmds.prg", "\n".join(commands) + "\nEND\n")
    device = ArcusDevice()
    for command in commands:
        host = command.replace("HSPD=", "HS=")
        assert device.feed(f"@00{host}\r".encode()) == b"OK\r", host
    busy = waited(device)
    pp = reply_lines(device, b"@00PP\r")[0].decode()
    assert [int(v) for v in pp.split(":")] == [round(trace.axes.get(a, 0)) for a in "XYZU"]
    # A host move does not wait for the one before on another axis (they overlap, as in the
    # program); one on the same axis waits for it (decision 0010): never shorter than the file.
    assert busy >= trace.time - 1e-6 or len({c[0] for c in commands if c[0] in "XY"}) > 1


def test_mcode_queries_read_the_machine():
    device = MCodeDevice()
    for command in ["VM=5000", "O2=1", "SL 2000"]:
        assert device.feed(f"{command}\r".encode()).endswith(b">")
    ask = lambda name: reply_lines(device, f"PR {name}\r".encode())[1]  # noqa: E731
    assert (ask("VM"), ask("O2"), ask("OT"), ask("MV"), ask("V")) == (b"5000", b"1", b"2", b"1", b"2000")
    # the slew runs on through later commands, until it is stopped
    device.feed(b"R1=3\r")
    assert (ask("MV"), ask("R1")) == (b"1", b"3")
    device.feed(b"SL 0\r")
    assert (ask("MV"), ask("V")) == (b"0", b"0")


def test_x150_sequence_run_and_stop_on_the_machine():
    device = X150Device()
    for command in ["1XD5", "1MPI", "1D1000", "1L", "1G", "1N", "1XT", "1XR5"]:
        device.feed(f"{command}\r".encode())
    # an endless loop of moves: running (R is immediate, parker-x150.md L3224); a second later the
    # axis has moved (PR, L3141)
    assert reply_lines(device, b"1R\r")[1] == b"*B"
    device.elapse(1.0)
    assert int(reply_lines(device, b"1PR\r")[1].lstrip(b"*")) > 0
    device.feed(b"1S\r")
    assert reply_lines(device, b"1R\r")[1] == b"*R"


def test_arcus_jog_stop_and_subroutine_call():
    device = ArcusDevice()
    device.load_program("V1=0\nEND\nSUB 3\nV1=V1+5\nX2500\nWAITX\nENDSUB\n")
    assert device.feed(b"@00JY-\r") == b"OK\r"
    assert reply_lines(device, b"@00PS\r")[0].split(b":")[1] != b"0"
    assert device.feed(b"@00STOP\r") == b"OK\r"   # STOP decelerates (arcus-pmx-4ex-sa.txt L696)
    device.elapse(1.0)
    assert reply_lines(device, b"@00PS\r")[0] == b"0:0:0:0"
    assert device.feed(b"@00GS3\r") == b"OK\r"
    assert reply_lines(device, b"@00V1\r") == [b"5"] and reply_lines(device, b"@00SASTAT\r") == [b"1"]
    device.elapse(10.0)   # the subroutine's move ends (WAITX) and so does the subroutine
    assert (reply_lines(device, b"@00PX\r"), reply_lines(device, b"@00SASTAT\r")) == ([b"2500"], [b"0"])
    assert device.feed(b"@00GS9\r") == b"?Invalid Command\r"   # no subroutine 9 (L823)
