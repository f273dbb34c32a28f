r"""# M322 trip-never-enabled

A trip is defined, but `TE` never enables it.

- kind: lint
- default severity: warning
- dialects: mcode
- fix available: no
- manual: L5657-L5696, L8110-L8116

## What it means

Defining a trip (`TI`, `TP`, `TC`, `TT`, `TR`, `TA`, `TM`) only names its handler; "Trip must be
enabled using Te=<num> following the trip definition" (L8111). Without the trip's bit in `TE` the
handler never runs.

## Bad

```
PG 1
LB G1
  TI 1,X1
  E
LB X1
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
  TE=1
  RT
PG
```
"""

from __future__ import annotations

from mcc.compiler.lint.rules import Context, rule
from mcc.compiler.lint.rules.mcode.helpers import EVENT_TRIP, handlers, te_writes, trip_bit


@rule
def trip_never_enabled(ctx: Context) -> None:
    enabled = 0
    for _, _, _, value in te_writes(ctx.module):
        enabled |= 127 if value is None or not isinstance(value, int) else value
    for op in handlers(ctx.module):
        bit = trip_bit(op.event)
        if bit and not enabled & bit:
            ctx.report(op.span, f"the {EVENT_TRIP[op.event]} trip is defined but never enabled: add `TE={bit}` "
                                "after the definition (L8111)")
