r"""# M310 declaration-in-loop

`VA` inside a loop declares the variable again on every pass.

- kind: lint
- default severity: warning
- dialects: mcode
- fix available: no
- manual: L555, L7996-L8000, L8472

## What it means

A variable declared inside a program is local: it is "erased and declared again each time a
program is executed" (L555). Inside a loop the declaration runs on every pass; the manual's own
sample does this (L7998) and whether a second declaration is accepted or raises Error 28 (name
already defined, L8472) is not documented. Declare the variable once, before the loop, or
globally outside `PG`.

## Bad

```
PG 1
LB G1
  VA K5
  K5=P/2
  PR K5
  BR G1
PG
```

## Good

```
PG 1
  VA K5
LB G1
  K5=P/2
  PR K5
  BR G1
PG
```
"""

from __future__ import annotations

from mcc.compiler import ir
from mcc.compiler.lint import flow
from mcc.compiler.lint.rules import Context, rule


@rule
def declaration_in_loop(ctx: Context) -> None:
    for routine in ctx.module.routines:
        looping = flow.in_loops(routine)
        for block in routine.blocks:
            if block.label not in looping:
                continue
            for op in block.ops:
                if isinstance(op, ir.Native) and op.mnemonic == "VA":
                    name = op.args[0].name if op.args and isinstance(op.args[0], ir.Var) else "?"
                    ctx.report(op.span, f"VA {name} is inside a loop and runs on every pass: declare it once, "
                                        "before the loop")
