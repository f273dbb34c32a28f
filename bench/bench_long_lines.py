"""Benchmark: a file with one megabyte-long statement line against the same program without it,
through `mcc check` and `mcc fmt --check`, per dialect, measured in the same run.

    .venv/bin/python bench/bench_long_lines.py [--size BYTES] [--repeat R]

Such a line is far past what any of the controllers reads; the driver reports it once (G007) and
leaves it out of the analysis, so the ratio long/plain should stay close to 1 in time and in peak
memory (before, the parser took 10-30 s and up to 930 MB on it). Each command runs as a user runs
it, in its own process; the time is the best of R runs, the memory the child's peak RSS.
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

PROGRAMS = {  # a short clean program and a statement to repeat into one long line
    "mcode": (".mxt", "PG 1\nLB G1\n  MA 1000\n  H\n  E\nPG\n", "MA 1000+"),
    "x150": (".x150", "1A10 1V5 1D4000 1G\n", "1G "),
    "arcus": (".prg", "X1000\nEND\n", "X1000 "),
}


def mcc() -> list[str]:
    exe = Path(sys.executable).parent / "mcc"
    return [str(exe)] if exe.exists() else [sys.executable, "-m", "mcc"]


def measure(args: list[str], repeat: int) -> tuple[float, float]:
    """(best seconds, peak RSS in MB) of running mcc with `args` in a child process."""
    best = float("inf")
    peak = 0.0
    for _ in range(repeat):
        code = ("import resource, subprocess, sys; subprocess.run(sys.argv[1:], capture_output=True); "
                "print(resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss)")
        start = time.perf_counter()
        out = subprocess.run([sys.executable, "-c", code] + mcc() + args, capture_output=True, text=True)
        best = min(best, time.perf_counter() - start)
        peak = max(peak, int(out.stdout.strip() or 0) / 1024)
    return best, peak


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--size", type=int, default=1_000_000, help="length of the long line in bytes")
    parser.add_argument("--repeat", type=int, default=3)
    options = parser.parse_args()
    with tempfile.TemporaryDirectory() as folder:
        print(f"{'dialect':8} {'command':12} {'plain s':>8} {'long s':>8} {'ratio':>6} {'plain MB':>9} "
              f"{'long MB':>8} {'ratio':>6}")
        for dialect, (ext, program, piece) in PROGRAMS.items():
            plain = os.path.join(folder, f"plain{ext}")
            long = os.path.join(folder, f"long{ext}")
            Path(plain).write_text(program + program)
            Path(long).write_text(program + piece * (options.size // len(piece)) + "\n" + program)
            for command in (["check"], ["fmt", "--check"]):
                t0, m0 = measure(command + [plain], options.repeat)
                t1, m1 = measure(command + [long], options.repeat)
                print(f"{dialect:8} {' '.join(command):12} {t0:8.2f} {t1:8.2f} {t1 / t0:6.2f} {m0:9.1f} "
                      f"{m1:8.1f} {m1 / m0:6.2f}")


if __name__ == "__main__":
    main()
