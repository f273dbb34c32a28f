r"""# M323 falls-into-subroutine

The main program runs on into a subroutine or handler without `E`.

- kind: semantic
- default severity: warning
- dialects: mcode
- fix available: no
- manual: L7617-L7658, L2523-L2531, L8489

## What it means

Programs end with `E`, and subroutines follow it (the layout of every sample, L7617-L7658). When
the last line of the main program is not `E` (or a `BR`), execution continues into the subroutine
below it and its `RT` returns with no call on the stack (stack error, L8489). End the main program
with `E` or with a branch back to its loop.

`mcc check` reports it (it was a lint rule before; the code kept its number so configurations
that name M323 keep working).

## Bad

```
PG 1
LB G1
  CL K1
  MA 0
  H
LB K1
  MR 1000
  H
  RT
PG
```

## Good

```
PG 1
LB G1
  CL K1
  MA 0
  H
  E
LB K1
  MR 1000
  H
  RT
PG
```
"""

from __future__ import annotations

from mcc.compiler import ir
from mcc.compiler.checks import Context, check


@check(needs=("subroutines",))
def falls_into_subroutine(ctx: Context) -> None:
    """The main (or SU) program runs past its last line into a subroutine or handler: its RT then
    returns with no call on the stack (L8489). Reported by `mcc check`, not only by lint.

    The lowering joins one label's code to the next label's with a Jump carrying the span of the
    `LB` it runs into (the target block's own span); a written `BR` carries its own span."""
    module = ctx.program.module
    owner = {block.label: (routine, block) for routine in module.routines for block in routine.blocks}
    for routine in module.routines:
        if routine.kind not in (ir.RoutineKind.MAIN, ir.RoutineKind.POWERUP) or routine.entry is None:
            continue
        for block in reachable(routine):
            term = block.terminator
            if not isinstance(term, ir.Jump) or term.target not in owner:
                continue
            target_routine, target = owner[term.target]
            if target_routine is routine or target_routine.kind not in (ir.RoutineKind.SUBROUTINE,
                                                                        ir.RoutineKind.HANDLER):
                continue
            if term.span is None or term.span != target.span:
                continue  # a written BR into a subroutine is another matter (M302 and friends)
            ctx.report(term.span, f"the program {routine.name} runs on into {target_routine.kind.value} "
                                  f"{target.label} without E: its RT returns with no call on the stack; end the "
                                  "program with E (or BR back to its loop)")


def reachable(routine: ir.Routine) -> list[ir.Block]:
    """The routine's blocks reachable from its entry, in routine order."""
    blocks = {block.label: block for block in routine.blocks}
    seen = {routine.entry.label}
    todo = [routine.entry]
    while todo:
        for label in ir.successors(todo.pop().terminator):
            if label in blocks and label not in seen:
                seen.add(label)
                todo.append(blocks[label])
    return [block for block in routine.blocks if block.label in seen]
