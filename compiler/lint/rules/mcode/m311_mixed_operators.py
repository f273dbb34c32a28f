r"""# M311 mixed-operators

An expression mixes different operators, whose precedence the manual does not define.

- kind: lint
- default severity: warning
- dialects: mcode
- fix available: no
- manual: L1251-L1279, L6277-L6360

## What it means

The manual documents each operator with two operands (`+` may be chained, L6292) and never says
how `R1=R2+R3*2` is evaluated: no example mixes two operators (Table 4.5, L1251-L1279). mcc reads
such expressions left to right, as the firmware family does, but another reader (or firmware) may
apply `*` first. Split the computation so each statement has one kind of operator.

## Bad

```
PG 1
LB G1
  R1=R2+R3*2
  E
PG
```

## Good

```
PG 1
LB G1
  R1=R3*2
  R1=R1+R2
  E
PG
```
"""

from __future__ import annotations

from mcc.compiler import ir
from mcc.compiler.lint.rules import Context, rule


def operators(expr) -> set[str]:
    """The binary operators of one arithmetic expression (a comparison's sides are separate)."""
    found: set[str] = set()
    stack = [expr]
    while stack:
        node = stack.pop()
        if isinstance(node, ir.BinOp):
            found.add(node.op)
            stack += [node.left, node.right]
        elif isinstance(node, ir.UnOp):
            stack.append(node.operand)
        elif isinstance(node, ir.Func):
            stack += list(node.args)
    return found


def expressions(item):
    """The arithmetic expressions of an operation or terminator, with comparisons split in two."""
    exprs = ir.term_exprs(item) if isinstance(item, ir.Branch) else ir.op_exprs(item)
    for expr in exprs:
        if isinstance(expr, ir.Compare):
            yield from (expr.left, expr.right)
        elif isinstance(expr, ir.Truth):
            yield expr.expr
        elif isinstance(expr, ir.Logic | ir.Not | ir.InputMatch):
            continue
        else:
            yield expr


@rule
def mixed_operators(ctx: Context) -> None:
    for _, block in ctx.module.blocks():
        for item in [*block.ops, block.terminator]:
            for expr in expressions(item):
                ops = operators(expr)
                if len(ops) > 1:
                    ctx.report(expr.span or item.span,
                               f"this expression mixes {' and '.join(sorted(ops))}, and the manual defines no "
                               "precedence (mcc evaluates left to right): split it into one operation per statement")
