r"""# M113 vi-not-below-vm

The initial velocity VI is not below the maximum velocity VM.

- kind: semantic
- default severity: error
- dialects: mcode
- fix available: no
- manual: L669, L676, L8466-L8467

## What it means

VI must be less than VM; the device refuses the setting with Error 22 (VI) or 23 (VM) and keeps
the previous value. mcc follows constant settings in file order, starting from the defaults.

## Bad

```
VM=100000
VI=200000
```

## Good

```
VI=20000
VM=100000
```
"""

from __future__ import annotations

from mcc.compiler import ir
from mcc.compiler.checks import Context, check


def constant(expr) -> int | float | None:
    return expr.value if isinstance(expr, ir.Const) else None


@check()
def vi_not_below_vm(ctx: Context) -> None:
    """VI must stay below VM where both are constants (device Errors 22/23), in file order; a
    setting that is not a constant leaves the pair unknown until the next constant one."""
    vi = ctx.lowering.cat.lookup("VI")
    vm = ctx.lowering.cat.lookup("VM")
    current = {ir.MotionParam.INITIAL_SPEED: (vi.entry.default if vi else 1000, None),
               ir.MotionParam.MAX_SPEED: (vm.entry.default if vm else 768000, None)}
    for _, block in ctx.program.module.blocks():
        for op in block.ops:
            if not isinstance(op, ir.SetMotion) or op.param not in current:
                continue
            value = constant(op.value)
            current[op.param] = (value, op)
            low, low_op = current[ir.MotionParam.INITIAL_SPEED]
            high, high_op = current[ir.MotionParam.MAX_SPEED]
            if low is None or high is None or low < high:
                continue
            other = high_op if op.param is ir.MotionParam.INITIAL_SPEED else low_op
            where = f" (set at line {other.span.line})" if other is not None and other.span else " (the default)"
            ctx.report(op.span, f"VI={low} is not below VM={high}{where}: the device refuses it (Error 22/23); VI "
                                "must be less than VM")
