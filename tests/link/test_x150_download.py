"""An X150 download round trip with the virtual device: the sender and the device agree on which
device answers a report. Every report is device specific (parker-x150.md L181), so the read-back
of a sequence defined without an address asks each device, one at a time."""

from __future__ import annotations

import json

from linkhelpers import mcc, serve  # noqa: F401  (serve: fixture)

from mcc.backends.listing import ListingLine
from mcc.link.device.x150 import X150Device
from mcc.link.download import download
from mcc.link.ports import Channel, open_port
from mcc.link.settings import LinkSettings
from mcc.link.x150 import Protocol

# An unaddressed sequence (stored by every device, XD is Universal: L4899) of 17 commands: the
# shape of the cross-compiled program whose read-back failed ("sent '17', device holds '68'").
UNADDRESSED = ["XE30", "XD30", "MN", "MPI", "A10", "V1", "VAR1=0",
               *["D1000", "G", "VAR1=VAR1+1"] * 3, "T0.1", "OUT1", "PZ", "XT", "1XR30"]


def protocol(server, address: str = "") -> Protocol:
    settings = LinkSettings(address=address, timeout=1.0)
    return Protocol(Channel(open_port(server.url, settings), settings), settings)


def test_an_unaddressed_sequence_downloads_and_reads_back_from_each_device(serve):
    """L181: XSD, XSS and XU are device specific; the sender addresses them to each device of the
    program (here device 1, named by `1XR30`) and compares the 17 stored commands with what it
    sent. Before, the chain's four virtual devices all answered an unaddressed XU at once."""
    device = X150Device()
    server = serve(device)
    proto = protocol(server)
    steps = proto.plan([ListingLine(t) for t in UNADDRESSED])
    assert [s.command for s in steps if s.kind == "verify"] == ["1XSD"]
    report = download(proto, steps, save=True, run=False)
    proto.channel.close()
    assert report.ok and report.verified and report.saved, report.mismatches
    assert len(device.units["1"].sequences[30]) == 17
    assert device.units["1"].saved["sequences"][30] == device.units["1"].sequences[30]


def test_the_download_command_verifies_a_cross_compiled_program(serve, tmp_path):
    """The whole command: a program written by the X150 backend (unaddressed sequences) is sent,
    read back with addressed XU (L181, L5442 `aXU<n>`), saved and reported verified."""
    source = tmp_path / "p.prg"
    source.write_text("HSPD=1000\nACC=100\nX1000\nWAITX\nX0\nWAITX\nEND\n")
    listing = tmp_path / "p.x150"
    compiled = mcc("compile", str(source), "--target", "x150", "-o", str(listing))
    assert compiled.returncode == 0, compiled.stderr
    assert any(line.startswith("XD") for line in listing.read_text().splitlines())
    server = serve(X150Device())
    result = mcc("download", str(listing), "--port", server.url, "--save", "--format", "json")
    report = json.loads(result.stdout)
    assert result.returncode == 0 and report["verified"] and report["saved"], result.stdout + result.stderr


def test_a_device_specific_report_without_an_address_is_not_answered():
    """L181: device specific commands "require a device address for execution"; an unaddressed XU
    or PR on a chain of four is executed by none of them (so their answers never collide)."""
    device = X150Device()
    for line in ["1XD2", "1A10", "1XT", "2XD2", "2V1", "2XT"]:
        device.feed((line + "\r").encode())
    assert device.feed(b"XU2\r") == b"XU2\r>"
    assert device.feed(b"1XU2\r") == b"1XU2\rXD2\r1A10\rXT\r>"
    assert device.feed(b"PR\r") == b"PR\r>"
