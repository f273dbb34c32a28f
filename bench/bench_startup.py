"""Benchmark: what one small `mcc` process costs, against `python -c pass` in the same interpreter.

A pre-commit user runs `mcc check` on a few files per commit: the cost that matters is the whole
process (interpreter start, imports, building the parser, reading the catalogs), not the check
itself. This script runs each command many times as separate processes and reports the best CPU
time (user + system, from the children's resource usage: other processes on a shared machine do
not count) and its ratio to `python -c pass`. Issue 26's target: `mcc check` of a 30-line
program and `mcc --help` at most 3x `python -c pass`. The first two rows are the floor under any
`mcc check`: importing the two libraries it is built on (docs/PERFORMANCE.md, "Issue 26").

Bytecode is written as it is on a user's machine (PYTHONDONTWRITEBYTECODE is removed from the
children's environment), and the first run of each command, which writes the caches (bytecode,
the Lark parser tables), is not counted.

Run: .venv/bin/python bench/bench_startup.py [--runs N]
"""

from __future__ import annotations

import argparse
import os
import resource
import subprocess
import sys
import tempfile
from pathlib import Path

SMALL = {
    "mcode": "` a small program\nVM=20000\nA=100000\nD=100000\nPG 100\nLB AA\n  MR 2000\n  H\n  O1=1\n"
             "  H 100\n  O1=0\n  BR AA, I1=0\nE\nPG\n",
    "x150": "; a small program\n1V5\n1A10\n1D4000\nXD1\n1L5\n1G\n1T0.5\n1N\nXT\n1XR1\n",
    "arcus": "; a small program\nHSPD=20000\nLSPD=1000\nACC=300\nABS\nV1=0\nWHILE V1<5\nX1000\nWAITX\n"
             "X0\nWAITX\nV1=V1+1\nENDWHILE\nEND\n",
}
EXTENSION = {"mcode": ".mxt", "x150": ".x150", "arcus": ".prg"}


def cpu_of(command: list[str], env: dict[str, str]) -> float:
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    subprocess.run(command, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, check=False)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def best(command: list[str], env: dict[str, str], runs: int) -> float:
    cpu_of(command, env)  # writes the caches
    return min(cpu_of(command, env) for _ in range(runs))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=15)
    options = parser.parse_args()
    env = {k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"}
    python = sys.executable
    mcc = [python, "-m", "mcc"]
    base = best([python, "-c", "pass"], env, options.runs)
    print(f"CPU time, best of {options.runs} processes (python -c pass: {base * 1000:.0f} ms)")
    print(f"  {'command':34} {'ms':>6} {'x pass':>7}")
    # the floor of any mcc command that parses its arguments with click and a program with Lark
    rows = [("(python -c 'import click')", [python, "-c", "import click"]),
            ("(python -c 'import click, lark')", [python, "-c", "import click, lark"]),
            ("mcc --help", mcc + ["--help"])]
    with tempfile.TemporaryDirectory() as tmp:
        for dialect, text in SMALL.items():
            path = Path(tmp) / f"small{EXTENSION[dialect]}"
            path.write_text(text, encoding="utf-8")
            rows.append((f"mcc check ({dialect}, {text.count(chr(10))} lines)", mcc + ["check", str(path)]))
        for name, command in rows:
            seconds = best(command, env, options.runs)
            print(f"  {name:34} {seconds * 1000:>6.0f} {seconds / base:>6.1f}x")


if __name__ == "__main__":
    main()
