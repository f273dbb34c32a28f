r"""# A313 constant-condition

An `IF`, `ELSEIF` or `WHILE` compares two numbers, so its outcome never changes.

- kind: lint
- default severity: warning
- dialects: arcus
- fix available: no
- manual: L2038-L2061, L2259-L2280, L2645-L2649

## What it means

A condition compares two arguments (L2046-L2057, L2265, L2726); when both are numbers the branch
is always or never taken, which usually means a variable or register was meant. `WHILE 1=1`, the
manual's endless loop (L2649), is the one accepted use and is not reported.

## Bad

```
IF 1=2
DO1=1
ENDIF
END
```

## Good

```
WHILE 1=1
IF DI1=1
DO1=1
ENDIF
DELAY=10
ENDWHILE
```
"""

from __future__ import annotations

from mcc.compiler.arcus import syntax as st
from mcc.compiler.lint.rules import Context, rule


@rule
def constant_condition(ctx: Context) -> None:
    for stmt in ctx.tree.statements():
        if not isinstance(stmt, st.Conditional):
            continue
        comp = stmt.condition.first
        if isinstance(comp.left, st.Number) and isinstance(comp.right, st.Number) and not comp.chained:
            truth = compare(comp.op, comp.left.value, comp.right.value)
            if stmt.keyword == "WHILE" and truth:
                continue  # WHILE 1=1: the documented endless loop (L2649)
            outcome = "always" if truth else "never"
            ctx.report(comp.span, f"{stmt.keyword} compares two numbers: the branch is {outcome} taken")


def compare(op: str, a: int, b: int) -> bool:
    return {"=": a == b, "!=": a != b, "<": a < b, "<=": a <= b, ">": a > b, ">=": a >= b}.get(op, False)
