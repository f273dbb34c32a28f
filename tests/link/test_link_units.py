"""The parts of the link one at a time: framing, settings, programs on the simulator's machine,
send, terminal, dry runs, and the message without pyserial."""

from __future__ import annotations

import json
import sys

import pytest
from conftest import SAMPLES
from hypothesis import given
from hypothesis import strategies as st
from linkhelpers import mcc, serve  # noqa: F401  (serve: fixture)

from mcc.link.device.arcus import ArcusDevice
from mcc.link.device.mcode import MCodeDevice
from mcc.link.device.x150 import X150Device
from mcc.link.errors import LinkError
from mcc.link.mcode import Protocol, checksum
from mcc.link.ports import Channel, open_port
from mcc.link.settings import LinkSettings, from_profile
from mcc.link.terminal import Terminal

MXT = str(SAMPLES / "mcode" / "pick_and_place.mxt")


def test_mcode_checksum_matches_the_manuals_worked_examples():
    assert checksum("MR 51200") == 0xC9   # L2066-L2076
    assert checksum("MR 1") == 0x90       # L6875-L6882


def test_mcode_party_and_checksum_framing():
    plain = Protocol(None, LinkSettings())
    assert plain.frame("MR 1") == b"MR 1\r"
    party = Protocol(None, LinkSettings(party=True, address="a", checksum=1))
    framed = party.frame("MR 1")
    assert framed[:5] == b"aMR 1" and framed[-1:] == b"\n"
    assert sum(framed[:-1]) & 0x7F == 0   # what the drive checks on receipt (L6888-L6892)
    assert party.frame("*VM=5")[:5] == b"*VM=5"   # already addressed: no second prefix


def test_profile_link_table_and_overrides():
    from mcc.compiler import profiles

    settings = from_profile(profiles.load("pmx-4ex-sa"), {"baudrate": 115200, "timeout": None})
    assert (settings.address, settings.baudrate, settings.timeout) == ("00", 115200, 1.0)
    assert from_profile(profiles.load("lmd-c")).address == "!"


def test_unknown_link_key_in_a_user_profile_is_a_usage_error(tmp_path):
    prof = tmp_path / "mine.toml"
    prof.write_text('extends = "lmd-c"\nname = "mine"\n\n[link]\nbaud = 19200\n')
    result = mcc("send", "--port", "loop://", "--dialect", "mcode", "--profile", str(prof), "PR P")
    assert result.returncode == 2 and "unknown [link] keys baud" in result.stderr


def test_without_pyserial_the_message_says_how_to_install(monkeypatch):
    monkeypatch.setitem(sys.modules, "serial", None)
    with pytest.raises(LinkError, match=r'pip install "mcc\[link\]"'):
        open_port("loop://", LinkSettings())
    result = mcc("send", "--port", "loop://", "--dialect", "mcode", "PR P")
    assert result.returncode == 1 and 'pip install "mcc[link]"' in result.stderr


def test_dry_run_prints_the_framed_exchange_without_a_port():
    result = mcc("download", MXT, "--port", "/dev/does-not-exist", "--dry-run", "--format", "json")
    assert result.returncode == 0, result.stderr
    steps = json.loads(result.stdout)["steps"]
    assert steps[0]["command"] == "CP 1" and steps[0]["bytes"] == "CP 1\r"
    save = [s for s in steps if s["kind"] == "save"]
    assert save and save[0]["bytes"] is None and "held back" in save[0]["note"]
    stored = [s for s in steps if s["command"] == "HM 1"][0]
    assert stored["sources"] == [f"{MXT}:14"] or stored["sources"][0].startswith(MXT + ":")


def test_programs_run_on_the_simulators_machine():
    device = MCodeDevice()
    program = ["VA QA=0", "VA QB=0", "PG 1", "LB GA", "QA=5", "QB=QA*3", "CL KB", "E", "LB KB", "QA=QA+1",
               "RT", "PG", "EX GA", "PR QA", "PR QB", "PR BY"]
    replies = [device.feed((line + "\r").encode()) for line in program]
    assert all(reply.endswith(b">") for reply in replies), replies
    assert replies[-3:] == [b"PR QA\r\n6\r\n>", b"PR QB\r\n15\r\n>", b"PR BY\r\n0\r\n>"]
    # The program goes on after EX has been answered (the drive answers after the command's
    # execution time, lexium-mcode.txt L6821): BY is 1 while it runs (L1828). A host polls BY, waiting
    # between polls, until the program has ended; P is then where its last move stopped.
    for line in ["CP 1", "PG 10", "LB GM", "MR 1000", "H", "MR -250", "E", "PG", "EX 10"]:
        assert device.feed((line + "\r").encode()).endswith(b">")
    assert device.feed(b"PR BY\r") == b"PR BY\r\n1\r\n>"
    for _poll in range(100):
        if device.feed(b"PR BY\r") == b"PR BY\r\n0\r\n>":
            break
        device.elapse(0.01)
    assert device.feed(b"PR P,\" \",BY,\" \",MV\r") == b"PR P,\" \",BY,\" \",MV\r\n750 0 0\r\n>"
    # A program waiting for an input that nothing sets is still running: busy.
    for line in ["PG 20", "LB GW", "BR GW,I1=0", "E", "PG", "EX GW"]:
        assert device.feed((line + "\r").encode()).endswith(b">")
    assert device.feed(b"PR BY\r") == b"PR BY\r\n1\r\n>"


def test_mcode_errors_are_the_manuals_codes():
    device = MCodeDevice()
    cases = {"FOO=1": 20, "A=5": 21, "I1=1": 25, "VA MA": 29, "ZZ 5": 60, "PG": 46, "EX QQ": 30, "L QQ": 30}
    for command, code in cases.items():
        assert device.feed((command + "\r").encode()).endswith(b"?"), command
        assert device.feed(b"PR ER\r") == f"PR ER\r\n{code}\r\n>".encode(), command
    device.feed(b"LK=1\r")
    assert device.feed(b"L\r").endswith(b"?") and device.feed(b"PR ER\r") == b"PR ER\r\n44\r\n>"


def test_send_decodes_replies_and_stops_at_a_refusal(serve):
    server = serve(MCodeDevice())
    result = mcc("send", "--port", server.url, "--dialect", "mcode", "--format", "json", "PR VM", "XX=1", "PR P")
    data = json.loads(result.stdout)
    assert result.returncode == 1 and not data["ok"]
    assert [r["command"] for r in data["replies"]] == ["PR VM", "XX=1"]
    assert data["replies"][1]["error"] == "20" and "Unknown Variable" in data["replies"][1]["meaning"]


def test_x150_upload_needs_the_password_when_protected(serve, tmp_path):
    device = X150Device()
    for line in ["1XD2", "1A10", "1G", "1XT", "1PASS4321", "1SV"]:
        device.feed((line + "\r").encode())
    server = serve(device)
    locked = mcc("upload", "--port", server.url, "--dialect", "x150")
    assert locked.returncode == 1 and "--password" in locked.stderr
    out = tmp_path / "up.x150"
    result = mcc("upload", "--port", server.url, "--dialect", "x150", "--password", "4321", "-o", str(out))
    assert result.returncode == 0, result.stderr
    assert out.read_text() == "1XE2\n1XD2\n1A10\n1G\n1XT\n"
    assert device.units["1"].locked  # protection restored


def test_terminal_decodes_replies_and_explains_codes(serve):
    server = serve(ArcusDevice())
    settings = LinkSettings(address="00", timeout=1.0)
    proto = __import__("mcc.link.arcus", fromlist=["Protocol"]).Protocol(
        Channel(open_port(server.url, settings), settings), settings)
    lines = iter(["SASTAT", "V3=7", "V3", "BOGUS", ":explain 4", ":explain M101", ":quit"])
    shown: list[str] = []

    def read(_prompt):
        return next(lines)

    Terminal(proto, "arcus", read=read, write=shown.append).loop()
    proto.channel.close()
    assert shown[1:5] == ["0  (stopped)", "OK", "7", "error Invalid Command: Invalid Command"]
    assert shown[5] == "SASTAT 4: in error"
    assert "M101" in shown[6]


@given(st.text(alphabet=st.characters(min_codepoint=32, max_codepoint=126), min_size=1, max_size=60),
       st.sampled_from(["!", "a", "Z", "7"]))
def test_every_checksummed_frame_passes_the_receivers_check(command, name):
    framed = Protocol(None, LinkSettings(party=True, address=name, checksum=1)).frame(command)
    body = framed[:-1]
    assert framed[-1:] == b"\n" and body[-1] & 0x80
    assert sum(body) & 0x7F == 0   # the low 7 bits of the sum, checksum included, are 0 (L6888)


def test_a_port_that_cannot_be_opened():
    result = mcc("download", MXT, "--port", "/dev/mcc-no-such-port")
    assert result.returncode == 1
    assert "cannot open port /dev/mcc-no-such-port" in result.stderr
    assert "nothing was sent" in result.stderr


def test_a_read_back_that_differs_is_never_saved_or_run(serve):
    from mcc.backends.listing import ListingLine
    from mcc.link.download import download
    from mcc.link.x150 import Protocol as X150Protocol

    device = X150Device()
    server = serve(device)
    settings = LinkSettings(address="1", timeout=1.0)
    proto = X150Protocol(Channel(open_port(server.url, settings), settings), settings)
    lines = [ListingLine(t) for t in ["1XE5", "1XD5", "1A10", "1QQQ7", "1XT", "1XR5"]]
    report = download(proto, proto.plan(lines), save=True, run=True)
    proto.channel.close()
    assert not report.ok and not report.verified and not report.saved and not report.ran
    assert report.message == "the device does not hold what was sent"
    assert [(m.where, m.found) for m in report.mismatches] == [("device 1 sequence 5", "missing (XSS 0)")]
    assert device.units["1"].saved["sequences"] == {} and device.sim.status != "running"


def test_a_drive_in_echo_mode_2_is_downloaded_in_mode_0_and_left_in_mode_2(serve, tmp_path):
    device = MCodeDevice()
    device.memory.variables["EM"] = 2   # no prompt, only PR and L output
    prof = tmp_path / "quiet.toml"
    prof.write_text('extends = "lmd-c"\nname = "quiet"\n\n[link]\necho = 2\n')
    result = mcc("download", MXT, "--port", serve(device).url, "--profile", str(prof), "--save")
    assert result.returncode == 0, result.stderr
    from mcc.compiler import driver

    compiled = driver.compile_file(str(MXT)).listing.text.splitlines()
    start, end = compiled.index("PG 1"), compiled.index("PG", compiled.index("PG 1"))
    assert device.memory.variables["EM"] == 2 and len(device.saved.program) == end - start - 1
