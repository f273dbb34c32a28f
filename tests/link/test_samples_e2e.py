"""Every sample of every dialect, downloaded, verified and uploaded through the `mcc` command to a
virtual device over a real socket (pyserial socket://)."""

from __future__ import annotations

import json

import pytest
from conftest import SAMPLES, run_mcc
from linkhelpers import mcc, serve  # noqa: F401  (serve: fixture)

from mcc.compiler import driver
from mcc.link.device.arcus import ArcusDevice
from mcc.link.device.mcode import MCodeBus, MCodeDevice
from mcc.link.device.x150 import X150Device
from mcc.link.protocol import normalize


def samples(dialect: str, ext: str) -> list[str]:
    return sorted(str(p) for p in (SAMPLES / dialect).glob(f"*{ext}"))


def program_lines(listing_text: str) -> list[str]:
    """The lines an MCode listing stores (between PG n and PG)."""
    stored, inside = [], False
    for line in listing_text.splitlines():
        word = line.split()[0].upper() if line.split() else ""
        if word == "PG":
            inside = len(line.split()) > 1
        elif inside:
            stored.append(normalize(line))
    return stored


PARTY = "party_mode_setup.mxt"  # addressed to drives a and b by their party names


@pytest.mark.parametrize("path", [p for p in samples("mcode", ".mxt") if not p.endswith(PARTY)],
                         ids=lambda p: p.rsplit("/", 1)[-1])
def test_mcode_sample_download_verify_upload(path, serve, tmp_path):
    device = MCodeDevice()
    server = serve(device)
    result = (run_mcc if path.endswith("pick_and_place.mxt") else mcc)("download", path, "--port", server.url, "--save", "--format", "json")
    assert result.returncode == 0, result.stdout + result.stderr
    report = json.loads(result.stdout)
    assert report["ok"] and report["verified"] and report["saved"] and not report["ran"]
    expected = program_lines(driver.compile_file(path).listing.text)
    assert [normalize(line) for line in device.saved.program] == expected
    out = tmp_path / "uploaded.mxt"
    up = mcc("upload", "--port", server.url, "--dialect", "mcode", "-o", str(out))
    assert up.returncode == 0, up.stderr
    checked = driver.check_file(str(out))
    assert not checked.has_errors, [d.message for d in checked.diagnostics]
    assert program_lines(out.read_text()) == expected


def test_mcode_party_sample_on_a_bus_of_two_drives(serve):
    path = str(SAMPLES / "mcode" / PARTY)
    bus = MCodeBus(("a", "b"))
    server = serve(bus)
    # Without --party the addressed lines are recognised and nothing is sent.
    refused = (run_mcc if path.endswith("pick_and_place.prg") else mcc)("download", path, "--port", server.url)
    assert refused.returncode == 1 and "--party" in refused.stderr and bus.received == 0
    held = mcc("download", path, "--port", server.url, "--party", "--address", "a", "--format", "json")
    assert held.returncode == 0, held.stdout + held.stderr
    assert json.loads(held.stdout)["held_back"] == ["aMR 51200", "bMR -51200"]  # moves wait for --run
    result = mcc("download", path, "--port", server.url, "--party", "--address", "a", "--run",
                     "--format", "json")
    assert result.returncode == 0, result.stdout + result.stderr
    assert json.loads(result.stdout)["verified"]
    # The global line reached both drives, each addressed line only its own drive.
    assert bus.drives["a"].memory.variables["VM"] == 500000 == bus.drives["b"].memory.variables["VM"]
    sent = [row["data"] for row in json.loads(result.stdout)["transcript"] if row["dir"] == "send"]
    assert "aMR 51200\n" in sent and "bMR -51200\n" in sent and "*VM=500000\n" in sent


@pytest.mark.parametrize("path", samples("x150", ".x150"), ids=lambda p: p.rsplit("/", 1)[-1])
def test_x150_sample_download_verify_upload(path, serve, tmp_path):
    device = X150Device()
    server = serve(device)
    result = (run_mcc if path.endswith("01_feed_punch_cell.x150") else mcc)("download", path, "--port", server.url, "--save", "--format", "json")
    assert result.returncode == 0, result.stdout + result.stderr
    report = json.loads(result.stdout)
    assert report["ok"] and report["verified"] and report["saved"]
    listing = driver.compile_file(path).listing.text
    defined = {(line.split("XD")[0], int(line.split("XD")[1])) for line in listing.splitlines()
               if "XD" in line and line.split("XD")[1].isdigit()}
    held = {(u.address, n) for u in device.units.values() for n in u.saved["sequences"]}
    assert defined and defined <= held
    out = tmp_path / "uploaded.x150"
    addresses = ",".join(sorted({a for a, _ in defined}))
    up = mcc("upload", "--port", server.url, "--dialect", "x150", "--devices", addresses, "-o", str(out))
    assert up.returncode == 0, up.stderr
    checked = driver.check_file(str(out))
    assert not any(d.severity.value == "error" for d in checked.diagnostics), [d.message for d in checked.diagnostics]
    text = out.read_text()
    for address, number in defined:
        assert f"{address}XD{number}\n" in text


@pytest.mark.parametrize("path", samples("arcus", ".prg"), ids=lambda p: p.rsplit("/", 1)[-1])
def test_arcus_sample_refused_then_image_cloned(path, serve, tmp_path):
    # The .prg itself cannot be downloaded (the compiled-line format is the vendor's): refused, nothing sent.
    blank = ArcusDevice()
    server = serve(blank)
    refused = (run_mcc if path.endswith("pick_and_place.prg") else mcc)("download", path, "--port", server.url)
    assert refused.returncode == 1
    # ... and the message says why (the undocumented compiled-line format, with the manual's lines)
    # and what to do instead (compile and download with the vendor's Windows software).
    message = " ".join(refused.stderr.split())
    assert "L1642-L1645" in message and "Arcus Windows software" in message and "Compile" in message
    assert "nothing was sent" in message
    assert blank.lines == {} and blank.received == 0
    # A controller that holds the program (put there by the vendor's software): upload it as an image ...
    source = ArcusDevice()
    source.load_program(open(path).read(), path)
    source.variables[5] = 42
    origin = serve(source)
    image, variables = tmp_path / "machine.sa", tmp_path / "vars.prg"
    up = mcc("upload", "--port", origin.url, "--dialect", "arcus", "--image", str(image), "-o", str(variables))
    assert up.returncode == 0, up.stderr
    assert "V5=42" in variables.read_text()
    assert not driver.check_file(str(variables)).has_errors
    # ... and put it on another controller, verified line by line, then run it.
    result = mcc("download", str(image), "--port", server.url, "--run", "--format", "json")
    assert result.returncode == 0, result.stdout + result.stderr
    report = json.loads(result.stdout)
    assert report["ok"] and report["verified"] and report["ran"]
    assert blank.lines == source.lines
    assert report["status"]["SASTAT"].split()[0] == blank.state
