"""Benchmark of validation by default (issue 23): the time of `mcc compile` validated against the
time of `mcc compile --no-verify`, as ratios measured in one run.

    .venv/bin/python bench/bench_verify.py [--repeat R] [--size N] [--targets]

Programs: the project's samples (every dialect) and a generated 3,000-statement Arcus drawing
(bench_opt.drawing_program: travel moves, contours, pen subroutines) and 1,500-statement machine
program. Each is compiled as `mcc compile` does by default (-O1, its own dialect), and with
`--targets` also to each other dialect (cross-dialect output is validated in every case). A
validated compile simulates the source and the written program on the scenarios generated from
the source (docs/SIMULATOR.md, "Verification"); a compile whose passes changed nothing, or whose
output lowers to the source's IR, simulates nothing.

Target: a validated compile costs at most 1.5x an unvalidated one (docs/OPTIMIZER.md). Each time is
the best of R rounds. Exit status 1 when a program misses it.
"""

from __future__ import annotations

import argparse
import gc
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from bench_opt import drawing_program, machine_program, statements  # noqa: E402

from mcc.compiler import dialects, driver  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent
TARGET = 1.5
DIALECTS = ("mcode", "x150", "arcus")


def best(func, rounds: int) -> tuple[float, object]:
    times, result = [], None
    for _ in range(rounds):
        gc.collect()
        start = time.perf_counter()
        result = func()
        times.append(time.perf_counter() - start)
    return min(times), result


def measure(name: str, text: str, dialect: str, target: str, level: str, repeat: int) -> tuple[float, float, str]:
    """(unvalidated seconds, validated seconds, what the validated compile said)."""
    def compile_(verify: bool):
        return driver.compile_file(name, dialect, target, text=text, opt_level=level, verify=verify)

    compile_(True)  # warm-up: imports, grammars, caches
    once, _ = best(lambda: compile_(False), 1)
    rounds = max(repeat, min(30, int(0.3 / max(once, 1e-4))))
    plain, result = best(lambda: compile_(False), rounds)
    checked, result = best(lambda: compile_(True), rounds)
    errors = [d.code for d in result.diagnostics if d.severity.value == "error"]
    simulated = result.optimization is not None and driver.needs_validation(result, result.optimization)
    state = ",".join(errors) if errors else ("validated" if simulated else "as written")
    return plain, checked, state


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--size", type=int, default=3000, help="statements of the generated drawing")
    parser.add_argument("--targets", action="store_true", help="also compile each program to the other dialects")
    args = parser.parse_args(argv)

    programs = []
    for dialect in DIALECTS:
        ext = dialects.get(dialect).extensions
        for path in sorted((ROOT / "samples" / dialect).iterdir()):
            if path.suffix in ext:
                programs.append((path.name, path.read_text(encoding="utf-8"), dialect, "O1"))
    drawing, machine = drawing_program(args.size), machine_program(1500)
    # -O1 is the default; the drawing needs -Os to fit the controller's memory (bench_opt.py)
    programs += [(f"drawing.prg ({statements(drawing)} st.)", drawing, "arcus", "Os"),
                 (f"machine.prg ({statements(machine)} st.)", machine, "arcus", "O1"),
                 (f"machine.prg ({statements(machine)} st.)", machine, "arcus", "Os")]

    print(f"{'program':<36}{'level':>6}{'target':>8}{'--no-verify ms':>16}{'validated ms':>14}{'ratio':>8}  outcome")
    missed, ratios = [], []
    for name, text, dialect, level in programs:
        for target in (DIALECTS if args.targets else (dialect,)):
            plain, checked, state = measure(name.split(" ")[0], text, dialect, target, level, args.repeat)
            if state not in ("validated", "as written") and state.split(",")[0] != "S010":
                continue  # refused by the backend: nothing would be written either way
            ratio = checked / plain
            ratios.append(ratio)
            print(f"{name:<36}{level:>6}{target:>8}{plain * 1000:>16.1f}{checked * 1000:>14.1f}{ratio:>8.2f}  {state}")
            if ratio > TARGET:
                missed.append(f"{name} -> {target}: {ratio:.2f}x")
    print()
    print(f"validated / unvalidated: median {sorted(ratios)[len(ratios) // 2]:.2f}, worst {max(ratios):.2f} "
          f"(target <= {TARGET})")
    for line in missed:
        print(f"MISSED {line}")
    return 1 if missed else 0


if __name__ == "__main__":
    sys.exit(main())
