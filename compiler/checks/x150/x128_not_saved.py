r"""# X128 not-saved

Sequences or a power-up selection are never saved with SV.

- kind: semantic
- default severity: warning
- dialects: x150
- fix available: no
- manual: L4904, L5117

## What it means

Sequences are kept in volatile memory until SV ("THE SEQUENCE IS NOT STORED IN NON-VOLATILE BACKUP
RAM UNTIL THE SV COMMAND IS GIVEN"), and XP takes effect at power-up only once saved. mcc writes SV
where the source has it and never adds one.

## Bad

```
1XE1
1XD1
1G
1XT
1XP1
```

## Good

```
1XE1
1XD1
1G
1XT
1XP1
1SV
```
"""

from __future__ import annotations

from mcc.compiler.checks import Context, check


@check()
def not_saved(ctx: Context) -> None:
    """On the power-up selection (the last one), else on the last definition, when no SV follows it."""
    lowering = ctx.lowering
    last_definition = None
    for unit in lowering.units:
        if unit.is_sequence:
            last_definition = unit
    selections = [site for site in lowering.sites if site.kind == "handler" and site.number
                  and site.command.info.ir == "powerup"]
    anchor = None
    if last_definition is not None:
        anchor = (last_definition.start, f"sequence {last_definition.number} stays in volatile memory until SV "
                                         "(L4904)")
    if selections:
        site = selections[-1]
        anchor = (site.command, f"the power-up sequence selected by {site.command.text} is used after a power cycle "
                                "only once saved with SV (L5117)")
    if anchor is None:
        return
    command, why = anchor
    # Is there an SV after the anchor? Read from the end back to it: the anchor is most often the
    # last definition, near the end of the file.
    saved = False
    for line in reversed(lowering.tree.lines):
        for other in reversed(line.commands):
            if other is command:
                if saved:
                    return
                break
            if other.info is not None and other.info.ir == "save":
                saved = True
        else:
            continue
        break
    ctx.report(command.span, f"{why}: add SV (addressed, e.g. 1SV) after the definitions if the program must "
                             "survive a power cycle")
