r"""# X310 move-while-disabled

A move is commanded while the drive is shut down (`ST1` or `OFF`).

- kind: lint
- default severity: warning
- dialects: x150
- fix available: no
- manual: L4015-L4027, L2796-L2811

## What it means

"Any move commands given during motor shutdown will not be executed. ST0 re-enables all move
commands" (L4019-L4027). `OFF` de-energises the drive (and kills the buffer) until `ON` (L2796-L2811).
A `G` after `ST1` or `OFF` on some path, with no `ST0`/`ON` in between, is silently ignored.

## Bad

```
1XE2
1XD2
1A10
1V5
1ST1
1D1000
1G
1XT
```

## Good

```
1XE2
1XD2
1A10
1V5
1ST1
1T5
1ST0
1D1000
1G
1XT
```
"""

from __future__ import annotations

from mcc.compiler import ir
from mcc.compiler.lint.rules import Context, rule
from mcc.compiler.lint.rules.x150.helpers import any_op, const, forward_all, is_go, native


@rule
def move_while_disabled(ctx: Context) -> None:
    if not any_op(ctx.module, lambda op: isinstance(op, ir.DriveEnable) or native(op, "ST") or native(op, "OFF")):
        return  # the drive is never shut down

    def transfer(off: frozenset, item) -> frozenset:
        if isinstance(item, ir.DriveEnable):  # ST0 / ST1 (the lowering's neutral form)
            on = const(item.on)
            return off | {(item.axis, "ST1")} if on != 1 else frozenset(f for f in off if f[1] != "ST1")
        if native(item, "ST"):
            value = const(item.args[0]) if item.args else None
            return off | {(item.axis, "ST1")} if value != 0 else frozenset(f for f in off if f[1] != "ST1")
        if native(item, "OFF"):
            return off | {(item.axis, "OFF")}
        if native(item, "ON"):
            return frozenset(f for f in off if f[1] != "OFF")
        return off

    for _, item, off in forward_all(ctx.module, transfer):
        if is_go(item) and off:
            why = sorted({f[1] for f in off})
            ctx.report(item.span, f"the drive may be shut down here ({' / '.join(why)}): this move is ignored until "
                                  "ST0 / ON (L4025)")
