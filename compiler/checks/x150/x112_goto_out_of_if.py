r"""# X112 goto-out-of-if

XG/GOTO leaves an IF open, and the target sequence does not begin with NIF.

- kind: semantic
- default severity: error
- dialects: x150
- fix available: no
- manual: L1794, L2024, L5079

## What it means

The controller keeps the IF open when a GOTO or XG jumps out of it: "the code jumped to must be
preceded by a NIF command to clear the original IF command". Begin the target sequence with one NIF
per open IF, or close the IF before the jump.

## Bad

```
XE2
XD2
G
XT
XE1
XD1
IF(IN_1)
XG2
NIF
XT
```

## Good

```
XE2
XD2
NIF
G
XT
XE1
XD1
IF(IN_1)
XG2
NIF
XT
```
"""

from __future__ import annotations

from mcc.compiler.checks import Context, check


@check(needs=("sequence transfers",))
def goto_out_of_if(ctx: Context) -> None:
    """An XG/GOTO inside IF(...) to a sequence of this file that does not begin with as many NIFs."""
    for site in ctx.lowering.sites:
        number = site.number
        if not number or not 1 <= number <= 64 or not site.targets:
            continue  # an undefined sequence is X127
        depth = site.depth.get("IF", 0) if site.kind == "goto" else 0
        if not depth:
            continue
        for target in site.targets:
            nifs = ctx.lowering.leading_nifs.get(target, 0)
            if nifs < depth:
                needed = "NIF" if depth == 1 else f"{depth} NIFs"
                ctx.report(site.command.span,
                           f"{site.command.text} leaves {depth} open IF(...) behind; the controller keeps it open, "
                           f"so sequence {site.number} must begin with {needed} (L1794, L2024, L5079); add "
                           f"{needed} as its first command, or close the IF before jumping")
