"""Copy propagation (within each block).

What it does: after `A = B`, the operations that follow in the same block read `B` where they
read `A`, until either is assigned again (`A = B` then `MA A` becomes `MA B`). Together with
`dead_stores` this removes temporaries the source needed only to pass a value along.

Why it is safe: `A` and `B` hold the same value until one of them is assigned; a call or a
native command may assign anything, so every copy is forgotten there, and variables an event
handler assigns are never propagated. Only integer variables are propagated, by the type the
lowering declares for every variable and register: a copy into a variable of another type converts
the value (MCode `RV=F3` drops the fraction, L2813, where `MA F3` rounds down, L2815), so it is
not a copy. The copy itself stays.

Needs: nothing beyond the block.
"""

from __future__ import annotations

from mcc.compiler import ir
from mcc.compiler.opt.common import clobbers_everything, handler_writes
from mcc.compiler.opt.fold import integer as is_integer, rewrite_op

NAME = "copies"
NEEDS = ()


def run(module: ir.Module, context) -> int:
    volatile, _ = handler_writes(module)

    def integer(name: str) -> bool:
        return is_integer(module, name)

    changed = 0
    for _, block in module.blocks():
        copies: dict[str, ir.Var] = {}
        for index, op in enumerate(block.ops):
            if copies:
                new = substitute(op, copies)
                if new is not op:
                    block.ops[index] = op = new
                    changed += 1
            if clobbers_everything(op):
                copies.clear()
            elif isinstance(op, ir.Assign):
                name = op.target.name
                copies = {k: v for k, v in copies.items() if k != name and v.name != name}
                value = op.value
                if isinstance(value, ir.Var) and value.name != name and name not in volatile \
                        and value.name not in volatile and integer(name) and integer(value.name):
                    copies[name] = value
        if copies and isinstance(block.terminator, ir.Branch):
            cond = replace_in_cond(block.terminator.cond, copies)
            if cond is not block.terminator.cond:
                block.terminator.cond = cond
                changed += 1
    return changed


def substitute(op, copies: dict[str, ir.Var]):
    """`op` reading the copies' sources (the folder's rewriting, with variables for values)."""
    return rewrite_op(op, copies)


def replace_in_cond(cond, copies):
    if isinstance(cond, ir.Compare):
        left, right = _swap(cond.left, copies), _swap(cond.right, copies)
        if left is cond.left and right is cond.right:
            return cond
        return ir.Compare(cond.op, left, right, cond.span)
    return cond


def _swap(expr, copies):
    if isinstance(expr, ir.Var) and expr.name in copies:
        return ir.Var(copies[expr.name].name, expr.span)
    return expr
