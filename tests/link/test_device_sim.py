"""A program downloaded to a virtual device and run there ends where the simulator says it does.

The virtual devices run programs on mcc.sim's machine (link/device/machine.py): for every sample
of each dialect, a download followed by a run over a real socket must leave the axes where
`mcc sim` (sim.files.simulate_file, the same default run limit) predicts, read back through the
dialect's own position query, and the device must report the program running exactly when the
simulator's run did not end.
"""

from __future__ import annotations

import json
import re

import pytest
from conftest import SAMPLES
from linkhelpers import mcc, serve  # noqa: F401  (serve: fixture)

from mcc.compiler import driver
from mcc.link.device.arcus import ArcusDevice
from mcc.link.device.machine import RUN_LIMIT
from mcc.link.device.mcode import MCodeBus, MCodeDevice
from mcc.link.device.x150 import X150Device
from mcc.sim.files import simulate_file


def samples(dialect: str, ext: str) -> list[str]:
    return sorted(str(p) for p in (SAMPLES / dialect).glob(f"*{ext}"))


def replies(url: str, dialect: str, *commands: str) -> list[str]:
    result = mcc("send", "--port", url, "--dialect", dialect, *commands)
    assert result.returncode == 0, result.stdout + result.stderr
    return [line.split(": ", 1)[1].split("  (")[0] for line in result.stdout.splitlines()]


# What a host asks to know whether the program still runs, and the answer once it has stopped:
# MCode BY (lexium-mcode.txt L1828), X150 R (parker-x150.md L3224-L3240), Arcus SASTAT (L1626).
STATUS = {"mcode": ("PR BY", "0"), "x150": ("1R", "*R"), "arcus": ("SASTAT", "0")}


def wait_for_the_program(device, url: str, dialect: str, status: str | None = None, ends: bool = True) -> None:
    """Wait as a host does: ask the status, and while the program runs, wait a second (the host's
    sleep, `device.elapse`) and ask again, up to the run limit (a program that has not ended by
    then is held there, as `mcc sim` stops it at its time limit). A program the simulator says
    runs on (`ends` false: a machine's endless cycle) is waited for the whole run limit at once,
    as a host that lets the machine run for a minute does, then asked once: the answer is the
    same, without 60 round trips of a second each."""
    command, idle = STATUS[dialect]
    if not ends:
        device.elapse(RUN_LIMIT + 1.0)
    for _second in range(int(RUN_LIMIT) + 2):
        if replies(url, dialect, status or command)[0] == idle:
            return
        if not ends:
            return
        device.elapse(1.0)


def prediction(path: str):
    trace = simulate_file(path).trace
    assert trace is not None, f"{path} cannot be simulated"
    return trace


def position(trace, axis: str) -> int:
    return round(trace.axes.get(axis, 0.0))


PARTY = "party_mode_setup.mxt"


@pytest.mark.parametrize("path", [p for p in samples("mcode", ".mxt") if not p.endswith(PARTY)],
                         ids=lambda p: p.rsplit("/", 1)[-1])
def test_mcode_sample_runs_where_the_simulator_predicts(path, serve):
    device = MCodeDevice()
    server = serve(device)
    result = mcc("download", path, "--port", server.url, "--run", "--format", "json")
    assert result.returncode == 0, result.stdout + result.stderr
    assert json.loads(result.stdout)["ran"]
    trace = prediction(path)
    wait_for_the_program(device, server.url, "mcode", ends=trace.stopped == "end")
    p, busy = replies(server.url, "mcode", "PR P", "PR BY")
    assert int(p) == position(trace, "1")
    assert busy == ("0" if trace.stopped == "end" else "1")


def test_mcode_party_drives_run_where_the_simulator_predicts(serve):
    path = str(SAMPLES / "mcode" / PARTY)
    bus = MCodeBus(("a", "b"))
    server = serve(bus)
    result = mcc("download", path, "--port", server.url, "--party", "--address", "a", "--run")
    assert result.returncode == 0, result.stdout + result.stderr
    for _second in range(int(RUN_LIMIT) + 2):   # the host waits until neither drive is busy
        if all(b"\r\n0\r\n" in drive.command(f"{name}PR {flag}\n".encode())
               for name, drive in bus.drives.items() for flag in ("BY", "MV")):   # L1828, L4424
            break
        bus.elapse(1.0)
    trace = prediction(path)
    assert {"a", "b"} <= set(trace.axes)
    for name in ("a", "b"):
        # each drive's own axis; the position is read the way a host reads it, by its party name
        reply = bus.drives[name].command(f"{name}PR P\n".encode())
        assert int(reply.split(b"\r\n")[1]) == position(trace, name), (name, reply)


def run_lines(path: str) -> list[str]:
    """What runs an X150 file's program: its own top-level runs, else its power-up sequence (XPn,
    which a real X150 runs when it is switched on) run by hand."""
    top, inside = [], False
    for line in driver.compile_file(path).listing.text.splitlines():
        if re.match(r"^\d*XD\d+$", line):
            inside = True
        elif re.match(r"^\d*XT$", line):
            inside = False
        elif not inside:
            top.append(line)
    if any(re.match(r"^\d*(XR|XG|GOSUB|GOTO)\d", line) for line in top):
        return []
    return [re.sub(r"XP(\d+)", r"XR\1", line) for line in top if re.match(r"^\d*XP\d+$", line)]


@pytest.mark.parametrize("path", samples("x150", ".x150"), ids=lambda p: p.rsplit("/", 1)[-1])
def test_x150_sample_runs_where_the_simulator_predicts(path, serve):
    device = X150Device()
    server = serve(device)
    result = mcc("download", path, "--port", server.url, "--save", "--run", "--format", "json")
    assert result.returncode == 0, result.stdout + result.stderr
    extra = run_lines(path)
    assert json.loads(result.stdout)["ran"] or extra
    if extra:
        replies(server.url, "x150", *extra)
    trace = prediction(path)
    wait_for_the_program(device, server.url, "x150", f"{sorted(set(trace.axes) | set(device.sim.positions()))[0]}R",
                         ends=trace.stopped == "end")
    axes = sorted(set(trace.axes) | set(device.sim.positions()))
    reported = replies(server.url, "x150", *[f"{a}PR" for a in axes])
    assert [int(r.lstrip("*")) for r in reported] == [position(trace, a) for a in axes]
    status = replies(server.url, "x150", f"{axes[0]}R")[0]
    assert status == ("*R" if trace.stopped == "end" else "*B")


@pytest.mark.parametrize("path", samples("arcus", ".prg"), ids=lambda p: p.rsplit("/", 1)[-1])
def test_arcus_sample_runs_where_the_simulator_predicts(path, serve, tmp_path):
    # The program reaches a controller as the vendor's software puts it there; mcc copies it to
    # another controller as an image (mcc upload --image, mcc download FILE.sa --run).
    source = ArcusDevice()
    source.load_program(open(path).read(), path)
    image = tmp_path / "machine.sa"
    assert mcc("upload", "--port", serve(source).url, "--dialect", "arcus", "--image", str(image),
               "-o", str(tmp_path / "vars.prg")).returncode == 0
    device = ArcusDevice()
    server = serve(device)
    result = mcc("download", str(image), "--port", server.url, "--run", "--format", "json")
    assert result.returncode == 0, result.stdout + result.stderr
    assert json.loads(result.stdout)["ran"]
    trace = prediction(path)
    wait_for_the_program(device, server.url, "arcus", ends=trace.stopped == "end")
    names = sorted(trace.variables, key=lambda n: int(n[1:]))
    pp, state, *values = replies(server.url, "arcus", "PP", "SASTAT", *names)
    assert [int(v) for v in pp.split(":")] == [position(trace, a) for a in "XYZU"]
    assert state == ("0" if trace.stopped == "end" else "1")
    assert [int(v) for v in values] == [int(trace.variables[n]) for n in names]


def test_x150_single_step_runs_one_command_per_step_request():
    """XST1 then XR1: each # runs one command and answers its trace line, the move has been made
    after the 4th (parker-x150.md L5350-L5372); #n runs n (L5557)."""
    device = X150Device()
    for command in ("XE1", "XD1", "A5", "V2", "D10000", "G", "XT", "1XST1", "1XTR1", "XR1"):
        device.feed(f"{command}\r".encode())

    def send(command: str) -> list[str]:
        return [line for line in device.feed(f"{command}\r".encode()).decode().split("\r")[1:] if line != ">"]

    assert send("#") == [";SEQUENCE: 1 COMMAND: A5"]
    assert send("#2") == [";SEQUENCE: 1 COMMAND: V2", ";SEQUENCE: 1 COMMAND: D10000"]
    assert send("1PR") == ["*+0"] and send("1R") == ["*B"]
    assert send("#") == [";SEQUENCE: 1 COMMAND: G"]
    assert send("1PR") == ["*+10000"]
    assert send("#") == [";SEQUENCE: 1 COMMAND: XT"]
    assert send("1R") == ["*R"] and send("#") == []


def test_arcus_interpolation_waits_in_the_buffer_until_bo_and_keeps_the_speeds():
    """I x:y:z:speed starts at once with BO on, else waits for BO; its constant speed is its own
    (arcus-pmx-4ex-sa.txt L622-L630)."""
    device = ArcusDevice()

    def send(command: str) -> str:
        return device.feed(f"@00{command}\r".encode()).decode().rstrip("\r")

    assert send("I1000:0:0:500") == "OK" and send("PX") == "0"
    assert send("BO") == "OK" and 0 < int(send("PX")) < 1000   # on its way: time runs between commands
    assert send("PS").split(":")[0] == "500"                     # at its constant speed from the start
    move = [e.t for e in device.sim.last.events if e.kind == "move"]
    device.elapse(2.0)
    assert send("PX") == "1000"
    ends = [e.t for e in device.sim.last.events if e.kind == "move_end"]
    assert abs(ends[0] - move[0] - 2.0) < 1e-6        # 1000 pulses at 500 pulses/s, no ramp
    assert send("I1000:2000:0:250") == "OK" and int(send("PY")) < 2000
    device.elapse(10.0)
    assert send("PY") == "2000"
    assert send("HS") == "1000" and send("LS") == "100"
