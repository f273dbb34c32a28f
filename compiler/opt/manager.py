"""The pass manager: which passes each level runs, in what order, and what they report.

A pass is a module of `mcc.compiler.opt` with `NAME`, `NEEDS` (the analyses it reads) and
`run(module, context) -> int` (operations removed, or added when negative). Analyses are computed
on demand by the `Context` and dropped after every pass that changed the module, so no pass reads
a stale one. With `verify=True` (the tests) the IR verifier runs after each pass and a broken
invariant raises, naming the pass.
"""

from __future__ import annotations

import importlib
from dataclasses import dataclass, field

from mcc.compiler import ir
from mcc.compiler.in_force import InForce
from mcc.compiler.opt.common import reached
from mcc.compiler.profiles import Profile

# Passes in the order they run; a level runs the ones it names, in this order.
PASSES = ("fold", "copies", "dead_stores", "settings", "branches", "unreachable", "merge", "tails", "outline")

LEVELS: dict[str, tuple[str, ...]] = {
    "O0": (),
    "O1": ("fold", "copies", "dead_stores", "settings", "branches", "unreachable", "merge"),
    "O2": ("fold", "copies", "dead_stores", "settings", "branches", "unreachable", "merge", "tails"),
    "Os": ("fold", "copies", "dead_stores", "settings", "branches", "unreachable", "merge", "tails", "outline"),
}
GLOBAL_LEVELS = frozenset({"O2", "Os"})  # levels whose passes also work across blocks and routines


class PassFailed(Exception):
    """A pass left the module breaking the IR contract (raised only with verify=True)."""


@dataclass
class PassStat:
    name: str
    ops_removed: int = 0
    changed: bool = False


@dataclass
class OptStats:
    level: str
    passes: list[PassStat] = field(default_factory=list)
    ops_before: int = 0
    ops_after: int = 0
    lines_before: int | None = None  # target lines at -O0 (set by the driver)
    lines_after: int | None = None
    fallback: bool = False  # the optimized program could not be written: the -O0 one was kept
    # Whether the passes left a program other than the one they were given (`fingerprint` before and
    # after: the code that can run, source lines aside): a compile whose passes changed nothing
    # writes the program as written, and needs no validation (driver.needs_validation).
    changed: bool = False

    @property
    def lines_saved(self) -> int | None:
        if self.lines_before is None or self.lines_after is None:
            return None
        return self.lines_before - self.lines_after

    def to_json(self) -> dict:
        return {"level": self.level, "ops_before": self.ops_before, "ops_after": self.ops_after,
                "target_lines_before": self.lines_before, "target_lines_after": self.lines_after,
                "target_lines_saved": self.lines_saved, "fallback_to_O0": self.fallback,
                "passes": [{"name": p.name, "ops_removed": p.ops_removed} for p in self.passes]}

    def summary(self) -> str:
        removed = ", ".join(f"{p.name} -{p.ops_removed}" for p in self.passes if p.ops_removed)
        saved = f", {self.lines_saved} target lines saved" if self.lines_saved else ""
        if self.fallback:
            return f"-{self.level}: the optimized program could not be written for the target; kept as written"
        return f"-{self.level}: {self.ops_before - self.ops_after} operations removed" \
               f"{' (' + removed + ')' if removed else ''}{saved}"


@dataclass
class Context:
    """What a pass may read besides the module: the level, the target profile, cached analyses."""

    module: ir.Module
    level: str
    profile: Profile | None = None
    _in_force: InForce | None = None

    @property
    def global_scope(self) -> bool:
        return self.level in GLOBAL_LEVELS

    def in_force(self) -> InForce:
        if self._in_force is None:
            self._in_force = InForce(self.module)
        return self._in_force

    def invalidate(self) -> None:
        self._in_force = None


def pass_names(level: str, passes: str | None) -> tuple[str, ...]:
    """The passes to run: an explicit comma-separated list, or the level's."""
    if passes:
        chosen = tuple(p.strip() for p in passes.split(",") if p.strip())
        unknown = [p for p in chosen if p not in PASSES]
        if unknown:
            raise ValueError(f"unknown pass {', '.join(unknown)} (passes: {', '.join(PASSES)})")
        return chosen
    return LEVELS[level]


def count_ops(module: ir.Module) -> int:
    return sum(len(block.ops) for _, block in module.blocks())


def optimize(module: ir.Module, level: str = "O1", profile: Profile | None = None,
             passes: str | None = None, verify: bool = False) -> OptStats:
    """Run the passes of `level` (or `passes`) over `module` in place; returns the statistics."""
    names = pass_names(level, passes)
    stats = OptStats(level, ops_before=count_ops(module))
    before_all = fingerprint(module) if names else ""
    context = Context(module, level if level in LEVELS else "O1", profile)
    for name in names:
        unit = importlib.import_module(f"mcc.compiler.opt.{name}")
        before = count_ops(module)
        changed = bool(unit.run(module, context))
        after = count_ops(module)
        stats.passes.append(PassStat(name, before - after, changed or before != after))
        if changed or before != after:
            context.invalidate()
        if verify:
            check(module, name)
    stats.ops_after = count_ops(module)
    # a pass's own count may say it changed something that makes no difference (an unreachable
    # block dropped): the fingerprint decides
    stats.changed = bool(names) and fingerprint(module) != before_all
    return stats


def fingerprint(module: ir.Module) -> str:
    """The program `module` is, source lines aside: its variables, routines, and the blocks that can
    run (`reachable`) with their operations and terminators, as text. Two modules with the same
    fingerprint run alike: removing a block no path reaches changes nothing."""
    from mcc.compiler.ir_print import expr_text, op_text, term_text

    module = reachable(module)
    lines = [f"{module.dialect} {module.steps_per_rev}"]
    lines += [f"{name} {v.type.value} {v.scope} {expr_text(v.init) if v.init is not None else ''}"
              for name, v in module.variables.items()]
    for routine in module.routines:
        lines.append(f"routine {routine.name} {routine.kind.value} {routine.number} {routine.origin}")
        for block in routine.blocks:
            lines.append(f"{block.label}:")
            lines += [op_text(op) for op in block.ops]
            lines.append(term_text(block.terminator))
    return "\n".join(lines)


def check(module: ir.Module, name: str) -> None:
    from mcc.compiler import ir_verify

    problems = ir_verify.verify(module, meaning=False)
    if problems:
        raise PassFailed(f"after pass {name}: " + "; ".join(str(p) for p in problems[:3]))


def reachable(module: ir.Module) -> ir.Module:
    """`module` without the unnamed blocks no path reaches: from the first block of every routine
    and every named block (a label a host may start at), along jumps and branches."""
    import dataclasses

    blocks = {block.label: block for _, block in module.blocks()}
    seen = reached(blocks, [r.blocks[0].label for r in module.routines if r.blocks]
                   + [b.label for b in blocks.values() if b.named])
    if len(seen) == len(blocks):
        return module
    routines = [dataclasses.replace(r, blocks=[b for b in r.blocks if b.label in seen]) for r in module.routines]
    return dataclasses.replace(module, routines=routines)
