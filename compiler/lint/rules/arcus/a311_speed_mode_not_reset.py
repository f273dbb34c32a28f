r"""# A311 speed-mode-not-reset

A normal move follows on-the-fly speed moves without `SSPDM[axis]=0` first.

- kind: lint
- default severity: warning
- dialects: arcus
- fix available: no
- manual: L514-L564, L2467-L2485

## What it means

"In order to begin normal operation after on-the-fly speed moves, it is required to first set
SSPDM to 0" (L564). A move on an axis whose `SSPDM` is still non-zero runs with the speed window
of the on-the-fly mode (L514-L533), not as set by `HSPD`/`LSPD`/`ACC`.

## Bad

```
HSPD=20000
LSPD=500
ACC=300
SSPDMX=2
X50000
SSPDX=90000
WAITX
X0
WAITX
END
```

## Good

```
HSPD=20000
LSPD=500
ACC=300
SSPDMX=2
X50000
SSPDX=90000
WAITX
SSPDMX=0
X0
WAITX
END
```
"""

from __future__ import annotations

from mcc.compiler.lint.rules import Context, rule
from mcc.compiler.lint.rules.arcus.helpers import argument, const, forward_all, keyword, keywords_in
from mcc.compiler.lint.rules.shared.helpers import motion_axes


@rule
def speed_mode_not_reset(ctx: Context) -> None:
    """The state holds ("armed", axis) after SSPDM<axis> != 0 and ("used", axis) once an SSPD ran
    in that mode; the move that SSPD changes is fine, a move after it is not."""
    if not {"SSPDM", "SSPD"} <= keywords_in(ctx.module):  # the mode armed, and a speed change in it
        return

    def transfer(state: frozenset, item) -> frozenset:
        name, axis = keyword(item)
        if name == "SSPDM":
            value = const(argument(item))
            cleared = frozenset(f for f in state if f[1] != axis)
            return cleared if value == 0 else cleared | {("armed", axis)}
        if name == "SSPD" and ("armed", axis) in state:
            return state | {("used", axis)}
        return state

    for _, item, state in forward_all(ctx.module, transfer):
        for axis in motion_axes(item):
            if ("used", axis) in state:
                ctx.report(item.span, f"SSPDM{axis} is not 0 here: set SSPDM{axis}=0 before a normal move after "
                                      "on-the-fly speed moves (L564)")
                break
