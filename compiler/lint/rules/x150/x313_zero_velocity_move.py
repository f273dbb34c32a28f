r"""# X313 zero-velocity-move

`V0` before a move means the fastest possible velocity, not a standstill.

- kind: lint
- default severity: warning
- dialects: x150
- fix available: no
- manual: L4541-L4550

## What it means

"If the command V0 is given when moving in MQ or MC the motor will stop as with the S command. If
the motor is not moving, the fastest possible velocity is used for the move" (L4547). A `V0`
followed by a `G` runs at the motor's top speed, which can exceed the position error limit and shut
the drive down (same line). Use `S` or `SB` to stop, and a real velocity to move.

## Bad

```
1XE8
1XD8
1A10
1V0
1D1000
1G
1XT
```

## Good

```
1XE8
1XD8
1A10
1V2
1D1000
1G
1XT
```
"""

from __future__ import annotations

from mcc.compiler import ir
from mcc.compiler.lint.rules import Context, rule
from mcc.compiler.lint.rules.x150.helpers import any_op, axis_of, const, forward_all, is_go


@rule
def zero_velocity_move(ctx: Context) -> None:
    if not any_op(ctx.module, lambda op: isinstance(op, ir.SetMotion) and op.param is ir.MotionParam.MAX_SPEED
                  and const(op.value) == 0):
        return  # V0 is never set

    def transfer(zero: frozenset, item) -> frozenset:
        if isinstance(item, ir.SetMotion) and item.param is ir.MotionParam.MAX_SPEED:
            return zero | {item.axis} if const(item.value) == 0 else zero - {item.axis}
        return zero

    for _, item, zero in forward_all(ctx.module, transfer):
        if is_go(item) and (axis_of(item) in zero or ir.ALL_AXES in zero):
            ctx.report(item.span, "V0 is in force: with the motor at rest this G runs at the fastest possible "
                                  "velocity (L4547); set a real V")
