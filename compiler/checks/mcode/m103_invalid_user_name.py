r"""# M103 invalid-user-name

A label or variable name does not follow MCode's naming rule.

- kind: semantic
- default severity: error
- dialects: mcode
- fix available: no
- manual: L549-L550, L888, L3764

## What it means

User names (labels and variables) are two characters: a letter, then a letter or a digit. The
manual contradicts itself on longer names; mcc follows the rule every example uses. Set
`label_rule = "relaxed"` in the profile's `[limits]` to also accept one character or a letter and
two digits.

## Bad

```
VA Count
LB 1A
```

## Good

```
VA Ct
LB A1
```
"""

from __future__ import annotations

from mcc.compiler.checks import Context, check
from mcc.compiler.checks.mcode.helpers import is_mnemonic, name_rule, user_names


@check(needs=("user names",))
def invalid_user_name(ctx: Context) -> None:
    """A name that is a mnemonic is M104's, whatever its form."""
    pattern, rule = name_rule(ctx.program)
    for kind, key, node in user_names(ctx.program):
        if not is_mnemonic(ctx.program, key) and not pattern.match(node.text):
            ctx.report(node.span, f"{kind} name '{node.text}' is not a valid MCode name ({rule})")
