r"""# M303 trip-not-re-enabled

A trip handler returns without enabling its trip again, so the trip fires only once.

- kind: lint
- default severity: warning
- dialects: mcode
- fix available: no
- manual: L5607, L5657-L5696, L8110-L8116

## What it means

Trips are one-shot: when a trip fires the device clears its bit in `TE`, and "Trip must be
re-enabled to re-execute trip" (L8115; also L5607, L5709, L5772). The usual place is the handler,
just before `RT`. The rule reports a handler with a path to `RT` on which `TE` is not set with the
trip's bit (1 input, 2 position, 4 capture, 8 time, 16 relative, 32 hMT, 64 power loss), unless
the main program sets `TE` in a loop. A relative trip `TR` with repeat 0 (the default) repeats by
itself and is not reported. If the trip is meant to fire once, suppress the finding on the trip
definition.

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
  RT
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
from mcc.compiler.lint.rules.mcode.helpers import EVENT_TRIP, handlers, is_te, te_value, trip_bit


def te_sets_bit(op, bit: int) -> bool:
    """Whether `op` is a TE that sets `bit` (one whose value is not known counts as setting it)."""
    if not is_te(op):
        return False
    value = te_value(op)
    return not isinstance(value, ir.Const) or bool(int(value.value) & bit)


def handler_re_enables(module: ir.Module, routine: ir.Routine, bit: int) -> bool:
    """True when every path from the handler's entry to an RT sets TE with the trip's bit."""

    def transfer(done: bool, item) -> bool:
        if te_sets_bit(item, bit):
            return True
        if isinstance(item, ir.Call):
            callee = module.routine(item.routine)
            if callee is not None and any(te_sets_bit(op, bit) for block in callee.blocks for op in block.ops):
                return True
        return done

    states = flow.forward(routine, False, transfer, lambda a, b: a and b)
    for block in routine.blocks:
        if block.label in states and isinstance(block.terminator, ir.Return):
            done = states[block.label]
            for op in block.ops:
                done = transfer(done, op)
            if not done:
                return False
    return True


def main_re_arms(module: ir.Module, bit: int) -> bool:
    """The main program sets TE (with the bit) inside a loop, re-arming the trip itself."""
    for routine in module.routines:
        if routine.kind not in (ir.RoutineKind.MAIN, ir.RoutineKind.POWERUP):
            continue
        looping = flow.in_loops(routine)
        for block in routine.blocks:
            if block.label in looping and any(te_sets_bit(op, bit) for op in block.ops):
                return True
    return False


@rule
def trip_not_re_enabled(ctx: Context) -> None:
    module = ctx.module
    for op in handlers(module):
        bit = trip_bit(op.event)
        if not bit or op.routine is None or op.event == "relative":  # TR repeats by itself (L5836)
            continue
        routine = module.routine(op.routine)
        if routine is None or handler_re_enables(module, routine, bit) or main_re_arms(module, bit):
            continue
        ctx.report(op.span, f"the {EVENT_TRIP[op.event]} trip fires once: its handler {routine.name} returns "
                            f"without setting TE bit {bit} again; add `TE={bit}` (or the sum of the trips "
                            "to keep) before its RT")
