"""Benchmark: check a generated 10,000-command X150 stream, and compare with a bare Lark parse.

Run:  .venv/bin/python bench/bench_x150.py [--commands N] [--repeat R]

What is compared, in one run on the same text:
- "bare parse": the Lark LALR parser of grammars/x150.lark (contextual lexer, Lark's own tree
  built, no callbacks): the floor of a frontend that parses this grammar with Lark;
- "mcc check": what `mcc check` runs for one file (`driver.check_file`): the text cut into lines of
  command tokens (one regular expression made of the grammar's own terminals, as the grammar is
  regular; Lark's parser runs only when a line does not lex, to report it and recover), each token
  read against the catalog (address, B prefix, longest-match mnemonic, argument), lowering to the
  IR, the modes resolved, and every check (including the sequence memory).
The ratio is check time / bare parse time (best of R runs each, in CPU time of this process,
`time.process_time`, so that other work on a shared machine does not count); target (issue 12):
at most 2.
See docs/PERFORMANCE.md.
"""

from __future__ import annotations

import argparse
import random
import time

from mcc.compiler import driver, profiles
from mcc.compiler.span import SourceFile
from mcc.compiler.x150 import frontend, parser

SETUP = ["1CUR4000", "1CMR4000", "1A10", "1V5", "1MN", "1MPI", "1IN3A", "1OUT1A", "1LD3", "1GA20", "1GHF0.5"]
BODY = ["1D4000", "1G", "1T0.5", "1VAR1=VAR1+1", "1VAR2=VAR1*100/VAR4", "1TRE_XX1", "1O1X0", "1A25",
        "1V8.5", "1D(VAR3)", "1DTXT\"PART DONE\"", "1DPC208", "1TX1,0,3,COUNT=", "1BCPE2000", "1SKEX1"]


def generate(commands: int, seed: int = 150) -> str:
    """A stream of exactly `commands` commands: blocks of setup then a 60-command sequence with
    loops and conditionals and the XR that runs it, padded with immediate commands; several
    commands share some lines, comments end others."""
    rng = random.Random(seed)
    stream: list[str] = []
    sequence = 0
    while True:
        sequence = sequence % 64 + 1
        block = list(SETUP) + [f"1XE{sequence}", f"1XD{sequence}", "1L5", "1IF(VAR1>5 AND IN_XX1)", "1XR64", "1ELSE"]
        block += [rng.choice(BODY) for _ in range(20)]
        block += ["1NIF", "1WHILE(VAR2<10)"] + [rng.choice(BODY) for _ in range(20)] + ["1NWHILE", "1N"]
        block += ["1REPEAT"] + [rng.choice(BODY) for _ in range(8)] + ["1UNTIL(IN_1 OR VAR3=2)", "1XT",
                                                                        f"1XR{sequence}"]
        if len(stream) + len(block) > commands:
            break
        stream += block
    stream += [rng.choice(SETUP) for _ in range(commands - len(stream))]
    out: list[str] = []
    line: list[str] = []
    for command in stream:
        line.append(command)
        if len(line) >= rng.choice((1, 1, 1, 3)):
            out.append(" ".join(line) + (" ; step" if rng.random() < 0.2 else ""))
            line = []
    if line:
        out.append(" ".join(line))
    return "\n".join(out) + "\n"


def best(runs: int, work) -> float:
    times = []
    for _ in range(runs):
        start = time.process_time()
        work()
        times.append(time.process_time() - start)
    return min(times)


def main() -> None:
    args = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    args.add_argument("--commands", type=int, default=10_000)
    args.add_argument("--repeat", type=int, default=5)
    opts = args.parse_args()
    text = generate(opts.commands)
    profile = profiles.load("x150-pdhx")
    bare = parser.bare_parser()
    frontend.analyze(SourceFile("warmup.x150", text[:2000]), profile)  # build the cached parser and catalog
    parse_time = best(opts.repeat, lambda: bare.parse(text))
    result = {}

    def check() -> None:
        result["file"] = driver.check_file("bench.x150", "x150", profile=profile, text=text)

    check_time = best(opts.repeat, check)
    analysis = result["file"].analysis
    tokens = sum(1 for _ in analysis.tree.commands())
    print(f"x150 benchmark: {tokens} commands on {text.count(chr(10))} lines ({len(text)} bytes), best of {opts.repeat}")
    print(f"  bare Lark parse (grammars/x150.lark, no callbacks): {parse_time * 1000:8.1f} ms")
    print(f"  mcc check (parse, read, lower, all checks):         {check_time * 1000:8.1f} ms")
    ratio = check_time / parse_time
    print(f"  ratio check / bare parse:                           {ratio:8.2f}x  (target <= 2.0) "
          f"{'OK' if ratio <= 2 else 'OVER'}")
    print(f"  routines {len(analysis.module.routines)}, diagnostics {len(result['file'].diagnostics)}")


if __name__ == "__main__":
    main()
