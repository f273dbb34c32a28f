r"""# X306 when-without-sequence

`WHEN` watches a condition, but no `XWHEN` selects the sequence it should run.

- kind: lint
- default severity: warning
- dialects: x150
- fix available: no
- manual: L4820-L4831, L5455-L5461

## What it means

When the WHEN condition becomes true "the Controller will execute the sequence defined by the XWHEN
command" (L4827); `XWHEN0` means none (L5459). A `WHEN` in a file that never selects a sequence
with `XWHENn` relies on a selection made earlier on the controller, or does nothing.

## Bad

```
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


@rule
def when_without_sequence(ctx: Context) -> None:
    handlers = [op for _, _, op in flow.ops(ctx.module, ir.SetHandler) if op.event == "when"]
    if any(op.routine for op in handlers):
        return
    for op in handlers:
        ctx.report(op.span, "WHEN watches this condition, but no XWHENn in this file selects the sequence to run "
                            "(L4827)")
        return
