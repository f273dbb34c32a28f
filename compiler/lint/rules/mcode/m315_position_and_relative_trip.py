r"""# M315 position-and-relative-trip

A program defines both a position trip (`TP`) and a relative trip (`TR`).

- kind: lint
- default severity: error
- dialects: mcode
- fix available: no
- manual: L5828-L5853, L8484

## What it means

"Trip on Position and Trip on Relative distance not allowed together": the device answers Error 39
(L8484, L5836). Use one kind of position trip; a relative trip with a repeat count covers evenly
spaced positions.

## Bad

```
PG 1
LB G1
  TP=51200,X1
  TR=1000,X1,5
  TE=18
  MA 102400
  H
  E
LB X1
  TE=18
  RT
PG
```

## Good

```
PG 1
LB G1
  TR=1000,X1,5
  TE=16
  MA 102400
  H
  E
LB X1
  RT
PG
```
"""

from __future__ import annotations

from mcc.compiler import ir
from mcc.compiler.lint.rules import Context, rule
from mcc.compiler.lint.rules.mcode.helpers import EVENT_TRIP, handlers, line_of


@rule
def position_and_relative_trip(ctx: Context) -> None:
    seen: dict[str, ir.SetHandler] = {}
    for op in handlers(ctx.module):
        if op.event in ("position", "relative"):
            other = seen.get("relative" if op.event == "position" else "position")
            if other is not None:
                ctx.report(op.span, f"{EVENT_TRIP[op.event]} and {EVENT_TRIP[other.event]} (line "
                                    f"{line_of(other.span)}) cannot be used together: the device answers Error 39")
            seen.setdefault(op.event, op)
