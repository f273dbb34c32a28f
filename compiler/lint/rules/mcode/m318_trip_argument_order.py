r"""# M318 trip-argument-order

`TA` is written with the event bits before the label.

- kind: lint
- default severity: warning
- dialects: mcode
- fix available: yes
- manual: L5560-L5588

## What it means

The syntax of the hMT trip is `TA=<label/address>,<bits>` (L5583), but the manual's example writes
`TA=4, k6` (L5587). mcc reads both orders the same way; firmware that follows the syntax would
take 4 as an address. The fix (safe) swaps the two arguments into the documented order.

## Bad

```
PG 1
LB G1
  TA=4,K6
  TE=32
  E
LB K6
  TE=32
  RT
PG
```

## Good

```
PG 1
LB G1
  TA=K6,4
  TE=32
  E
LB K6
  TE=32
  RT
PG
```
"""

from __future__ import annotations

from mcc.compiler.diagnostics import Fix
from mcc.compiler.lint.edits import replace
from mcc.compiler.lint.rules import Context, rule
from mcc.compiler.mcode import syntax as st


@rule
def trip_argument_order(ctx: Context) -> None:
    for stmt in ctx.tree.statements():
        if stmt.head.key != "TA" or len(stmt.args) != 2:
            continue
        bits, label = stmt.args
        if isinstance(bits, st.Number) and isinstance(label, st.Name):
            text = ctx.source.text
            first, second = text[bits.span.start:bits.span.end], text[label.span.start:label.span.end]
            fix = Fix("put the label first", (replace(bits.span, second), replace(label.span, first)))
            ctx.report(stmt.span, f"TA takes the label first: `TA={second},{first}` (L5583)", fix=fix)
