r"""# M302 branch-out-of-subroutine

A subroutine, trip or OE handler is left with `BR` instead of `RT`.

- kind: lint
- default severity: error
- dialects: mcode
- fix available: no
- manual: L2115-L2121, L5607, L5707, L8489

## What it means

`CL`, a trip and the `OE` error handler all push a return address; only `RT` pops it (L2115-L2121).
Leaving the routine with `BR` to a label elsewhere leaves the address on the stack: the manual
warns on every trip page that this "will cause stack errors" (L5607, L5707, L5740, L5772, L5832,
L5903), and after enough passes the device stops with Error 43 (stack overflow, L8489). Branch
back inside the routine, or end it with `RT` and let the caller branch.

Only the code the routine's own entry reaches is judged: a label after the routine's `RT` that
nothing in the file reaches (no `BR`, `CL`, `EX` or trip names it) is an entry point the host starts
with `EX` (L533, "EX K1 executes a program labeled K1"), so its `BR` leaves no return address.

## Bad

```
PG 1
LB G1
  TI 1,X1
  TE=1
LB G2
  BR G2
LB X1
  MR 1000
  H
  BR G1
PG
```

## Good

```
PG 1
LB G1
  TI 1,X1
  TE=1
LB G2
  BR G2
LB X1
  MR 1000
  H
  TE=1
  RT
PG
```
"""

from __future__ import annotations

from mcc.compiler import ir
from mcc.compiler.lint import flow
from mcc.compiler.lint.rules import Context, rule
from mcc.compiler.lint.rules.mcode.helpers import SUBROUTINE_KINDS


@rule
def branch_out_of_subroutine(ctx: Context) -> None:
    index = flow.block_index(ctx.module)
    for routine in ctx.module.routines:
        if routine.kind not in SUBROUTINE_KINDS:
            continue
        # only code the routine's own entry reaches: a label after its RT that nothing in the file
        # reaches is an entry point the host starts with EX, and leaving it with BR pushes nothing
        inside = {b.label for b in flow.reachable(routine)}
        for block, label, target, fallthrough in flow.foreign_jumps(ctx.module, routine, index):
            if fallthrough or block.label not in inside:
                continue
            what = "handler" if routine.kind is ir.RoutineKind.HANDLER else "subroutine"
            ctx.report(block.terminator.span,
                       f"BR leaves the {what} {routine.name} for {label} in {target.name}: the return address "
                       f"stays on the stack (stack errors, L5607); end the {what} with RT")
