"""Benchmark: `mcc lint` over a generated tree of 1,000 files, with one and with two workers.

The tree mixes the three dialects (the bundled samples, each copied into many directories with
small variations so no two files are identical) in nested folders, as a repository of machine
programs looks. Both runs go through the same entry point as `mcc lint` (file discovery, the
nearest configuration, the process pool) and are measured in one run of this script, so a noisy
shared machine affects both alike. The report gives files per second and the speed-up.

Run: .venv/bin/python bench/bench_lint.py [--files N] [--repeat R]
"""

from __future__ import annotations

import argparse
import os
import shutil
import tempfile
import time
from pathlib import Path

from mcc.compiler.config import Resolver
from mcc.compiler.lint import engine

ROOT = Path(__file__).resolve().parent.parent
SAMPLES = sorted(p for p in (ROOT / "samples").glob("*/*") if p.suffix in (".mxt", ".prg", ".x150"))
COMMENT = {".mxt": "`", ".prg": ";", ".x150": ";"}


def generate(target: Path, count: int) -> list[str]:
    """`count` files in 20 folders of 5 sub-folders each, from the samples with a header comment."""
    written = []
    for i in range(count):
        sample = SAMPLES[i % len(SAMPLES)]
        folder = target / f"line{i % 20:02}" / f"cell{i % 5}"
        folder.mkdir(parents=True, exist_ok=True)
        path = folder / f"{sample.stem}_{i:04}{sample.suffix}"
        text = sample.read_text(encoding="utf-8")
        path.write_text(f"{COMMENT[sample.suffix]} generated copy {i} of {sample.name}\n{text}", encoding="utf-8")
        written.append(str(path))
    (target / "mcc.toml").write_text('ignore = ["A305"]\n', encoding="utf-8")
    return written


def lint_tree(root: Path, jobs: int) -> tuple[int, float]:
    start = time.perf_counter()
    resolver = Resolver()
    files = engine.expand([str(root)], resolver)
    work = [(path, resolver.for_path(path)) for path in files]
    outcomes = engine.run(work, engine.Options(), jobs)
    elapsed = time.perf_counter() - start
    assert len(outcomes) == len(files)
    return len(files), elapsed


def main() -> None:
    args = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    args.add_argument("--files", type=int, default=1000)
    args.add_argument("--repeat", type=int, default=3)
    options = args.parse_args()
    tmp = Path(tempfile.mkdtemp(prefix="mcc-bench-lint-"))
    try:
        generate(tmp, options.files)
        lint_tree(tmp, 1)  # warm the file cache and the imports once
        results = {}
        for jobs in (1, 2):
            best = min(lint_tree(tmp, jobs)[1] for _ in range(options.repeat))
            results[jobs] = best
            print(f"jobs={jobs}: {options.files} files in {best:.2f} s = {options.files / best:,.0f} files/s")
        load = ", ".join(f"{x:.2f}" for x in os.getloadavg()) if hasattr(os, "getloadavg") else "n/a"
        print(f"speed-up with 2 workers: {results[1] / results[2]:.2f}x (CPUs: {os.cpu_count()}, load average "
              f"{load}: other processes compete for the CPUs when it is near the CPU count)")
    finally:
        shutil.rmtree(tmp, ignore_errors=True)


if __name__ == "__main__":
    main()
