r"""# A304 speed-change-with-s-curve

`SSPD` changes the speed on the fly on an axis whose S-curve profile is on.

- kind: lint
- default severity: error
- dialects: arcus
- fix available: no
- manual: L512, L2420-L2465

## What it means

"If s-curve is enabled for an axis, on-the-fly speed feature can not be used for the corresponding
axis" (L2432, L2455; also L512). After `SCV[axis]=1` an `SSPD[axis]` is not executed as intended.
Switch the axis back to trapezoidal (`SCV[axis]=0`) before changing its speed on the fly.

## Bad

```
SCVX=1
SSPDMX=2
SSPDX=90000
END
```

## Good

```
SCVX=0
SSPDMX=2
SSPDX=90000
END
```
"""

from __future__ import annotations

from mcc.compiler.lint.rules import Context, rule
from mcc.compiler.lint.rules.arcus.helpers import forward_all, keyword, keywords_in, switch_state


@rule
def speed_change_with_s_curve(ctx: Context) -> None:
    if not {"SCV", "SSPD"} <= keywords_in(ctx.module):  # an S-curve switched on, and a speed change
        return
    transfer = switch_state("SCV", None)
    for _, item, on in forward_all(ctx.module, transfer):
        name, axis = keyword(item)
        if name == "SSPD" and axis in on:
            ctx.report(item.span, f"S-curve is on for axis {axis} (SCV{axis}=1): on-the-fly speed change cannot be "
                                  f"used on it (L2432); set SCV{axis}=0 first")
