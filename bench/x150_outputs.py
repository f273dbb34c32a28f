"""Dump every output of the X150 check and compile for many inputs, to diff before/after a change
that must change no behaviour (the speed rounds of docs/PERFORMANCE.md).

Run:  .venv/bin/python bench/x150_outputs.py OUT.txt [--seeds 300]

For each input: the check's diagnostics (code, severity, kind, span with offsets, message, notes,
fix), the IR's text (`mcc ir`) and a full dump of the module (every node and every span with its
offsets, so a constant kept from another command shows), and the compile at O0 and at the default
level (O1): its diagnostics and the listing with its source map. The compile is not validated in
the simulator (`verify=False`): the verdict depends only on the IR and the listing, dumped here.
It also checks, for each input, that the syntax tree built with the copies of earlier readings
(`CommandReader.read_again`) equals, node for node and span for span, the one built by reading
every token afresh, with the same diagnostics and no node shared between two commands.

Inputs: the benchmark's generated text at several sizes and seeds, every `.x150` file of the
repository, the programs of tests/x150/test_x150_generated.py's `Program` (addressed "1", "12" and
unaddressed), and those programs mutated with mode commands, D, H, calls and deleted lines.
"""

from __future__ import annotations

import argparse
import dataclasses
import pathlib
import random
import sys
from enum import Enum

ROOT = pathlib.Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "bench"))
sys.path.insert(0, str(ROOT / "tests" / "x150"))
sys.path.insert(0, str(ROOT / "tests"))

from bench_x150 import generate  # noqa: E402
from mcc.compiler import driver, ir_print  # noqa: E402
from mcc.compiler.diagnostics import Diagnostics  # noqa: E402
from mcc.compiler.span import SourceFile  # noqa: E402
from mcc.compiler.x150 import parser, tokens  # noqa: E402

MUTATIONS = ["1MPA", "1MPI", "1MN", "1MC", "MPA", "MPI", "1D4000", "D-200", "1D(VAR2)", "1H", "1H+", "H-",
             "1G", "G", "1XR1", "1XR2", "1XG3", "1V3", "1A7", "1MQ", "1GH5", "2MPA", "2G", "1XRT"]


def dump(value, out: list[str], depth: int = 0) -> None:
    """Every field of a dataclass tree, spans in full."""
    pad = "  " * depth
    if value is None or isinstance(value, (bool, int, float, str)):
        out.append(f"{pad}{value!r}")
    elif isinstance(value, Enum):
        out.append(f"{pad}{type(value).__name__}.{value.name}")
    elif isinstance(value, (tuple, list, frozenset, set)):
        items = sorted(value, key=repr) if isinstance(value, (set, frozenset)) else value
        out.append(f"{pad}{type(value).__name__}[{len(items)}]")
        for item in items:
            dump(item, out, depth + 1)
    elif isinstance(value, dict):
        out.append(f"{pad}dict[{len(value)}]")
        for key, item in value.items():
            out.append(f"{pad} key {key!r}")
            dump(item, out, depth + 1)
    elif type(value).__name__ == "Span":
        out.append(f"{pad}Span({value.file},{value.line},{value.column},{value.end_line},"
                   f"{value.end_column},{value.start},{value.end})")
    elif dataclasses.is_dataclass(value):
        out.append(f"{pad}{type(value).__name__}")
        for f in dataclasses.fields(value):
            out.append(f"{pad} .{f.name}")
            dump(getattr(value, f.name), out, depth + 1)
    else:
        out.append(f"{pad}{type(value).__name__}:{value!r}")


def diagnostics(items, out: list[str]) -> None:
    for d in items:
        s = d.span
        out.append(f"  {d.code} {d.severity.value} {d.kind.value} {s.file}:{s.line}:{s.column}-{s.end_line}:"
                   f"{s.end_column} [{s.start},{s.end}] {d.message!r} notes={list(d.notes)!r} "
                   f"fix={d.fix.to_json() if d.fix else None!r}")


def outputs(name: str, text: str, out: list[str]) -> None:
    out.append(f"=== {name}")
    result = driver.check_file(name, "x150", text=text)
    out.append("check:")
    diagnostics(result.diagnostics, out)
    module = result.analysis.module if result.analysis is not None else None
    if module is not None:
        out.append("ir:")
        out.append(ir_print.to_text(module))
        out.append("module:")
        dump(module, out)
        if result.analysis.memory:
            out.append(f"memory: {result.analysis.memory!r}")
    for level in ("O0", "O1"):
        compiled = driver.compile_file(name, "x150", text=text, opt_level=level, verify=False)
        out.append(f"compile {level}:")
        diagnostics(compiled.diagnostics, out)
        if compiled.listing is not None:
            out.append(compiled.listing.render())


def same_readings(name: str, text: str) -> None:
    """The tree with copied readings is the tree read afresh (see the module's docstring)."""
    diags = Diagnostics()
    copied = parser.parse(SourceFile(name, text), diags)
    again = tokens.CommandReader.read_again
    tokens.CommandReader.read_again = lambda self, token, base, spans, readings: self.read_token(token, base, spans)
    try:
        fresh_diags = Diagnostics()
        fresh = parser.parse(SourceFile(name, text), fresh_diags)
    finally:
        tokens.CommandReader.read_again = again
    if copied.lines != fresh.lines:
        raise SystemExit(f"{name}: the copied readings differ from a fresh reading")
    if [(d.code, d.span, d.message) for d in diags.items] != [(d.code, d.span, d.message) for d in fresh_diags.items]:
        raise SystemExit(f"{name}: the diagnostics of the copied readings differ")
    seen: set[int] = set()
    for command in copied.commands():
        nodes = [command, command.span, command.arg] + ([command.arg.span] if command.arg is not None else [])
        for node in nodes:
            if node is not None and id(node) in seen:
                raise SystemExit(f"{name}: two commands share a node ({node!r})")
        seen.update(id(node) for node in nodes if node is not None)


def mutate(text: str, rng: random.Random) -> str:
    lines = text.splitlines()
    for _ in range(rng.randint(1, 6)):
        roll = rng.random()
        where = rng.randrange(len(lines) + 1)
        if roll < 0.3 and lines:
            del lines[min(where, len(lines) - 1)]
        else:
            lines.insert(where, rng.choice(MUTATIONS))
    return "\n".join(lines) + "\n"


def inputs(seeds: int):
    for commands, seed in ((300, 150), (2000, 150), (2000, 7), (10_000, 150), (10_000, 3)):
        yield f"bench-{commands}-{seed}.x150", generate(commands, seed)
    for path in sorted(ROOT.glob("**/*.x150")):
        if ".venv" in path.parts:
            continue
        yield str(path.relative_to(ROOT)), path.read_text(encoding="utf-8", errors="replace")
    from test_x150_generated import Program

    for seed in range(seeds):
        address = ("1", "12", "")[seed % 3]
        text = Program(random.Random(seed), address).build()
        if not address:
            text = text.replace("\nSV\n", "\n1SV\n")
        yield f"gen-{seed}.x150", text
        if seed % 2 == 0:
            yield f"mut-{seed}.x150", mutate(text, random.Random(seed))


def main() -> None:
    args = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    args.add_argument("out")
    args.add_argument("--seeds", type=int, default=300)
    opts = args.parse_args()
    out: list[str] = []
    count = 0
    for name, text in inputs(opts.seeds):
        same_readings(name, text)
        outputs(name, text, out)
        count += 1
    pathlib.Path(opts.out).write_text("\n".join(out) + "\n", encoding="utf-8")
    print(f"{count} inputs, {len(out)} lines -> {opts.out}")


if __name__ == "__main__":
    main()
