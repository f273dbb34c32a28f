r"""# X305 when-not-re-armed

The XWHEN sequence does not end with `WHEN` again, so it runs only the first time.

- kind: lint
- default severity: warning
- dialects: x150
- fix available: no
- manual: L4820-L4831, L5455-L5461

## What it means

"The XWHEN sequence will not execute every time that the WHEN condition is met, only the first
time. For multiple execution of the XWHEN sequence, the last command of the XWHEN sequence should be
the WHEN command again" (L4829). If one run is what you want, suppress the finding on the
sequence's `XD` line.

## Bad

```
1XE7
1XD7
1O1
1XT
1XWHEN7
1WHEN(IN_1)
```

## Good

```
1XE7
1XD7
1O1
1WHEN(IN_1)
1XT
1XWHEN7
1WHEN(IN_1)
```
"""

from __future__ import annotations

from mcc.compiler import ir
from mcc.compiler.lint import flow
from mcc.compiler.lint.rules import Context, rule


def re_arms(module: ir.Module, routine: ir.Routine, seen: set[str] | None = None) -> bool:
    """The routine (or a sequence it calls) sets a WHEN condition again."""
    seen = seen if seen is not None else set()
    work = [routine]
    while work:  # the sequences it calls, at any depth, without Python recursion
        current = work.pop()
        if current.name in seen and current is not routine:
            continue
        seen.add(current.name)
        for block in current.blocks:
            for op in block.ops:
                if isinstance(op, ir.SetHandler) and op.event == "when" and op.routine is None:
                    return True
                if isinstance(op, ir.Call) and op.routine not in seen:
                    callee = module.routine(op.routine)
                    if callee is not None:
                        work.append(callee)
    return False


@rule
def when_not_re_armed(ctx: Context) -> None:
    module = ctx.module
    selected = {op.routine for _, _, op in flow.ops(module, ir.SetHandler) if op.event == "when" and op.routine}
    for name in sorted(selected):
        routine = module.routine(name)
        if routine is None or re_arms(module, routine):
            continue
        ctx.report(routine.span or ctx.source.line_span(1),
                   f"the XWHEN sequence {routine.number} does not end with WHEN(...): it runs only the first time "
                   "the condition is met (L4829)")
