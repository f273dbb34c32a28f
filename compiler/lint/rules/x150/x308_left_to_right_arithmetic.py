r"""# X308 left-to-right-arithmetic

A variable expression puts `*` or `/` after `+` or `-`: X150 evaluates strictly left to right.

- kind: lint
- default severity: warning
- dialects: x150
- fix available: no
- manual: L4569-L4643

## What it means

"The mathematical operations are evaluated in order from left to right along the command line":
`VAR4=VAR1-VAR2*VAR3` is `(VAR1-VAR2)*VAR3`, not `VAR1-(VAR2*VAR3)` (L4638-L4642). Written that way
the line reads as the usual precedence and computes something else. Reorder it (`VAR4=VAR2*VAR3`
then `VAR4=VAR1-VAR4`) so that it means what it looks like.

## Bad

```
1VAR4=VAR1-VAR2*VAR3
```

## Good

```
1VAR4=VAR2*VAR3
1VAR4=VAR1-VAR4
```
"""

from __future__ import annotations

from mcc.compiler.lint.rules import Context, rule
from mcc.compiler.x150 import syntax as st


@rule
def left_to_right_arithmetic(ctx: Context) -> None:
    for command in ctx.tree.commands():
        statement = command.arg
        if not isinstance(statement, st.VarStatement) or statement.value is None:
            continue
        ops = [op for op, _ in statement.value.rest]
        additive = False
        for op in ops:
            if op in "+-":
                additive = True
            elif op in "*/" and additive:
                ctx.report(statement.value.span, f"X150 evaluates left to right: this {op} applies to everything "
                                                 "before it, not only to the operand before it (L4638-L4642)")
                break
