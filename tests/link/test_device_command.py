"""`mcc device` as a user starts it: a separate process on a TCP port, driven by `mcc download`,
`mcc send` and `mcc upload` in other processes."""

from __future__ import annotations

import re
import subprocess
import sys
import time
from pathlib import Path

from conftest import SAMPLES, run_mcc

from mcc.sim.files import simulate_file


def start_device(*args: str) -> tuple[subprocess.Popen, str]:
    exe = Path(sys.executable).parent / "mcc"
    proc = subprocess.Popen([str(exe), "device", *args, "--listen", "127.0.0.1:0"], stderr=subprocess.PIPE,
                            text=True)
    line = proc.stderr.readline()
    match = re.search(r"(socket://127\.0\.0\.1:\d+)", line)
    assert match, line
    return proc, match.group(1)


def test_virtual_arcus_device_process_runs_its_program():
    # The program runs on the simulator's machine, on the device's clock: it runs on after SR=1
    # is answered (SASTAT 1, arcus-pmx-4ex-sa.txt L1626) and ends with the variables `mcc sim`
    # computes for it. The device runs 50 virtual seconds per second the host is silent; the host
    # polls SASTAT until the program has stopped.
    sample = str(SAMPLES / "arcus" / "drill_grid_variables.prg")
    predicted = simulate_file(sample).trace
    assert predicted.stopped == "end" and predicted.time > 1.0
    proc, url = start_device("--dialect", "arcus", "--program", sample, "--time-scale", "50")
    try:
        result = run_mcc("send", "--port", url, "--dialect", "arcus", "SASTAT", "SR=1", "SASTAT")
        assert result.returncode == 0, result.stdout + result.stderr
        assert result.stdout.splitlines() == ["SASTAT: 0  (stopped)", "SR=1: OK", "SASTAT: 1  (running)"]
        for _poll in range(100):
            time.sleep(0.05)
            state = run_mcc("send", "--port", url, "--dialect", "arcus", "SASTAT").stdout.strip()
            if state == "SASTAT: 0  (stopped)":
                break
        result = run_mcc("send", "--port", url, "--dialect", "arcus", "SASTAT", "V4", "V14")
        assert result.stdout.splitlines() == ["SASTAT: 0  (stopped)", f"V4: {predicted.variables['V4']}",
                                              f"V14: {predicted.variables['V14']}"]
    finally:
        proc.terminate()
        proc.wait(10)


def test_virtual_mcode_device_process_keeps_state_between_connections(tmp_path):
    proc, url = start_device("--dialect", "mcode", "--fault", "")
    try:
        sample = str(SAMPLES / "mcode" / "trip_on_input.mxt")
        assert run_mcc("download", sample, "--port", url, "--save").returncode == 0
        out = tmp_path / "back.mxt"
        assert run_mcc("upload", "--port", url, "--dialect", "mcode", "-o", str(out)).returncode == 0
        assert run_mcc("check", str(out)).returncode == 0
    finally:
        proc.terminate()
        proc.wait(10)


def test_bad_fault_spec_is_a_usage_error():
    result = run_mcc("device", "--dialect", "x150", "--fault", "explode=3")
    assert result.returncode == 2 and "drop_reply=N" in result.stderr


def test_terminal_reads_commands_and_decodes_replies(tmp_path):
    proc, url = start_device("--dialect", "mcode")
    try:
        result = run_mcc("terminal", "--port", url, "--dialect", "mcode",
                         input="PR VM\nFOO=1\n:explain 20\n:status\n:quit\n")
        assert result.returncode == 0, result.stderr
        out = result.stdout
        assert "connected: LMDCM 6.002" in out
        assert "error 20: Tried to SET Unknown Variable/Flag (L8464)" in out
        assert "BY 0, ER 0" in out
    finally:
        proc.terminate()
        proc.wait(10)


def test_run_limit_cuts_a_long_move_in_virtual_time():
    # A program with a 5 s move on a device that runs a program for at most 1 virtual second: the
    # program is held where its move had got to after 1 s (about 2000 steps at 2000 steps/s),
    # reported busy (BY, lexium-mcode.txt L1828) and moving (MV, L4424). The host waits 2 s of
    # virtual time (0.2 s at --time-scale 10) before it asks.
    proc, url = start_device("--dialect", "mcode", "--run-limit", "1", "--time-scale", "10")
    try:
        program = ["VM=2000", "PG 1", "LB GO", "MR 10000", "H", "E", "PG", "EX GO"]
        result = run_mcc("send", "--port", url, "--dialect", "mcode", *program)
        assert result.returncode == 0, result.stdout + result.stderr
        time.sleep(0.2)
        result = run_mcc("send", "--port", url, "--dialect", "mcode", "PR P", "PR BY", "PR MV")
        lines = result.stdout.splitlines()
        position = int(lines[0].split(": ")[1])
        assert 1500 < position < 2100 and lines[1:] == ["PR BY: 1", "PR MV: 1"], lines
    finally:
        proc.terminate()
        proc.wait(10)
    bad = run_mcc("device", "--dialect", "mcode", "--run-limit", "0")
    assert bad.returncode == 2 and "--run-limit" in bad.stderr
