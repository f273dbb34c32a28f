r"""# M127 numeric-target

A branch, call or trip targets a numeric address mcc cannot check.

- kind: semantic
- default severity: warning
- dialects: mcode
- fix available: no

## What it means

mcc only knows the addresses where this file's programs start (PG <address>). Prefer labels: they survive edits.

## Bad

```
BR 117
```

## Good

```
BR G1
```
"""

from __future__ import annotations

from mcc.compiler.checks import Context, check
from mcc.compiler.mcode import syntax as st


@check(needs=("label references",))
def numeric_target(ctx: Context) -> None:
    """A target written as an address must be the address a `PG` of this file starts a program at."""
    origins = {r.origin for r in ctx.program.module.routines if r.origin is not None}
    for _, node, command in ctx.lowering.label_refs:
        if isinstance(node, st.Number) and node.value not in origins:
            ctx.report(node.span, f"{command} {node.text}: no program starts at address {node.text} in this file; "
                                  "mcc cannot check this target")
