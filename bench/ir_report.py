"""The IR's meaning, measured: the share of Native operations per dialect, and the cross-dialect
table (per pair: programs converted to a program that checks clean, refusals and why, and any
output that does not check or internal error).

    .venv/bin/python bench/ir_report.py                      # the project's samples and golden programs
    .venv/bin/python bench/ir_report.py ../shared/examples   # another tree: <dir>/<dialect>/*.<ext>

Each refusal is counted under its first error's code, so the table shows what blocks conversion.
"""

from __future__ import annotations

import collections
import sys
from pathlib import Path

from mcc.compiler import dialects, driver, ir

ROOT = Path(__file__).resolve().parent.parent


def programs(tree: Path | None, dialect: str) -> list[Path]:
    info = dialects.get(dialect)
    if tree is not None:
        folder = tree / dialect
        return sorted(p for p in folder.glob("*") if p.suffix in info.extensions)
    found = sorted(p for p in (ROOT / "samples" / dialect).glob("*") if p.suffix in info.extensions)
    return found + sorted(p for p in (ROOT / "tests" / "golden" / dialect).glob("*/*")
                          if p.suffix in info.extensions)


def native_share(files: list[Path], dialect: str) -> tuple[int, int, collections.Counter]:
    total = native = 0
    kinds: collections.Counter = collections.Counter()
    for path in files:
        result = driver.check_file(str(path), dialect)
        module = result.analysis.module if result.analysis is not None else None
        if module is None or result.has_errors:
            continue
        for _, block in module.blocks():
            for op in block.ops:
                total += 1
                if isinstance(op, ir.Native):
                    native += 1
                    kinds[op.mnemonic] += 1
    return native, total, kinds


def cross_row(files: list[Path], source: str, target: str) -> tuple[int, collections.Counter]:
    outcome: collections.Counter = collections.Counter()
    tried = 0
    for path in files:
        if driver.check_file(str(path), source).has_errors:
            continue
        tried += 1
        result = driver.compile_file(str(path), source, target)
        if any(d.kind.value == "internal" for d in result.diagnostics):
            outcome["internal"] += 1
        elif result.has_errors:
            first = next(d for d in result.diagnostics if d.severity.value == "error")
            outcome[f"refused {first.code}"] += 1
        else:
            again = driver.compile_file("out" + dialects.get(target).output_extension, target,
                                        text=result.listing.text)
            outcome["clean" if not again.has_errors else "bad output"] += 1
    return tried, outcome


def main(argv: list[str]) -> int:
    tree = Path(argv[0]) if argv else None
    names = dialects.names()
    print("Native operations per dialect")
    for dialect in names:
        native, total, kinds = native_share(programs(tree, dialect), dialect)
        share = 100 * native / total if total else 0.0
        top = ", ".join(f"{k or '(number)'} {n}" for k, n in kinds.most_common(6))
        print(f"  {dialect:6} {native:4} of {total:5} operations = {share:5.1f} %   {top}")
    print("\nCross-dialect compilation (programs without errors of their own)")
    print(f"  {'pair':16} {'tried':>5} {'clean':>6} {'bad':>4} {'internal':>8}  refusals")
    for source in names:
        files = programs(tree, source)
        for target in names:
            if target == source:
                continue
            tried, outcome = cross_row(files, source, target)
            refusals = ", ".join(f"{k.split()[1]} {n}" for k, n in sorted(outcome.items()) if k.startswith("refused"))
            print(f"  {source + ' -> ' + target:16} {tried:5} {outcome['clean']:6} {outcome['bad output']:4} "
                  f"{outcome['internal']:8}  {refusals}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
