r"""# M305 unused-label

A label is defined with `LB` but nothing branches to it, calls it or runs it.

- kind: lint
- default severity: warning
- dialects: mcode
- fix available: yes
- manual: L537, L3755-L3773

## What it means

Labels share the device's table of 192 names with the user variables (L537, L3759); a label
nothing refers to uses an entry and suggests a `BR` or `CL` that was lost or misspelt. Labels at
the start of a program (`PG <address>` followed by `LB`) and `SU` are exempt: they are started
from outside, with `EX` or at power-up. So is a label that nothing in the file reaches (one after
`E`, `RT` or `BR` that no `BR`, `CL`, `EX` or trip names): that is how a host starts a part of the
program (`EX <label>`), an entry point of its own. The fix deletes the line; it is unsafe because a
host may still run the label with `EX`.

## Bad

```
PG 1
LB G1
  MA 1000
  H
LB G2
  E
PG
```

## Good

```
PG 1
LB G1
  MA 1000
  H
  E
PG
```
"""

from __future__ import annotations

from mcc.compiler.diagnostics import Fix
from mcc.compiler.lint import flow
from mcc.compiler.lint.edits import delete_line
from mcc.compiler.lint.rules import Context, rule


@rule
def unused_label(ctx: Context) -> None:
    labels = ctx.analysis.symbols.labels  # references: BR (not a fall-through), CL, EX, trips, OE

    def used(name: str) -> bool:
        return name in labels and labels[name].used

    for routine in ctx.module.routines:
        # a label nothing reaches (after RT, E or BR) is how the host starts a part of the program
        # (EX <label>): deleting it would cut that part off, so it is not reported (issue 24)
        starts = flow.entry_points(routine, used)
        for block in routine.blocks:
            if not block.named or used(block.label) or block.label == "SU" or block.label in starts:
                continue
            if routine.origin is not None and block is routine.entry:
                continue  # a program start: run with EX <label> or EX <address>
            fix = Fix("delete the label", (delete_line(ctx.source, block.span.line),), safe=False)
            ctx.report(block.span, f"label {block.label} is never the target of BR, CL, EX or a trip: remove it "
                                   "or branch to it", fix=fix)
