"""Unreachable blocks and subroutines never called.

What it does: a block no path reaches from its routine's entry (code after an END, a loop
nothing enters) is removed; at -O2, a subroutine nothing calls is removed where the source dialect
reaches subroutines only through the program's own calls (Arcus: GOSUB, and SUB 31 on an error).

Why it is safe: no run can execute code no path reaches. Blocks the source named are kept (a
host may run an MCode label with EX), as is the entry of every routine and any block named as a
value (an MCode trip's label). MCode labels and X150 sequences can be started by a host, so their
routines are never removed.

An X150 sequence that leaves with XG inside an IF or a loop keeps that construct open on the
controller (the next sequence must close it, L1794); the code after such an XG is part of how the
constructs nest, so routines of X150 programs that end a path with XG are left as written.

Needs: the call graph and the CFG's edges (computed here).
"""

from __future__ import annotations

from mcc.compiler import dialects, ir
from mcc.compiler.opt.common import reached, referenced_labels

NAME = "unreachable"
NEEDS = ()


def run(module: ir.Module, context) -> int:
    removed = blocks(module)
    # routines of a dialect whose routines only the program's own calls reach (an Arcus SUB runs
    # only by GOSUB): a host cannot start one (MCode EX, X150 XR), so an uncalled one is dead
    if context.global_scope and dialects.get(module.dialect).private_routines:
        removed += routines(module)
    return removed


def blocks(module: ir.Module) -> int:
    """Remove unreachable unnamed blocks; returns the operations removed."""
    keep_always = referenced_labels(module)
    targets_from_elsewhere: set[str] = set()
    for routine in module.routines:
        own = {b.label for b in routine.blocks}
        for block in routine.blocks:
            targets_from_elsewhere |= {t for t in ir.successors(block.terminator) if t not in own}
    removed = 0
    for routine in module.routines:
        if not routine.blocks or dialects.get(module.dialect).keeps_code_after_transfer and any(
                isinstance(b.terminator, ir.GotoRoutine) for b in routine.blocks):
            continue
        roots = [routine.blocks[0].label] + [b.label for b in routine.blocks if b.named or b.label in keep_always
                                             or b.label in targets_from_elsewhere]
        seen = reached({b.label: b for b in routine.blocks}, roots)
        dead = [b for b in routine.blocks if b.label not in seen]
        removed += sum(len(b.ops) for b in dead)
        routine.blocks[:] = [b for b in routine.blocks if b.label in seen]
    return removed


def routines(module: ir.Module) -> int:
    called: set[str] = set()
    stack = [r.name for r in module.routines if r.kind is not ir.RoutineKind.SUBROUTINE or r.number == 31]
    by_name = {r.name: r for r in module.routines}
    while stack:
        name = stack.pop()
        if name in called or name not in by_name:
            continue
        called.add(name)
        for block in by_name[name].blocks:
            for op in block.ops:
                if isinstance(op, ir.Call):
                    stack.append(op.routine)
                elif isinstance(op, ir.SetHandler) and op.routine:
                    stack.append(op.routine)
            if isinstance(block.terminator, ir.GotoRoutine):
                stack.append(block.terminator.routine)
    dead = [r for r in module.routines if r.name not in called]
    removed = sum(len(b.ops) for r in dead for b in r.blocks)
    module.routines[:] = [r for r in module.routines if r.name in called]
    return removed
