"""Benchmark: download a generated MCode program of N stored lines to the virtual device over a
TCP socket, and compare with the bare round trips of the same exchange.

Run:  .venv/bin/python bench/bench_link.py [--lines N] [--repeat R]

What is compared, in one run against the same virtual device on the loopback address:
- "bare round trips": for every command the download sends, write the framed bytes and read until
  the prompt, with no planning, checks or read-back (the floor set by the socket and the device);
- "mcc download": the whole download as `mcc download --save` runs it: the plan from the listing,
  every reply decoded and checked, the read-back (`L`) compared line by line, then `S`.
The ratio is download time / bare time (best of R runs each). A real drive at 9600 bps adds about
1 ms per character each way; this measures mcc's own cost on top of the line.

Then what running on the simulator's machine costs the virtual device (link/device/machine.py):
- "EX 1": running the downloaded program on the device (compile what it stores, simulate),
  against `mcc sim` of the same listing as a file (check, lower, simulate) in this process;
- "immediate MR 100": an immediate command that runs on the machine (compiled and simulated
  before the device answers), against a query (`PR VR`) that does not, per round trip.
"""

from __future__ import annotations

import argparse
import time

from mcc.backends.listing import ListingLine
from mcc.link.device.mcode import MCodeDevice
from mcc.link.device.server import DeviceServer
from mcc.link.download import download
from mcc.link.mcode import Protocol
from mcc.link.ports import Channel, open_port
from mcc.link.settings import LinkSettings
from mcc.sim.files import simulate_file


def listing(lines: int) -> list[ListingLine]:
    body = ["VA QA=0", "PG 1", "LB GA"]
    body += [("QA=QA+1", "MR 100", "H", "PR \"N=\",QA")[i % 4] for i in range(lines - 2)]
    return [ListingLine(text) for text in body + ["E", "PG", "S"]]


def best(func, repeat: int) -> float:
    times = []
    for _ in range(repeat):
        start = time.perf_counter()
        func()
        times.append(time.perf_counter() - start)
    return min(times)


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--lines", type=int, default=1000)
    parser.add_argument("--repeat", type=int, default=3)
    args = parser.parse_args()
    settings = LinkSettings(timeout=5.0)
    with DeviceServer(MCodeDevice(program_lines=args.lines + 10)) as server:
        channel = Channel(open_port(server.url, settings), settings)
        proto = Protocol(channel, settings)
        steps = proto.plan(listing(args.lines))
        commands = [s.command for s in steps if s.kind != "run"] + ["PR VR", "L", "S"]

        def bare() -> None:
            for command in commands:
                channel.send(proto.frame(command))
                channel.read_until(lambda b: len(b) if b[-1:] in (b">", b"?") and len(b) > len(command) else 0)

        def full() -> None:
            report = download(proto, steps, save=True, run=False)
            assert report.ok, report.message

        t_bare, t_full = best(bare, args.repeat), best(full, args.repeat)

        def ask(command: str, times: int):
            def go() -> None:
                for _ in range(times):
                    assert proto.transact(command).ok
            return go

        t_run = best(ask("EX 1", 1), args.repeat)
        text = "\n".join(line.text for line in listing(args.lines)) + "\n"
        t_sim = best(lambda: simulate_file("bench.mxt", "mcode", text=text), args.repeat)
        n = 100
        t_move, t_query = best(ask("MR 100", n), args.repeat), best(ask("PR VR", n), args.repeat)
        channel.close()
    print(f"stored lines        {args.lines}")
    print(f"commands            {len(commands)}")
    print(f"bare round trips    {t_bare * 1000:8.1f} ms  ({len(commands) / t_bare:8.0f} commands/s)")
    print(f"mcc download        {t_full * 1000:8.1f} ms  ({len(commands) / t_full:8.0f} commands/s)")
    print(f"ratio               {t_full / t_bare:8.2f}x")
    print(f"EX 1 on the device  {t_run * 1000:8.1f} ms")
    print(f"mcc sim (in process){t_sim * 1000:8.1f} ms  (ratio {t_run / t_sim:.2f}x)")
    print(f"immediate MR 100    {t_move / n * 1000:8.2f} ms per command")
    print(f"query PR VR         {t_query / n * 1000:8.2f} ms per command  (ratio {t_move / t_query:.1f}x)")


if __name__ == "__main__":
    main()
