r"""# M106 undefined-label

BR, CL, EX, OE or a trip names a label this file does not define.

- kind: semantic
- default severity: error
- dialects: mcode
- fix available: no
- manual: L2779, L4540, L8474

## What it means

The target of a branch, call, execute, error handler or trip must be a label (LB) in program
memory. An unknown target is Error 30 on the device; at run time the jump or call never happens.

## Bad

```
PG 1
CL K1
E
PG
```

## Good

```
PG 1
CL K1
E
LB K1
RT
PG
```
"""

from __future__ import annotations

from mcc.compiler.checks import Context, check
from mcc.compiler.mcode import syntax as st


@check(needs=("label references",), also=("M129",))
def undefined_label(ctx: Context) -> None:
    """Every BR, CL, EX, OE, trip (and BP, L, CP) that names a label must name one of this file;
    a name that is a variable is M129 (its page is M129's, shared with resolve.py)."""
    names = ctx.lowering.resolver.names
    for key, node, command in ctx.lowering.label_refs:
        if isinstance(node, st.Number) or key in names.labels:
            continue  # an address: M127
        if key in names.variables:
            ctx.report(node.span, f"{node.text} is a variable, not a label: {command} needs a label", code="M129")
        else:
            ctx.report(node.span, f"label {node.text} is not defined: add `LB {node.text}` where {command} should "
                                  "go, or fix the name")
