r"""# A312 output-used-by-sync

A digital output is set while the axis's synchronisation output drives it.

- kind: lint
- default severity: warning
- dialects: arcus
- fix available: no
- manual: L756-L787, L2537-L2567

## What it means

Each axis has a synchronisation output on a fixed digital output: X on DO1, Y on DO2, Z on DO3, U
on DO4. "While feature is enabled for an axis, the corresponding digital output can not be
controlled by user" (L756-L765): after `SYN[axis]O` and before `SYN[axis]F`, writing that output
(or `DO`, all of them) has no effect on it.

## Bad

```
SYNXO
DO1=1
END
```

## Good

```
SYNXO
DO5=1
SYNXF
DO1=1
END
```
"""

from __future__ import annotations

from mcc.compiler import ir
from mcc.compiler.lint.rules import Context, rule
from mcc.compiler.lint.rules.arcus.helpers import forward_all, keywords_in, switch_state

AXES = ("X", "Y", "Z", "U")  # SYNXO drives DO1, SYNYO DO2, ... (L756-L787)


@rule
def output_used_by_sync(ctx: Context) -> None:
    if "SYNO" not in keywords_in(ctx.module):  # no synchronisation output switched on
        return
    transfer = switch_state("SYNO", None)
    for _, item, on in forward_all(ctx.module, transfer):
        if not isinstance(item, ir.SetOutput) or not on:
            continue
        outputs = {AXES.index(axis) + 1: axis for axis in on if axis in AXES}
        hit = sorted(outputs) if item.index is None else [item.index] if item.index in outputs else []
        for index in hit:
            ctx.report(item.span, f"DO{index} is driven by the synchronisation output of axis {outputs[index]} "
                                  f"(SYN{outputs[index]}O): it cannot be set until SYN{outputs[index]}F (L765)")
