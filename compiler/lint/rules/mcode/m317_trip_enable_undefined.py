r"""# M317 trip-enable-undefined

`TE` enables a trip this file never defines.

- kind: lint
- default severity: error
- dialects: mcode
- fix available: no
- manual: L5657-L5696, L8471

## What it means

"A trip must be defined prior to being enabled. Enabling an undefined trip will throw an Error 27:
Trip not defined" (L5678). Each bit of `TE` is one trip (1 `TI`, 2 `TP`, 4 `TC`, 8 `TT`, 16 `TR`,
32 `TA`, 64 `TM`); the rule checks constant `TE` values against the trips the file defines.

## Bad

```
PG 1
LB G1
  TI 1,X1
  TE=3
  E
LB X1
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
  TE=1
  RT
PG
```
"""

from __future__ import annotations

from mcc.compiler.lint.rules import Context, rule
from mcc.compiler.lint.rules.mcode.helpers import catalog, te_writes, trip_bit
from mcc.compiler.mcode.lower import TRIP_EVENTS


def defined_trip_bits(ctx: Context) -> int:
    """Trips the file defines, read from the syntax tree: a definition the frontend rejected (an
    undeclared variable in TP=Ds*3,X2) is still a definition, and is already reported."""
    bits = 0
    for stmt in ctx.tree.statements():
        command = catalog().lookup(stmt.head.key)
        if command is not None:
            bits |= int(command.entry.get("trip_bit", 0)) if command.ir == "trip" else 0
    return bits


@rule
def trip_enable_undefined(ctx: Context) -> None:
    defined = defined_trip_bits(ctx)
    for _, _, op, value in te_writes(ctx.module):
        if value is None or not isinstance(value, int):
            continue
        missing = value & ~defined & 127
        if missing:
            names = [f"{bit} ({mnemonic})" for mnemonic, bit in trip_bits_table() if missing & bit]
            ctx.report(op.span, f"TE={value} enables trip{'s' if len(names) > 1 else ''} {', '.join(names)} that "
                                "this file never defines: the device answers Error 27 (L5678)")


def trip_bits_table() -> list[tuple[str, int]]:
    return [(name, trip_bit(event)) for name, event in TRIP_EVENTS.items()]
