"""Random valid programs through every -O level and every target, validated by the simulator (issue 23).

    .venv/bin/python bench/fuzz_codegen.py [--count N] [--seed S] [--dialect D ...] [--jobs J]
        [--features a,b] [--exclude a,b] [--exclude-known] [--minimize K] [--save] [--quiet]

For each dialect, programs `seed .. seed+N-1` of tests/codegen_programs.py (text through the
frontend, `mcc check` clean) are compiled at -O0 -O1 -O2 -Os to mcode, arcus and x150. Each
compile must validate equal (`sim.verify.check_translation`, the comparison `--verify` runs) or
be refused with errors that name a line. Anything else is a finding; findings are grouped by a
signature (kind, route, the message without its numbers) and the first program of each group is
minimized (lines deleted while the same finding persists) and printed, and with --save written
to bench/findings/<dialect>-<seed>-<target>-<level><ext> with the finding in a comment at its top.

Prints progress every 5 % and the rate (programs/s and compiles/s) at the end. Exit status 1 when
there is any finding. Target (issue 23): 10,000 programs per dialect with no wrong code.
"""

from __future__ import annotations

import argparse
import re
import sys
import time
from collections import Counter, defaultdict
from multiprocessing import Pool
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "tests"))

from codegen_programs import (DIALECTS, EXTENSIONS, FEATURES, KNOWN_DEFECT_FEATURES,  # noqa: E402
                              KNOWN_DEFECT_FEATURES_BY_DIALECT, LEVELS, TARGETS, Finding, generate, run_program)

FINDINGS = ROOT / "bench" / "findings"
COMMENT = {"mcode": "'", "arcus": ";", "x150": ";"}


def signature(finding: Finding) -> str:
    """Findings that are probably one defect: the same kind and route, the message without numbers."""
    detail = finding.detail.split("; nothing was written")[0]
    difference = re.search(r"scenario '[^']*': (.*)", detail)  # a divergence: what differs, not where
    detail = re.sub(r"-?\d+(\.\d+)?(e[+-]?\d+)?", "#", difference.group(1) if difference else detail)
    return f"{finding.kind} {finding.dialect}->{finding.target} {detail[:160]}"


def same_finding(dialect: str, text: str, finding: Finding) -> bool:
    outcome = run_program(dialect, text, (finding.target,), (finding.level,) if finding.level != "-" else ("O0",))
    return any(signature(f) == signature(finding) for f in outcome.findings)


def minimize(dialect: str, text: str, finding: Finding, budget: float = 120.0) -> str:
    """Delete chunks of lines, then single lines, while a finding of the same signature (kind, route,
    message without its numbers) persists; an invalid program is another kind, so it checks clean."""
    lines = text.splitlines()
    start = time.monotonic()
    chunk = max(1, len(lines) // 2)
    while chunk >= 1 and time.monotonic() - start < budget:
        i, changed = 0, False
        while i < len(lines) and time.monotonic() - start < budget:
            candidate = lines[:i] + lines[i + chunk:]
            if candidate and same_finding(dialect, "\n".join(candidate) + "\n", finding):
                lines, changed = candidate, True
            else:
                i += chunk
        if not changed or chunk > 1:
            chunk //= 2
    return "\n".join(lines) + "\n"


def work(task: tuple[str, int, tuple[str, ...]]):
    dialect, seed, features = task
    program = generate(dialect, seed, features)
    outcome = run_program(dialect, program.text)
    return dialect, seed, program.text, outcome


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--count", type=int, default=100, help="programs per dialect")
    parser.add_argument("--seed", type=int, default=0, help="first seed")
    parser.add_argument("--dialect", action="append", choices=DIALECTS, help="source dialect (repeatable)")
    parser.add_argument("--jobs", type=int, default=1)
    parser.add_argument("--features", help=f"comma-separated subset of: {', '.join(FEATURES)}")
    parser.add_argument("--exclude", default="", help="features to leave out")
    parser.add_argument("--exclude-known", action="store_true",
                        help="leave out the features of known defects (codegen_programs.KNOWN_DEFECT_FEATURES), "
                             "as the bounded test does")
    parser.add_argument("--minimize", type=int, default=10, help="groups of findings to minimize")
    parser.add_argument("--save", action="store_true", help="write minimized reproducers to bench/findings/")
    parser.add_argument("--quiet", action="store_true", help="no progress lines")
    args = parser.parse_args(argv)

    features = tuple(args.features.split(",")) if args.features else FEATURES
    unknown = [f for f in features + tuple(filter(None, args.exclude.split(","))) if f not in FEATURES]
    if unknown:
        parser.error(f"unknown feature(s) {', '.join(unknown)}; choose from {', '.join(FEATURES)}")
    features = tuple(f for f in features if f not in args.exclude.split(","))
    dialects = args.dialect or list(DIALECTS)

    def for_dialect(dialect: str) -> tuple[str, ...]:
        if not args.exclude_known:
            return features
        known = {**KNOWN_DEFECT_FEATURES, **KNOWN_DEFECT_FEATURES_BY_DIALECT.get(dialect, {})}
        return tuple(f for f in features if f not in known)

    tasks = [(d, s, for_dialect(d)) for d in dialects for s in range(args.seed, args.seed + args.count)]

    groups: dict[str, list[tuple[str, int, str, Finding]]] = defaultdict(list)
    counts = {"validated": 0, "refused": 0, "findings": 0}
    refusals: Counter[str] = Counter()
    start = time.monotonic()
    step = max(1, len(tasks) // 20)
    pool = Pool(args.jobs) if args.jobs > 1 else None
    results = pool.imap_unordered(work, tasks, chunksize=4) if pool else map(work, tasks)
    for done, (dialect, seed, text, outcome) in enumerate(results, 1):
        counts["validated"] += outcome.validated
        counts["refused"] += outcome.refused
        counts["findings"] += len(outcome.findings)
        for refusal in outcome.refusals:  # "target -Olevel CODE line n: message"
            target, _, code, _, _, message = refusal.split(" ", 5)
            refusals[f"{dialect}->{target} {code}: {re.sub(r'-?[0-9][0-9.e+]*', '#', message)[:100]}"] += 1
        for finding in outcome.findings:
            groups[signature(finding)].append((dialect, seed, text, finding))
        if not args.quiet and (done % step == 0 or done == len(tasks)):
            elapsed = time.monotonic() - start
            print(f"[{done}/{len(tasks)}] {elapsed:.0f} s, {done / elapsed:.2f} programs/s, "
                  f"{counts['findings']} findings in {len(groups)} groups", flush=True)
    if pool:
        pool.close()
    elapsed = time.monotonic() - start
    compiles = len(tasks) * len(TARGETS) * len(LEVELS)
    print(f"\n{len(tasks)} programs ({', '.join(dialects)}), {compiles} compiles in {elapsed:.1f} s: "
          f"{len(tasks) / elapsed:.2f} programs/s, {compiles / elapsed:.1f} compiles/s")
    print(f"validated {counts['validated']}, refused with a line {counts['refused']}, findings {counts['findings']}")

    if refusals:
        print("most frequent refusals (a line named, as required):")
        for reason, count in refusals.most_common(12):
            print(f"  {count:6d}  {reason}")
    for n, (sig, members) in enumerate(sorted(groups.items(), key=lambda kv: -len(kv[1]))):
        dialect, seed, text, finding = members[0]
        seeds = sorted({(d, s) for d, s, _, _ in members})
        print(f"\n== {len(members)} x {sig}\n   first: {finding}\n   programs: "
              + ", ".join(f"{d}:{s}" for d, s in seeds[:12]) + (" ..." if len(seeds) > 12 else ""))
        if n >= args.minimize:
            continue
        small = minimize(dialect, text, finding)
        print("   minimized reproducer:\n" + "\n".join("     " + line for line in small.splitlines()))
        if args.save:
            FINDINGS.mkdir(exist_ok=True)
            name = FINDINGS / f"{dialect}-{seed}-{finding.target}-{finding.level}{EXTENSIONS[dialect]}"
            c = COMMENT[dialect]
            header = [f"{c} bench/fuzz_codegen.py --dialect {dialect} --seed {seed} --count 1",
                      f"{c} mcc compile -{finding.level} --target {finding.target}: {finding.kind}"]
            header += [f"{c} {part}" for part in re.findall(r".{1,100}(?:\s|$)", finding.detail)]
            name.write_text("\n".join(header) + "\n" + small)
            print(f"   saved {name.relative_to(ROOT)}")
    return 1 if groups else 0


if __name__ == "__main__":
    sys.exit(main())
