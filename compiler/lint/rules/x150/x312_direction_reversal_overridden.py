r"""# X312 direction-reversal-overridden

`H` reverses the next move, but the next `D` is signed and sets the direction itself.

- kind: lint
- default severity: warning
- dialects: x150
- fix available: no
- manual: L813-L820, L1824-L1829

## What it means

`H` "reverses direction of the next move. The D command could subsequently be used to reset the
direction" (L1828); a `D` with a sign sets the direction and "overrides a previous H command"
(L819). `H` followed by `D+n` or `D-n` before the `G` has no effect. Drop the `H`, or the sign.

## Bad

```
1XE6
1XD6
1A10
1V5
1H
1D-4000
1G
1XT
```

## Good

```
1XE6
1XD6
1A10
1V5
1H
1D4000
1G
1XT
```
"""

from __future__ import annotations

from mcc.compiler.lint.rules import Context, rule
from mcc.compiler.x150 import syntax as st


@rule
def direction_reversal_overridden(ctx: Context) -> None:
    pending: dict[int | None, st.Command] = {}
    for command in ctx.tree.commands():
        name = command.mnemonic
        if name == "H" and command.arg is None:
            pending[command.address] = command
        elif name == "D" and isinstance(command.arg, st.Number) and command.arg.text[:1] in "+-" \
                and command.address in pending:
            h = pending.pop(command.address)
            ctx.report(h.span, f"H reverses the next move, but the signed {command.text} at line {command.span.line} "
                               "sets the direction itself (L819): H has no effect")
        elif name in ("G", "XD", "XT"):
            pending.pop(command.address, None)
