"""Injected faults end in a clear message and a known device state; nothing is reported as done
that is not. Each download runs through the `mcc` command against a virtual device on a socket."""

from __future__ import annotations

import json

from conftest import SAMPLES
from linkhelpers import mcc, serve  # noqa: F401  (serve: fixture)

from mcc.compiler import driver
from mcc.link.device.arcus import ArcusDevice
from mcc.link.device.faults import Faults
from mcc.link.device.mcode import MCodeDevice
from mcc.link.device.x150 import X150Device
from mcc.link.mcode import Protocol
from mcc.link.settings import LinkSettings

MXT = str(SAMPLES / "mcode" / "pick_and_place.mxt")
HELLO = 2  # commands the MCode download sends before its plan: an empty line, PR VR


def plan():
    return Protocol(None, LinkSettings()).plan(driver.compile_file(MXT).listing.lines)


def received_number(command: str) -> int:
    """Which command the device receives when the download sends `command` (1-based)."""
    return HELLO + 1 + [s.command for s in plan()].index(command)


def source_of(command: str) -> str:
    step = next(s for s in plan() if s.command == command)
    return f"{step.sources[0].file}:{step.sources[0].line}"


def download(url: str, *extra: str, path: str = MXT):
    result = mcc("download", path, "--port", url, "--save", "--timeout", "1.0", *extra)
    return result, result.stderr


def test_lost_reply_on_a_stored_line_stops_and_reads_back(serve):
    device = MCodeDevice(Faults(drop_reply=received_number("HM 1")))
    result, err = download(serve(device).url)
    assert result.returncode == 1
    assert "the reply to `HM 1` was lost" in err
    assert source_of("HM 1") in err and "HM 1" in err
    # The device did store it (only the reply was lost): the report says so, as read back.
    assert "program memory now holds 2 lines, the first 2 as sent" in err
    assert "NOT saved" in err and device.saved.program == [] and not device.program_mode
    assert device.memory.program == ["LB SU", "HM 1"]


def test_garbled_line_is_named_with_what_the_device_holds(serve):
    device = MCodeDevice(Faults(garble=received_number("MA PP")))
    result, err = download(serve(device).url)
    assert result.returncode == 1
    assert "the reply to `MA PP` was garbled" in err
    assert source_of("MA PP") in err
    stored = device.memory.program
    assert "NOT saved" in err and device.saved.program == []
    assert f"program memory now holds {len(stored)} lines" in err
    if stored[-1] != "MA PP":  # the noisy line was stored as received: the report names it
        assert f"`{stored[-1]}`, not `MA PP` as sent" in err


def test_device_error_mid_download_names_the_source_line(serve):
    device = MCodeDevice(program_lines=5)
    result, err = download(serve(device).url, "--format", "json")
    report = json.loads(result.stdout)
    assert result.returncode == 1 and not report["ok"] and not report["saved"] and not report["verified"]
    assert report["error"] == "45" and "Overflow Program Space" in report["meaning"]
    sixth = [s for s in plan() if s.stored][5]
    assert report["failed"]["command"] == sixth.command
    assert report["failed"]["sources"] == [f"{MXT}:{sixth.sources[0].line}"]
    assert "program memory now holds 5 lines, the first 5 as sent" in report["device_state"]
    assert "program mode was left" in report["device_state"] and not device.program_mode
    assert "what the device held before was cleared (`CP 1`)" in report["device_state"]


def test_port_closing_mid_download(serve):
    device = MCodeDevice(Faults(close=received_number("CL K1")))
    result, err = download(serve(device).url)
    assert result.returncode == 1
    assert "the port closed" in err
    assert "NOT saved" in err and "`CL K1` may have reached the device" in err
    assert device.saved.program == []


def test_checksum_mode_resends_a_line_the_device_nak_ed(serve):
    device = MCodeDevice(Faults(garble=received_number("IC NP")))
    device.memory.variables["CK"] = 1
    result, err = download(serve(device).url, "--checksum", "1", "--format", "json")
    report = json.loads(result.stdout)
    assert result.returncode == 0, err
    assert report["verified"] and report["saved"]
    assert "IC NP" in device.saved.program
    sent = [row["data"] for row in report["transcript"] if row["dir"] == "send" and row["data"].startswith("IC NP")]
    assert len(sent) == 2  # NAK, then sent again


def test_x150_sequence_buffer_full_is_reported_with_its_source(serve, tmp_path):
    path = str(SAMPLES / "x150" / "01_feed_punch_cell.x150")
    device = X150Device(capacity=40)
    result, err = download(serve(device).url, path=path)
    assert result.returncode == 1
    assert "device error 2: sequence buffer full" in err
    assert path in err and "NOT saved" in err
    assert all(unit.saved["sequences"] == {} for unit in device.units.values())


def test_x150_garbled_echo_closes_the_open_sequence(serve):
    path = str(SAMPLES / "x150" / "01_feed_punch_cell.x150")
    device = X150Device(Faults(garble=22))
    result, err = download(serve(device).url, path=path)
    assert result.returncode == 1 and "garbled" in err
    assert "closed (XT) and erased" in err
    assert all(unit.defining is None for unit in device.units.values())
    assert 3 not in device.units["2"].sequences


def test_arcus_image_download_cut_short(serve, tmp_path):
    source = ArcusDevice()
    source.load_program(open(SAMPLES / "arcus" / "pick_and_place.prg").read())
    image = tmp_path / "machine.sa"
    image.write_text("".join(f"SA{i}={line}\n" for i, line in sorted(source.lines.items())))
    device = ArcusDevice(Faults(close=12))
    result, err = download(serve(device).url, path=str(image))
    assert result.returncode == 1
    assert "the port closed" in err
    assert "partly written and written to flash as they arrived" in err
    assert "could not read back" in err
    written = len(device.lines)
    assert 0 < written < len(source.lines) and device.state == "0"  # cut short, and not run


def test_a_device_that_does_not_answer(serve, tmp_path):
    image = tmp_path / "machine.sa"
    image.write_text("SA0=ABS\nSA1=END\n")
    device = ArcusDevice(address="07")   # mcc talks to @00: nobody answers
    server = serve(device)
    result = mcc("download", str(image), "--port", server.url, "--timeout", "0.2", "--retries", "1")
    assert result.returncode == 1
    assert "no answer from device 00" in result.stderr and "nothing was changed on the device" in result.stderr
    assert device.lines == {}
    sent = mcc("send", "--port", server.url, "--dialect", "arcus", "--timeout", "0.2", "--retries", "1", "SASTAT")
    assert sent.returncode == 1 and "reply lost" in sent.stdout


def test_a_refused_line_that_appears_twice_is_named_by_its_own_source_line(serve):
    stored = [s for s in plan() if s.stored]
    index = [i for i, s in enumerate(stored) if s.command == "H"][1]   # the second plain `H`
    device = MCodeDevice(program_lines=index)
    result, err = download(serve(device).url, "--format", "json")
    report = json.loads(result.stdout)
    assert report["failed"]["command"] == "H"
    assert report["failed"]["sources"] == [f"{MXT}:{stored[index].sources[0].line}"]
    first_h = stored[[i for i, s in enumerate(stored) if s.command == "H"][0]].sources[0].line
    assert stored[index].sources[0].line != first_h


def test_a_failed_download_never_runs_the_program_on_the_machine(serve):
    # The X150 sample moves device 1 when it runs; each fault mid-download leaves the machine of
    # the virtual device (the simulator's) where it was, and the program not running.
    path = str(SAMPLES / "x150" / "01_feed_punch_cell.x150")
    for fault in (Faults(garble=22), Faults(drop_reply=22), Faults(close=22)):
        device = X150Device(fault)
        result, err = download(serve(device).url, "--run", path=path)
        assert result.returncode == 1, fault
        assert "NOT saved" in err and "ran" not in result.stdout, fault
        assert all(p == 0 for p in device.sim.positions().values()), (fault, device.sim.positions())
        assert device.sim.status != "running", fault
        assert not any(e.kind == "move" for trace in device.sim.traces for e in trace.events), fault   # nothing moved
    # The same download without a fault runs, and moves.
    device = X150Device()
    result, err = download(serve(device).url, "--run", path=path)
    assert result.returncode == 0, err
    assert device.sim.positions()["1"] != 0
