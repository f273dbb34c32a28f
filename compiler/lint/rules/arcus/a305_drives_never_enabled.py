r"""# A305 drives-never-enabled

The program moves axes but never sets the enable outputs (`EO`).

- kind: lint
- default severity: info
- dialects: arcus
- fix available: no
- manual: L746-L748, L2124-L2172

## What it means

The four enable outputs "enable or disable the driver if the stepper driver has such input"
(L746-L748) and they are not kept in flash (L833-L844). On a machine whose drivers are wired to
them, a program that never sets `EO` sends pulses to disabled drivers and nothing moves. If the
drivers are enabled another way, ignore this rule in the configuration (`ignore = ["A305"]`).

## Bad

```
HSPD=20000
LSPD=500
ACC=300
X10000
WAITX
END
```

## Good

```
EO=1
HSPD=20000
LSPD=500
ACC=300
X10000
WAITX
END
```
"""

from __future__ import annotations

from mcc.compiler import ir
from mcc.compiler.lint import flow
from mcc.compiler.lint.rules import Context, rule
from mcc.compiler.lint.rules.arcus.helpers import MOTION, keyword


@rule
def drives_never_enabled(ctx: Context) -> None:
    first = next((op for _, _, op in flow.ops(ctx.module, MOTION)), None)
    if first is None:
        return
    if any(keyword(op)[0] == "EO" for _, _, op in flow.ops(ctx.module, (ir.Setting, ir.DriveEnable))):
        return
    ctx.report(first.span, "the program moves axes but never sets the enable outputs (EO): drives wired to them "
                           "stay disabled (L748)")
