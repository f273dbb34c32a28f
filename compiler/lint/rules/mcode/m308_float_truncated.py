r"""# M308 float-truncated

A floating point register (F1-F8) is assigned to an integer variable: the fraction is dropped.

- kind: lint
- default severity: warning
- dialects: mcode
- fix available: no
- manual: L2808-L2816, L580, L1249

## What it means

Only the floating point registers F1-F8 hold fractions. "When transferred to a user variable or
an integer register R1 – R4, the fraction portion of the floating point number is discarded"
(L2812); all factory variables are integers as well. `R1=F1` with F1 = 2.75 gives 2, silently.
Keep the computation in F registers until the last step, and round on purpose (`F1=F1+0.5` before
the transfer) when rounding is what you want.

## Bad

```
PG 1
LB G1
  F1=SQ 2
  R1=F1*100
  E
PG
```

## Good

```
PG 1
LB G1
  F1=SQ 2
  F2=F1*100
  PR F2
  E
PG
```
"""

from __future__ import annotations

from mcc.compiler import ir
from mcc.compiler.lint import flow
from mcc.compiler.lint.rules import Context, rule


@rule
def float_truncated(ctx: Context) -> None:
    for _, _, op in flow.ops(ctx.module, (ir.Assign, ir.SetMotion)):
        target = op.target.name if isinstance(op, ir.Assign) else None
        # the module's types, not the Lexium catalog's: on an MDrivePlus (profile mdrive-plus) F1 is a
        # user variable like any other (docs/dialects/mcode.md)
        if target is not None and ctx.module.type_of(target) is ir.VarType.FLOAT64:
            continue
        floats = sorted({n.name for n in ir.walk_expr(op.value)
                         if isinstance(n, ir.Var) and ctx.module.type_of(n.name) is ir.VarType.FLOAT64})
        if floats:
            what = target or "the setting"
            ctx.report(op.span, f"{', '.join(floats)} {'is a' if len(floats) == 1 else 'are'} floating point; "
                                f"{what} holds integers, so the fraction is discarded (L2812)")
