r"""# M304 motion-at-power-up

The `SU` start-up program moves the axis as soon as the device is powered.

- kind: lint
- default severity: warning
- dialects: mcode
- fix available: no
- manual: L5524-L5547

## What it means

A program labelled `SU` runs on power-up and after a software reset (L5540). The manual's DANGER
note (L5526-L5531): "Depending on the program structure this could result in immediate motion"
and "Only use the SU label in instances or applications where operation does not represent a
hazard to personnel or equipment". The rule reports the first move, slew or homing the start-up
program reaches. Wait for an input (an operator's start button) before moving, or start the
program with `EX` instead of `SU`; if motion at power-up is intended, suppress the finding on
that line.

## Bad

```
PG 1
LB SU
  HM 1
  H
  E
PG
```

## Good

```
PG 1
LB SU
LB W1
  BR W1,I1=0
  HM 1
  H
  E
PG
```
"""

from __future__ import annotations

from mcc.compiler import ir
from mcc.compiler.lint import flow
from mcc.compiler.lint.rules import Context, rule


MOTION_OPS = (ir.Move, ir.Slew, ir.Home, ir.Arc)


def reads_input(item) -> bool:
    found = flow.term_reads(item) if isinstance(item, ir.Branch) else flow.op_reads(item) if item is not None else ()
    return any(isinstance(n, ir.Status) and n.meaning in ("input", "inputs") for n in found) or \
        isinstance(item, ir.WaitInput)


@rule
def motion_at_power_up(ctx: Context) -> None:
    module = ctx.module

    def transfer(unguarded: bool, item) -> bool:
        return unguarded and not isinstance(item, ir.WaitInput)

    def edge(unguarded: bool, block: ir.Block, succ: ir.Block) -> bool:
        return unguarded and not reads_input(block.terminator)

    routines = flow.routine_index(module)

    def moves(routine_name: str, seen: set[str]) -> bool:
        """The routine, or one it calls (at any depth), starts motion."""
        work = [routine_name]
        while work:
            routine = routines.get(work.pop())
            if routine is None or routine.name in seen:
                continue
            seen.add(routine.name)
            for block in routine.blocks:
                for op in block.ops:
                    if isinstance(op, MOTION_OPS):
                        return True
                    if isinstance(op, ir.Call):
                        work.append(op.routine)
        return False

    for routine in module.routines:
        if routine.kind is not ir.RoutineKind.POWERUP:
            continue
        states = flow.forward(routine, True, transfer, lambda a, b: a or b, edge)
        for block in routine.blocks:
            if not states.get(block.label):
                continue
            for item, unguarded in flow.replay(block, True, transfer):
                if not unguarded:
                    break
                if isinstance(item, MOTION_OPS) or isinstance(item, ir.Call) and moves(item.routine, set()):
                    ctx.report(item.span, "the SU program starts motion as soon as the device is powered "
                                          "(DANGER, L5526): wait for an input first, or start it with EX")
                    return
