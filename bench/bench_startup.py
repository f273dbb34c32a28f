"""Benchmark: what one small `mcc` process costs, against `python -c pass` in the same interpreter.

A pre-commit user runs `mcc check` on a few files per commit: the cost that matters is the whole
process (interpreter start, imports, building the parser, reading the catalogs), not the check
itself. This script runs each command many times as separate processes and reports the best CPU
time (user + system, from the children's resource usage: other processes on a shared machine do
not count) and its ratio to `python -c pass`. Issue 26's target: `mcc check` of a 30-line
program and `mcc --help` at most 3x `python -c pass`. The rows in parentheses are floors under a
`mcc check`: importing click (the command line), and importing click and the modules a check of
each dialect loads before it reads the file (docs/PERFORMANCE.md, "Issue 26").

`--python` (repeatable) measures other interpreters too, each with its own `python -c pass`, the
processes of the interpreters run alternately: two virtual environments, one with the version
before a change and one after, or an editable install (`pip install -e .`, whose import hook
every process of that environment loads at start-up) and a plain one (`pip install .`, what users
run), compare in one run on the same machine.

Bytecode is written as it is on a user's machine (PYTHONDONTWRITEBYTECODE is removed from the
children's environment), and the first run of each command, which writes the caches (bytecode,
the Lark parser tables), is not counted.

Run: .venv/bin/python bench/bench_startup.py [--runs N] [--python OTHER/bin/python ...]
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


def best(commands: list[list[str]], env: dict[str, str], runs: int) -> list[float]:
    """The best CPU time of each command, the commands run alternately (the first run of each,
    which writes the caches, not counted)."""
    for command in commands:
        cpu_of(command, env)
    times = [float("inf")] * len(commands)
    for _ in range(runs):
        for i, command in enumerate(commands):
            times[i] = min(times[i], cpu_of(command, env))
    return times


def check_imports(dialect: str) -> str:
    """What a check of `dialect` imports before it reads the file: the command line, the driver,
    the frontend (and with it the generated parser)."""
    return f"import mcc.cli.commands, mcc.compiler.driver, mcc.compiler.{dialect}.frontend"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=15)
    parser.add_argument("--python", action="append", default=[],
                        help="another interpreter to measure (repeatable; default: only this one)")
    options = parser.parse_args()
    env = {k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"}
    pythons = [sys.executable] + options.python
    bases = best([[python, "-c", "pass"] for python in pythons], env, options.runs)
    print(f"CPU time, best of {options.runs} processes, against python -c pass of the same interpreter")
    for number, (python, base) in enumerate(zip(pythons, bases), 1):
        print(f"  [{number}] {python}: python -c pass {base * 1000:.0f} ms")
    print(f"  {'command':44}" + "".join(f" {f'[{n}] ms':>7} {'x pass':>7}" for n in range(1, len(pythons) + 1)))
    rows: list[tuple[str, list[str]]] = [("(python -c 'import click')", ["-c", "import click"])]
    rows += [(f"(imports of a check: {dialect})", ["-c", check_imports(dialect)]) for dialect in SMALL]
    rows.append(("mcc --help", ["-m", "mcc", "--help"]))
    with tempfile.TemporaryDirectory() as tmp:
        for dialect, text in SMALL.items():
            path = Path(tmp) / f"small{EXTENSION[dialect]}"
            path.write_text(text, encoding="utf-8")
            rows.append((f"mcc check ({dialect}, {text.count(chr(10))} lines)", ["-m", "mcc", "check", str(path)]))
        for name, arguments in rows:
            times = best([[python] + arguments for python in pythons], env, options.runs)
            print(f"  {name:44}" + "".join(f" {t * 1000:>7.0f} {t / b:>6.1f}x" for t, b in zip(times, bases)))


if __name__ == "__main__":
    main()
