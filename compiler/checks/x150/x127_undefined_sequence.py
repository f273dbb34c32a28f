r"""# X127 undefined-sequence

XR, XG, GOSUB, GOTO, XP, XFK or XWHEN names a sequence this file does not define.

- kind: semantic
- default severity: warning
- dialects: x150
- fix available: no
- manual: L5129-L5151, L5294

## What it means

The sequence may already be stored on the controller; if it is not, XR/XG set a function error
(XSR reports 2). mcc cannot check what it does, nor the nesting and NIF rules through it.

## Bad

```
XR7
```

## Good

```
XE7
XD7
G
XT
XR7
```
"""

from __future__ import annotations

from mcc.compiler.checks import Context, check


@check(needs=("sequence transfers",))
def undefined_sequence(ctx: Context) -> None:
    """A transfer to a sequence number (1-64, L4899) that no XD of this file defines."""
    for site in ctx.lowering.sites:
        number = site.number
        if number and 1 <= number <= 64 and not site.targets:
            command = site.command
            ctx.report(command.span, f"sequence {number} is not defined in this file: {command.text} uses whatever "
                                     f"sequence {number} is stored on the controller (define it here, or check it "
                                     "is downloaded)")
