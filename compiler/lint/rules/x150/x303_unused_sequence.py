r"""# X303 unused-sequence

A sequence is defined but nothing in the file runs it.

- kind: lint
- default severity: info
- dialects: x150
- fix available: no
- manual: L4865-L4871, L5072-L5140

## What it means

Sequences run through `XR`/`GOSUB`, `XG`/`GOTO`, the power-up, fault and WHEN selections (`XP`,
`XFK`, `XWHEN`), a thumbwheel or input selection, or a host sending `XRn` (L5072-L5140). A sequence
none of these in the file names takes sequence memory (8,000 bytes for all of them, L4865) and may
be left over. Files that select sequences through a variable (`XR(VAR1)`) are not checked. Suppress
the finding on the `XD` line when a host runs the sequence.

## Bad

```
1XE1
1XD1
1T1
1XT
1XE2
1XD2
1T2
1XT
1XR1
```

## Good

```
1XE1
1XD1
1T1
1XR2
1XT
1XE2
1XD2
1T2
1XT
1XR1
```
"""

from __future__ import annotations

from mcc.compiler import ir
from mcc.compiler.lint import flow
from mcc.compiler.lint.rules.shared import unused_subroutine
from mcc.compiler.lint.rules.shared.voice import speak
from mcc.compiler.lint.rules.x150.helpers import meaning
from mcc.compiler.x150 import syntax as st


def dynamic_selection(module: ir.Module, tree: st.SyntaxTree) -> bool:
    """Sequences chosen at run time: XR(VARn), GOTO(VARn), thumbwheels (XRD), select inputs (B/O)."""
    for _, _, op in flow.ops(module, ir.Native):
        if meaning(op.mnemonic) in ("call", "goto") and any(isinstance(a, ir.Var) for a in op.args):
            return True
        if op.mnemonic in ("XRD", "XRP"):
            return True
    return any(isinstance(c.arg, st.IoFunction) and c.arg.function.upper() in ("B", "O") for c in tree.commands())


speak(__name__, unused_subroutine,
      messages={"unused-subroutine": "nothing in this file runs sequence {number} (XR, XG, XP, XFK, XWHEN): remove it, "
                                     "or suppress this if a host runs it"},
      hooks={"dynamic": lambda ctx: dynamic_selection(ctx.module, ctx.tree)})
