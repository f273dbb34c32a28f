r"""# M116 name-table-full

More than 192 labels and variables.

- kind: semantic
- default severity: error
- dialects: mcode
- fix available: no
- manual: L537, L8475

## What it means

Labels and user variables share one table of 192 entries on the device (Error 31 when full).

## Bad

```
` 193 different labels and variables in one file
```

## Good

```
` reuse working variables (R1-R4 need no table entry) and keep labels for real jump targets
```
"""

from __future__ import annotations

from mcc.compiler.checks import Context, check


@check(needs=("user names",))
def name_table_full(ctx: Context) -> None:
    """Reported on the last variable (else the last label): the name that no longer fits."""
    names = ctx.lowering.resolver.names
    limit = int(ctx.profile.get("limits.user_names", 192))
    count = len(set(names.labels) | set(names.variables))
    if count > limit:
        node = list(names.variables.values())[-1] if names.variables else list(names.labels.values())[-1]
        ctx.report(node.span, f"{count} labels and variables: the device's name table holds {limit} (Error 31); "
                              "reuse names or split the program")
