r"""# X311 repeated-absolute-move

In absolute mode (`MPA`) a second `G` without a new `D` does not move.

- kind: lint
- default severity: warning
- dialects: x150
- fix available: no
- manual: L2560-L2573

## What it means

"In the absolute mode, giving two G (go) commands in succession, without changing the value of D
(distance) will cause the motor to move only once as the motor will have achieved the desired
absolute position" (L2572). Set a new `D` before each `G`, or use incremental mode (`MPI`) to repeat
a distance.

## Bad

```
1XE4
1XD4
1MN
1MPA
1A10
1V5
1D8000
1G
1T1
1G
1XT
```

## Good

```
1XE4
1XD4
1MN
1MPA
1A10
1V5
1D8000
1G
1T1
1D0
1G
1XT
```
"""

from __future__ import annotations

from mcc.compiler import ir
from mcc.compiler.lint.rules import Context, rule
from mcc.compiler.lint.rules.x150.helpers import any_op, axis_of, forward_all, native


@rule
def repeated_absolute_move(ctx: Context) -> None:
    if not any_op(ctx.module, lambda op: isinstance(op, ir.Move) and op.mode is ir.MoveMode.ABSOLUTE):
        return  # no absolute move: nothing is reached

    def target(item) -> tuple:
        value = item.targets[0][1] if item.targets else None
        return (axis_of(item), value.value if isinstance(value, ir.Const) else getattr(value, "name", None))

    def transfer(reached: frozenset, item) -> frozenset:
        if isinstance(item, ir.Move):
            axis = axis_of(item)
            kept = frozenset(r for r in reached if r[0] != axis)
            return kept | {target(item)} if item.mode is ir.MoveMode.ABSOLUTE else kept
        if isinstance(item, ir.Assign) and item.target.name.startswith("%D"):
            return frozenset(r for r in reached if r[0] != item.target.name[2:])
        if isinstance(item, (ir.Call, ir.Home, ir.SetPosition, ir.Slew)) or native(item, "SP", "PZ", "G"):
            return frozenset()
        return reached

    # Since the lowering resolves D by data flow, a G that repeats the last absolute target (the
    # register unchanged, or set again to the same value) has the same Move target as the last one.
    for _, item, reached in forward_all(ctx.module, transfer):
        if isinstance(item, ir.Move) and item.mode is ir.MoveMode.ABSOLUTE and target(item) in reached:
            ctx.report(item.span, "in absolute mode (MPA) this G goes to the position the last G already reached: "
                                  "set a new D first (L2572)")
