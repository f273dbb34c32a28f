"""Benchmark: `mcc check` on a 10,000-line MCode program against a bare Lark parse, and start-up.

Targets: the full check takes at most 2x a bare Lark parse of the same file (issue 12; 3x in
issue 2): the same grammar, LALR, building Lark's own tree, no callbacks; `mcc --version` takes
at most 5x `python -c pass`. Ratios are measured in one run, with the best of several repeats of each side,
so a noisy shared machine affects both sides alike.

Run: .venv/bin/python bench/bench_mcode.py [--lines N] [--repeat R]
"""

from __future__ import annotations

import argparse
import os
import statistics
import subprocess
import sys
import time
from pathlib import Path

from mcc.compiler import driver
from mcc.compiler.mcode import parser as mcode_parser

BODY = [
    "  MA {n}",
    "  H",
    "  R1=R1+{k}",
    "  CL K1,I1=1",
    "  PR \"Position: \",P",
    "  BR {lbl},R1<{n}",
    "  O1={b}",
    "  H 10",
    "  VM={v}",
    "  IC Q1",
]


LABELS = [f"{a}{b}" for a in "GHJNWXYZAB" for b in "0123456789"]  # 100 labels: well under the 192-name table


def program(lines: int) -> str:
    """A realistic program: setup, then blocks of motion, I/O, math and branches (every tenth labelled)."""
    out = ["` generated benchmark program", "VA Q1", "VI=1000", "VM=768000", "PG 1"]
    g = 0
    while len(out) < lines - 6:
        labelled = g % 10 == 0 and g // 10 < len(LABELS)
        out.append(f"LB {LABELS[g // 10]}" if labelled else f"  ` block {g}")
        for i, template in enumerate(BODY):
            out.append(template.format(n=1000 + g, k=i, b=g % 2, v=500000 + g,
                                       lbl=LABELS[min(g // 10, len(LABELS) - 1)]))
        g += 1
    out += ["  E", "LB K1", "  MR 100", "  H", "  RT", "PG", "S"]
    out = out[:lines - 7] + ["  E", "LB K1", "  MR 100", "  H", "  RT", "PG", "S"] if len(out) > lines else out
    return "\n".join(out[:lines]) + "\n"


def best(fn, repeat: int) -> float:
    times = []
    for _ in range(repeat):
        start = time.perf_counter()
        fn()
        times.append(time.perf_counter() - start)
    return min(times)


def startup(repeat: int) -> tuple[float, float]:
    exe = Path(sys.executable).parent / "mcc"
    env = {**os.environ, "NO_COLOR": "1"}

    def run(cmd):
        return best(lambda: subprocess.run(cmd, capture_output=True, env=env, check=True), repeat)

    return run([str(exe), "--version"]), run([sys.executable, "-c", "pass"])


def main() -> int:
    ap = argparse.ArgumentParser()
    ap.add_argument("--lines", type=int, default=10_000)
    ap.add_argument("--repeat", type=int, default=5)
    args = ap.parse_args()
    text = program(args.lines)
    bare = mcode_parser.bare_parser()
    driver.check_file("warmup.mxt", "mcode", text=text)  # catalogs, grammar and code registry loaded once

    t_bare = best(lambda: bare.parse(text), args.repeat)
    result = driver.check_file("bench.mxt", "mcode", text=text)
    errors = [d for d in result.diagnostics if d.severity.value == "error"]
    t_check = best(lambda: driver.check_file("bench.mxt", "mcode", text=text), args.repeat)
    t_compile = best(lambda: driver.compile_file("bench.mxt", "mcode", text=text), args.repeat)
    t_version, t_python = startup(args.repeat * 2)

    lines = text.count("\n")
    print(f"program: {lines} lines, {len(text)} bytes, {len(result.diagnostics)} diagnostics ({len(errors)} errors)")
    print(f"bare Lark parse : {t_bare * 1000:8.1f} ms")
    print(f"mcc check       : {t_check * 1000:8.1f} ms  ({lines / t_check:,.0f} lines/s)")
    print(f"mcc compile     : {t_compile * 1000:8.1f} ms  ({lines / t_compile:,.0f} lines/s)")
    ratio = t_check / t_bare
    print(f"check / bare parse ratio : {ratio:.2f}  (target <= 2.0, issue 12) {'OK' if ratio <= 2 else 'OVER'}")
    startup_ratio = t_version / t_python
    print(f"mcc --version {t_version * 1000:.1f} ms / python -c pass {t_python * 1000:.1f} ms = "
          f"{startup_ratio:.2f}  (target <= 5.0) {'OK' if startup_ratio <= 5 else 'OVER'}")
    return 0 if not errors else 1


if __name__ == "__main__":
    sys.exit(main())
