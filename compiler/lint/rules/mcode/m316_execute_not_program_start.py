r"""# M316 execute-not-program-start

`EX` runs a label that is not where a program starts.

- kind: lint
- default severity: warning
- dialects: mcode
- fix available: no
- manual: L2773-L2787, L8489

## What it means

`EX <label>` starts execution at the label (L2773-L2787). A label inside a subroutine or a handler
ends in `RT` with no call to return to (stack error, L8489); a label in the middle of a program
skips the program's start, including its local `VA` declarations and trip set-up. Run the label
that follows `PG <address>` (or the address itself).

## Bad

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
EX K1
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
EX G1
```
"""

from __future__ import annotations

from mcc.compiler import ir
from mcc.compiler.lint import flow
from mcc.compiler.lint.rules import Context, rule
from mcc.compiler.lint.rules.mcode.helpers import SUBROUTINE_KINDS


@rule
def execute_not_program_start(ctx: Context) -> None:
    index = flow.block_index(ctx.module)
    for _, _, op in flow.ops(ctx.module, ir.Native):
        if op.mnemonic != "EX" or not op.args or not isinstance(op.args[0], ir.LabelRef):
            continue
        found = index.get(op.args[0].name)
        if found is None:
            continue
        routine, block = found
        if routine.kind in SUBROUTINE_KINDS:
            ctx.report(op.args[0].span or op.span,
                       f"EX {op.args[0].name} runs a {routine.kind.value} directly: its RT has no call to return to "
                       "(stack error); run the program that calls it")
        elif block is not routine.entry or routine.origin is None:
            ctx.report(op.args[0].span or op.span,
                       f"EX {op.args[0].name} starts in the middle of program {routine.name}, skipping its start")
