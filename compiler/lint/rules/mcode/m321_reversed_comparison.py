r"""# M321 reversed-comparison

`=<` is written for `<=`.

- kind: lint
- default severity: warning
- dialects: mcode
- fix available: yes
- manual: L1256-L1261, L3314

## What it means

The comparison operators are `=`, `<>`, `<`, `<=`, `>` and `>=` (Table 4.5, L1256-L1261). The
manual once writes `I5=<2048` (L3314), a typo for `<=` that mcc accepts; other tools and readers
may not. The fix (safe) writes `<=`.

## Bad

```
PG 1
LB G1
  BR G1,I5=<2048
  E
PG
```

## Good

```
PG 1
LB G1
  BR G1,I5<=2048
  E
PG
```
"""

from __future__ import annotations

from mcc.compiler.diagnostics import Edit, Fix
from mcc.compiler.lint.rules import Context, rule
from mcc.compiler.mcode import syntax as st


@rule
def reversed_comparison(ctx: Context) -> None:
    text = ctx.source.text
    for stmt in ctx.tree.statements():
        for arg in stmt.args:
            if isinstance(arg, st.Comparison) and arg.op == "=<":
                start = text.find("=<", arg.left.span.end, arg.right.span.start)
                if start < 0:
                    continue
                span = ctx.source.span(start, start + 2)
                ctx.report(span, "`=<` is not an MCode operator: write `<=` (L1259)",
                           fix=Fix("write <=", (Edit(span, "<="),)))
