r"""# M122 label-and-variable

The same name is a label and a variable.

- kind: semantic
- default severity: error
- dialects: mcode
- fix available: no
- manual: L537, L8472

## What it means

Labels and variables share one name table on the device; the second definition is Error 28.

## Bad

```
VA K1
PG 1
LB K1
```

## Good

```
VA Q1
PG 1
LB K1
```
"""

from __future__ import annotations

from mcc.compiler.checks import Context, check


@check(needs=("user names",))
def label_and_variable(ctx: Context) -> None:
    names = ctx.lowering.resolver.names
    for key, node in names.variables.items():
        if key in names.labels:
            label = names.labels[key]
            ctx.report(node.span, f"{node.text} is both a variable and a label (line {label.span.line}); labels "
                                  "and variables share one name table, rename one")
