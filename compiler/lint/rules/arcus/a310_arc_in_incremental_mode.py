r"""# A310 arc-in-incremental-mode

`ARC` or `CIR` runs while `INC` (incremental mode) may be in force.

- kind: lint
- default severity: warning
- dialects: arcus
- fix available: no
- manual: L582-L598, L1831-L1866, L2284-L2300

## What it means

The centre of `CIR` and `ARC` is "the X,Y position of the circle center" (L586, L1860); whether it
is read as absolute or relative to the current position in incremental mode is not documented.
Switch to `ABS` before circular moves so the centre means the same on every controller.

## Bad

```
HSPD=20000
LSPD=500
ACC=300
INC
CIRP0:100
WAITX
END
```

## Good

```
HSPD=20000
LSPD=500
ACC=300
ABS
CIRP0:100
WAITX
END
```
"""

from __future__ import annotations

from mcc.compiler import ir
from mcc.compiler.lint import flow
from mcc.compiler.lint.rules import Context, rule


@rule
def arc_in_incremental_mode(ctx: Context) -> None:
    """The lowering resolves ABS/INC into the moves and keeps the modes possible at each arc."""
    arc_modes = getattr(ctx.tree, "arc_modes", {})
    for _, _, item in flow.ops(ctx.module, ir.Arc):
        if item.span is not None and "INC" in arc_modes.get((item.span.line, item.span.column), ()):
            ctx.report(item.span, "ARC/CIR while INC may be in force: whether the centre is then relative is "
                                  "not documented (L586); write ABS before it")
