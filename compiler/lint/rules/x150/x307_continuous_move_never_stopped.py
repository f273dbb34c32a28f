r"""# X307 continuous-move-never-stopped

A `G` in continuous mode (`MC`) runs until stopped, and nothing in the program stops it.

- kind: lint
- default severity: warning
- dialects: x150
- fix available: no
- manual: L2494-L2499, L3700-L3702, L4545-L4547

## What it means

`MC` "causes subsequent moves to ignore any distance parameter and move continuously at the
programmed velocity until stopped by an S, LS or K command" (L2498); `SB` (L3702) and `V0`
(L4547) stop it too. A program with such a move and none of these leaves the axis running until a
limit or an operator stops it. Each continuous move whose direction is known is reported; a `G`
mcc keeps as X150 text (its mode differs on the paths that reach it, X142) is reported once per
file. The rule is written once for every dialect (docs/LINT.md, motion-never-stopped).

## Bad

```
1XE3
1XD3
1A10
1V2
1MC
1G
1XT
```

## Good

```
1XE3
1XD3
1A10
1V2
1MC
1G
1TRE_1
1SB
1XT
```
"""

from __future__ import annotations

from mcc.compiler import ir
from mcc.compiler.lint.rules.shared import motion_never_stopped
from mcc.compiler.lint.rules.shared.voice import speak
from mcc.compiler.lint.rules.x150.helpers import X150, const, meaning, native


STOPPING_IRS = ("stop", "kill")  # S, SB, LS, K (catalog `ir`)


def stops(item) -> bool:
    if isinstance(item, ir.Stop):  # SB (the lowering's neutral stop)
        return True
    if isinstance(item, ir.Native) and item.dialect == X150:
        return meaning(item.mnemonic) in STOPPING_IRS or item.mnemonic in ("HALT", "OFF")
    return isinstance(item, ir.SetMotion) and item.param is ir.MotionParam.MAX_SPEED and const(item.value) == 0


def native_endless(item) -> str:
    """A G kept as X150 text: in continuous mode with a direction not known statically (L2498)."""
    return "native" if native(item, "G") else ""


def stopped_axis(item) -> str | None:
    """The axis an X150 command stops: S, SB, LS, K (catalog `ir`), HALT, OFF, or V0 (L4547)."""
    if stops(item):
        return getattr(item, "axis", "")
    return None


CONTINUOUS = "in continuous mode this G runs until S, SB, LS, K or V0 (L2498), and the program has none of them"


speak(__name__, motion_never_stopped,
      messages={"motion-never-stopped.native": CONTINUOUS,
                "motion-never-stopped.slew": CONTINUOUS,
                "motion-never-stopped.move": CONTINUOUS},
      # a G kept as text may or may not be in continuous mode (X142 says why): said once per file
      options={"once": ("native",)},
      hooks={"endless": native_endless, "stops": stopped_axis})
