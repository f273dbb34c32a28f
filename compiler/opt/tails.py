"""Tail merging (-O2).

What it does: when every block that jumps to a block ends with the same operation, that operation
is written once at the start of the block instead (`IF ... X1000 ELSE ... X1000 ENDIF` moves the
common `X1000` after `ENDIF`).

A loop's header is never the joined block (one of its predecessors is the loop's back edge), so
the loops a backend without GOTO rebuilds keep their shape.

Why it is safe: the joined block is entered only from those blocks (never from the routine's
start, a host's EX, or a branch), and each of them ran that same operation last; running it
first in the joined block runs the same operations in the same order on every path.

Needs: the predecessors of each block (computed here).
"""

from __future__ import annotations

from mcc.compiler import ir
from mcc.compiler.opt.common import key, predecessors, referenced_labels

NAME = "tails"
NEEDS = ()


def run(module: ir.Module, context) -> int:
    moved = 0
    pinned = referenced_labels(module)
    for routine in module.routines:
        by_label = {b.label: b for b in routine.blocks}
        order = {b.label: i for i, b in enumerate(routine.blocks)}
        preds = predecessors(module)
        for block in routine.blocks:
            if block is routine.entry or block.named or block.label in pinned:
                continue
            sources = [by_label.get(p) for p in preds.get(block.label, [])]
            if len(sources) < 2 or any(s is None or not isinstance(s.terminator, ir.Jump) or s is block
                                       or order[s.label] > order[block.label] for s in sources):
                continue  # only joins every path reaches forwards: never a loop's header
            while all(s.ops for s in sources) and len({key(s.ops[-1]) for s in sources}) == 1:
                op = sources[0].ops[-1]
                for source in sources:
                    source.ops.pop()
                block.ops.insert(0, op)
                moved += len(sources) - 1
    return moved
