"""Branch simplification and jump threading.

What it does: a branch whose condition is decided by constants becomes a jump (`IF 1=1`); a
branch whose two targets are the same block becomes a jump; a jump or branch to an empty block
that only jumps on goes straight to where that block goes.

Why it is safe: a condition of two constants has one value on every run; an empty block that
jumps on does nothing, so going past it changes nothing. Blocks the source named (MCode labels,
which a host can run with EX) are never skipped. Jumps are threaded forward only: a loop's
back edge keeps going through its latch, and only for targets with labels (MCode): a backend
without GOTO (Arcus, X150) rebuilds IF/WHILE from the graph, and a jump that skips an IF's join
or a loop's exit block is one it could no longer write as a construct.

Needs: nothing beyond the module.
"""

from __future__ import annotations

from mcc.compiler import dialects, ir
from mcc.compiler.opt.fold import decide

NAME = "branches"
NEEDS = ()


def run(module: ir.Module, context) -> int:
    changed = 0
    blocks = {block.label: block for _, block in module.blocks()}
    order = {label: index for index, label in enumerate(blocks)}
    target = context.profile.dialect if context.profile is not None else module.dialect
    thread = dialects.get(target).writes_jumps  # a target that rebuilds structure keeps its shape
    for _, block in module.blocks():
        term = block.terminator
        if isinstance(term, ir.Branch):
            verdict = decide(term.cond)
            if verdict is not None:
                block.terminator = ir.Jump(term.then if verdict else term.otherwise, term.span)
                changed += 1
            elif term.then == term.otherwise:
                block.terminator = ir.Jump(term.then, term.span)
                changed += 1
        for target in ir.successors(block.terminator) if thread else ():
            final = through(target, blocks)
            if final != target and order.get(final, -1) > order[block.label] and order[target] > order[block.label]:
                ir.retarget(block.terminator, target, final)
                changed += 1
    return changed


def through(label: str, blocks: dict[str, ir.Block]) -> str:
    """Follow empty unnamed blocks that only jump, stopping at a cycle."""
    seen = {label}
    block = blocks.get(label)
    while block is not None and not block.ops and not block.named and isinstance(block.terminator, ir.Jump):
        nxt = block.terminator.target
        if nxt in seen:
            break
        seen.add(nxt)
        label, block = nxt, blocks.get(nxt)
    return label
