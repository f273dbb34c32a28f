r"""# M312 missing-return

A subroutine, trip or OE handler has a path that does not end with `RT`.

- kind: lint
- default severity: warning
- dialects: mcode
- fix available: no
- manual: L2115-L2121, L4538-L4549, L8329-L8336

## What it means

"The subroutine must end with an RT" (L2115-L2121); the same holds for trip handlers and the
`OE` handler ("an RT must be inserted at the end of the subroutine", L4542). A path that reaches
`E` ends the whole program with the return address still on the stack (the manual's own OE sample
does this, L8329-L8336); a path that runs past the last line, or on into the next subroutine's
label, executes code that was never meant to run.

## Bad

```
PG 1
LB G1
  CL K1
  E
LB K1
  MA 1000
  H
  E
PG
```

## Good

```
PG 1
LB G1
  CL K1
  E
LB K1
  MA 1000
  H
  RT
PG
```
"""

from __future__ import annotations

from mcc.compiler import ir
from mcc.compiler.lint import flow
from mcc.compiler.lint.rules import Context, rule
from mcc.compiler.lint.rules.mcode.helpers import SUBROUTINE_KINDS, line_of


@rule
def missing_return(ctx: Context) -> None:
    index = flow.block_index(ctx.module)
    for routine in ctx.module.routines:
        if routine.kind not in SUBROUTINE_KINDS:
            continue
        what = "handler" if routine.kind is ir.RoutineKind.HANDLER else "subroutine"
        for block in flow.reachable(routine):
            term = block.terminator
            if isinstance(term, ir.End):
                ctx.report(term.span, f"E ends the whole program inside the {what} {routine.name}, with its return "
                                      "address still on the stack: end it with RT")
            elif isinstance(term, ir.FallOff):
                ctx.report(term.span or routine.span,
                           f"the {what} {routine.name} runs past its last line without RT: add RT")
            elif isinstance(term, ir.Jump) and term.target in index and index[term.target][0] is not routine \
                    and flow.is_fallthrough(term, index[term.target][1]):
                ctx.report(routine.span, f"the {what} {routine.name} runs on into {term.target} (line "
                                         f"{line_of(term.span)}) without RT: add RT before that label")
