"""Virtual time on the virtual devices (docs/LINK.md, "Virtual time"; decision 0017): time passes
between the host's commands (each command's characters at the baud rate and the product's
execution time, and what the host waits), moves and programs go on across commands, and a query
reads the state at the device's clock: during a move an intermediate position, after the move's
time its end."""

from __future__ import annotations

import socket
import time

import pytest
from linkhelpers import serve  # noqa: F401  (serve: fixture)

from mcc.link.device.arcus import ArcusDevice
from mcc.link.device.machine import timing
from mcc.link.device.mcode import MCodeDevice
from mcc.link.device.server import DeviceServer
from mcc.link.device.x150 import X150Device


def answer(device, command: str) -> str:
    """The device's answer to one command without its echo and prompt (MCode, X150) or framing
    (Arcus: `@00` ... CR)."""
    if isinstance(device, ArcusDevice):
        return device.feed(f"@00{command}\r".encode()).decode().rstrip("\r")
    lines = device.feed(f"{command}\r".encode()).decode().replace("\r\n", "\r").split("\r")
    return "\r".join(line for line in lines[1:] if line not in (">", ""))


def test_mcode_pr_mp_reads_1_while_the_move_runs_and_0_after_it():
    """lexium-mcode.txt L4220: `MA 5120000` then `PR MP` prints 1, "the MP status while axis is
    moving"; the drive answers each command after its execution time, 1-5 ms (L6821). With the
    factory VI 1000, VM 768000, A = D 1,000,000 (L662-L690) the move takes 0.767 s to reach VM over
    294,912 steps each way and cruises (5,120,000 - 589,823) / 768,000 = 5.899 s: 7.433 s in all."""
    device = MCodeDevice()
    assert answer(device, "MA 5120000") == ""
    assert (answer(device, "PR MP"), answer(device, "PR MV")) == ("1", "1")   # L4220, MV L4424
    first = int(answer(device, "PR P"))
    assert 0 < first < 5_120_000 and 0 < int(answer(device, "PR V")) <= 768_000
    second = int(answer(device, "PR P"))
    assert first < second < 5_120_000   # it moves on between two queries
    device.elapse(7.5)                   # the host waits for the move's time
    assert (answer(device, "PR MP"), answer(device, "PR MV"), answer(device, "PR P")) == ("0", "0", "5120000")


def test_mcode_each_command_costs_its_characters_and_the_execution_time():
    """A command's characters cross the line at the profile's baud rate (9600 bps, 8N1: 10 bits a
    character, lexium-mcode.txt L1586-L1590), the drive executes it in its command execution time
    (L6821; the profile's `[device] command_time`, 5 ms) and the reply crosses back."""
    device = MCodeDevice()
    command_time, char_time = timing(device.sim.profile)
    assert (command_time, char_time) == (0.005, 10 / 9600)
    reply = device.feed(b"PR VI\r")   # echo, CR LF, 1000, CR LF, prompt
    assert device.sim.clock == pytest.approx(len(b"PR VI\r") * char_time + command_time + len(reply) * char_time)


def test_mcode_a_program_runs_on_after_ex_is_answered():
    """BY is 1 while a program executes (lexium-mcode.txt L1828): EX is answered at once and the
    program's move (H waits for it, L3037-L3067) goes on; its PR output reaches the host as it runs
    (L4895), before the next answer."""
    device = MCodeDevice()
    for line in ["PG 1", "LB GO", "MR 100000", "H", "PR P", "E", "PG"]:
        assert device.feed(f"{line}\r".encode()).endswith(b">")
    assert answer(device, "EX GO") == ""
    assert answer(device, "PR BY") == "1" and 0 < int(answer(device, "PR P")) < 100_000
    device.elapse(2.0)
    reply = device.feed(b"PR BY\r").decode()
    assert reply == "100000\r\nPR BY\r\n0\r\n>"   # the program's print came while the host waited


def test_x150_r_reads_busy_during_the_move_and_pr_waits_for_it():
    """parker-x150.md L3224-L3240: `R` (Immediate) answers `*B`, "busy performing a move", while
    the move runs, `*R` after it; `PR` is Buffered (L3123-L3145), so it is executed once the move
    in the buffer before it has ended (buffered commands run "in sequential order", L177) and
    reports the end position. A10 = 40,000 steps/s², V2 = 8,000 steps/s (4,000 steps/rev, L195,
    L4540): 0.2 s ramps over 800 steps each, 18,400 steps at 8,000 steps/s: 2.7 s in all."""
    device = X150Device()
    for command in ["1MPI", "1A10", "1V2", "1D20000", "1G"]:
        assert answer(device, command) == ""
    started = device.sim.clock
    assert answer(device, "1R") == "*B"
    assert 0 < device.sim.position("1") < 20_000        # on its way
    assert answer(device, "1PR") == "*+20000"            # waits in the buffer for the move's end
    assert device.sim.clock >= started + 2.7 - 0.05
    assert answer(device, "1R") == "*R"


def test_x150_a_sequence_runs_on_after_xr_is_answered():
    """A sequence started by `XR` (parker-x150.md L1415, "execute sequence 1") runs on after the command is answered: `R` reads
    `*B` while it moves, and after the sequence's time its end position and `*R`."""
    device = X150Device()
    for command in ["1XD1", "1MPI", "1A10", "1V2", "1D20000", "1G", "1XT"]:
        device.feed(f"{command}\r".encode())
    assert answer(device, "1XR1") == ""
    assert answer(device, "1R") == "*B" and 0 <= device.sim.position("1") < 20_000
    device.elapse(3.0)
    assert (answer(device, "1R"), answer(device, "1PR")) == ("*R", "*+20000")


def test_arcus_px_mst_and_ps_read_the_move_as_it_runs():
    """arcus-pmx-4ex-sa.txt L436-L445: from LSPD 100 to HSPD 1000 pulses/s in ACC 300 ms over
    (100 + 1000) / 2 x 0.3 = 165 pulses each way, cruise (5000 - 330) / 1000 = 4.67 s: 5.27 s.
    PX reads the position (L1581-L1614), PS the speed (L716, L1611), MST bit 0 accelerating, bit 2
    constant speed (L720-L731); after the move's time PX is 5000 and MST 0."""
    device = ArcusDevice()
    assert answer(device, "X5000") == "OK"
    assert answer(device, "MST").split(":")[0] == "1"          # accelerating
    assert 0 < int(answer(device, "PX")) < 5000
    device.elapse(1.0)
    assert answer(device, "MST").split(":")[0] == "4"          # constant speed
    assert answer(device, "PS").split(":")[0] == "1000"
    middle = int(answer(device, "PX"))
    assert 900 < middle < 1200
    device.elapse(5.0)
    assert (answer(device, "PX"), answer(device, "MST").split(":")[0], answer(device, "PS")) == ("5000", "0", "0:0:0:0")


def test_arcus_a_standalone_program_runs_on_after_sr_1():
    """SR=1 starts the standalone program (L1626-L1632); SASTAT reads 1 while it runs and 0 once it
    has ended; its variables are what the host reads (V[n], L1703)."""
    device = ArcusDevice()
    device.load_program("V1=1\nX2000\nWAITX\nV1=2\nEND\n")
    assert answer(device, "SR=1") == "OK"
    assert (answer(device, "SASTAT"), answer(device, "V1")) == ("1", "1")
    device.elapse(5.0)
    assert (answer(device, "SASTAT"), answer(device, "V1"), answer(device, "PX")) == ("0", "2", "2000")


def exchange(sock: socket.socket, command: bytes) -> bytes:
    sock.sendall(command)
    data = b""
    while not data.endswith(b">"):
        data += sock.recv(4096)
    return data


def test_the_server_lets_the_hosts_silence_pass_as_time():
    """Over TCP the host's silence is time too (`--time-scale`, 50 virtual seconds per second
    here): a host that waits 0.5 s after `MA 5120000` (25 virtual seconds, past the move's 7.433 s,
    lexium-mcode.txt L662-L690) reads the end position; one that asks at once reads MP 1 (L4220)."""
    device = MCodeDevice()
    with DeviceServer(device, time_scale=50.0) as server:
        with socket.create_connection((server.host, server.port), timeout=10) as sock:
            assert exchange(sock, b"MA 5120000\r").endswith(b">")
            assert exchange(sock, b"PR MP\r") == b"PR MP\r\n1\r\n>" or device.sim.clock > 7.4
            time.sleep(0.5)
            assert exchange(sock, b"PR P\r") == b"PR P\r\n5120000\r\n>"


def test_mcc_send_reads_its_reply_after_what_a_running_program_printed(serve):
    """A drive sends a running program's PR output as it runs (lexium-mcode.txt L4895): a host's
    next reply comes after those lines, and mcc's link reads its own reply past them."""
    from linkhelpers import mcc

    device = MCodeDevice()
    for line in ["PG 1", "LB GO", "MR 100000", "H", "PR P", "E", "PG"]:
        device.feed(f"{line}\r".encode())
    server = serve(device)
    assert mcc("send", "--port", server.url, "--dialect", "mcode", "EX GO").returncode == 0
    device.elapse(2.0)   # the program's move ends and it prints while the host is silent
    result = mcc("send", "--port", server.url, "--dialect", "mcode", "PR BY", "PR P")
    assert result.returncode == 0, result.stdout + result.stderr
    assert result.stdout.splitlines() == ["PR BY: 0", "PR P: 100000"]


def test_arcus_a_paused_program_does_not_go_on_until_it_is_continued():
    """SR=2 pauses the standalone program and SR=3 continues it (arcus-pmx-4ex-sa.txt L1626-L1632;
    SASTAT 2 while paused): paused longer than its DELAY, it has not gone on past it; continued,
    it does."""
    device = ArcusDevice()
    device.load_program("V1=1\nDELAY=500\nV1=2\nEND\n")
    assert answer(device, "SR=1") == "OK" and answer(device, "SR=2") == "OK"
    device.elapse(2.0)
    assert (answer(device, "SASTAT"), answer(device, "V1")) == ("2", "1")
    assert answer(device, "SR=3") == "OK"
    device.elapse(1.0)
    assert (answer(device, "SASTAT"), answer(device, "V1")) == ("0", "2")


def test_a_variable_the_host_sets_is_what_the_running_program_reads():
    """The host writes a standalone variable while the program runs (V[n]=value, arcus-pmx-4ex-sa.txt
    L1705): the program, waiting for it in a loop, reads the new value and ends."""
    device = ArcusDevice()
    device.load_program("V1=0\nWHILE V1=0\nDELAY=10\nENDWHILE\nV2=7\nEND\n")
    assert answer(device, "SR=1") == "OK"
    device.elapse(1.0)
    assert answer(device, "SASTAT") == "1"
    assert answer(device, "V1=1") == "OK"
    device.elapse(0.1)
    assert (answer(device, "SASTAT"), answer(device, "V2")) == ("0", "7")


def test_mcode_a_register_the_host_sets_is_what_the_running_program_reads():
    """An immediate assignment while a program runs (R1=1; R1-R4, the user
    registers, lexium-mcode.txt L5063) changes the register the program reads: it leaves its
    waiting loop (BR, L805)."""
    device = MCodeDevice()
    for line in ["PG 1", "LB GO", "R1=0", "LB W1", "H 10", "BR W1, R1=0", "R2=7", "E", "PG"]:
        assert device.feed(f"{line}\r".encode()).endswith(b">")
    assert answer(device, "EX GO") == ""
    device.elapse(1.0)
    assert answer(device, "PR BY") == "1"
    assert answer(device, "R1=1") == ""
    device.elapse(0.1)
    assert (answer(device, "PR BY"), answer(device, "PR R2")) == ("0", "7")


def test_mcode_a_slew_runs_on_with_the_clock_until_sl_0():
    """SL slews at the given speed until another SL changes it (lexium-mcode.txt L736-L739): from
    VI 1000 at A 1,000,000 steps/s² (L662-L690) it reaches 2000 steps/s within a millisecond and
    then covers 2000 steps a second; SL 0 ramps it down and it stays where it stopped."""
    device = MCodeDevice()
    assert answer(device, "SL 2000") == ""
    device.elapse(1.0)
    first, at = int(answer(device, "PR P")), device.sim.clock
    assert 1950 < first < 2150 and answer(device, "PR V") == "2000" and answer(device, "PR MP") == "0"
    device.elapse(1.0)
    second = int(answer(device, "PR P"))
    assert abs(second - first - 2000 * (device.sim.clock - at)) <= 2   # the queries' own time counts too
    assert answer(device, "SL 0") == ""
    device.elapse(0.1)
    stopped = answer(device, "PR P")
    device.elapse(1.0)
    assert (answer(device, "PR MV"), answer(device, "PR P")) == ("0", stopped)
