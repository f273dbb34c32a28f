r"""# M104 user-name-is-mnemonic

A label or variable has the name of an MCode command, variable or function.

- kind: semantic
- default severity: error
- dialects: mcode
- fix available: no
- manual: L547, L599, L886, L3763

## What it means

Labels and variables must not use a name the firmware already has: the device rejects them with
Error 24 (illegal data) or 29. Reserved names without a function (FT, PK, I7-I13) are included.

## Bad

```
VA MS
LB PR
```

## Good

```
VA Ms1
LB P1
```
"""

from __future__ import annotations

from mcc.compiler.checks import Context, check
from mcc.compiler.checks.mcode.helpers import is_mnemonic, user_names


@check(needs=("user names",))
def user_name_is_mnemonic(ctx: Context) -> None:
    cat = ctx.lowering.cat
    profile = ctx.profile
    for kind, key, node in user_names(ctx.program):
        if not is_mnemonic(ctx.program, key):
            continue
        entry = cat.lookup(key) or cat.functions.get(key)
        what = f"the MCode {entry.kind} {key} ({entry.entry.title})" if entry else f"the command {key}"
        if entry is not None and entry.kind == "function" and entry.firmware:
            targets = profile.firmware or "the newest"
            what += (f" from firmware {entry.firmware} on (the profile targets {targets}; on older "
                     "firmware it is a plain name: use a profile with `firmware = \"5.0\"`, see docs/PROFILES.md)")
        ctx.report(node.span, f"{kind} name {node.text} is {what}: user names must not be MCode names; choose "
                              "another")
