"""Block merging.

What it does: a block that ends in a jump to a block only it reaches is joined with that block
(`A: ...; jump B` and `B: ...` become one block), so backends that write labels or structure write
fewer of them.

Why it is safe: control always goes from the first block to the second and nowhere else enters
the second, so running them as one block runs the same operations in the same order. A block the
source named, a routine's entry and a block named as a value are never merged away.

Needs: the predecessors of each block (computed here).
"""

from __future__ import annotations

from mcc.compiler import ir
from mcc.compiler.opt.common import predecessors, referenced_labels

NAME = "merge"
NEEDS = ()


def run(module: ir.Module, context) -> int:
    merged = 0
    pinned = referenced_labels(module)
    preds = predecessors(module)
    for routine in module.routines:
        by_label = {b.label: b for b in routine.blocks}
        gone: set[str] = set()
        for block in routine.blocks:
            if block.label in gone:
                continue
            while isinstance(block.terminator, ir.Jump):
                target = by_label.get(block.terminator.target)
                if target is None or target is block or target.named or target.label in pinned \
                        or preds.get(target.label, []) != [block.label]:
                    break
                block.ops.extend(target.ops)
                block.terminator = target.terminator
                for succ in ir.successors(target.terminator):
                    preds[succ] = [block.label if p == target.label else p for p in preds.get(succ, [])]
                gone.add(target.label)
                merged += 1
        routine.blocks[:] = [b for b in routine.blocks if b.label not in gone]
    return merged
