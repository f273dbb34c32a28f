r"""# M319 second-input-trip

More than one input trip (`TI`) is defined.

- kind: lint
- default severity: warning
- dialects: mcode
- fix available: no
- manual: L8110-L8116

## What it means

The manual's trip rules: "Only a single input trip may be defined in a program" (L8114). A second
`TI` replaces the first, so only one input is watched. Watch the second input by polling it, or
branch on the input states inside one handler.

## Bad

```
PG 1
LB G1
  TI 1,X1
  TI 2,X2
  TE=1
  E
LB X1
  TE=1
  RT
LB X2
  TE=1
  RT
PG
```

## Good

```
PG 1
LB G1
  TI 1,X1
  TE=1
  E
LB X1
  CL X2,I2=1
  TE=1
  RT
LB X2
  RT
PG
```
"""

from __future__ import annotations

from mcc.compiler import ir
from mcc.compiler.lint.rules import Context, rule
from mcc.compiler.lint.rules.mcode.helpers import handlers, line_of


@rule
def second_input_trip(ctx: Context) -> None:
    first: ir.SetHandler | None = None
    for op in handlers(ctx.module):
        if op.event != "input":
            continue
        if first is None:
            first = op
        elif (op.routine, op.args) != (first.routine, first.args):
            ctx.report(op.span, f"a second input trip: only one may be defined (L8114), this one replaces TI at "
                                f"line {line_of(first.span)}")
