r"""# A301 position-read-while-moving

The position of an axis is read after a move starts and before `WAIT` on that axis.

- kind: lint
- default severity: warning
- dialects: arcus
- fix available: no
- manual: L2702-L2716, L2376-L2416

## What it means

Move statements (`X1000`, `HOMEX+`, `ARC`, `CIR`) start the motion and the program goes on to the
next line; `WAIT[axis]` is what makes the program "wait until move on the certain axis is finished
before executing next line" (L2702-L2706). Reading `P[axis]` or `E[axis]` in between gives a
position from the middle of the move, different on every run. The rule follows the program's flow
per axis; reading the axis's status `MST[axis]` counts as polling for the end, and a `GOSUB` to a
subroutine that waits for the axis on every path ends its moves. A jog has no end, so reading the
position (or the speed, `PS[axis]`) while jogging is not reported. The rule is written once for
every dialect (docs/LINT.md, position-read-while-moving; MCode M301).

## Bad

```
HSPD=20000
LSPD=500
ACC=300
X10000
V1=PX
END
```

## Good

```
HSPD=20000
LSPD=500
ACC=300
X10000
WAITX
V1=PX
END
```
"""

from __future__ import annotations

from mcc.compiler.lint.rules.shared import position_read_while_moving
from mcc.compiler.lint.rules.shared.voice import speak


speak(__name__, position_read_while_moving,
      messages={"position-read-while-moving": "{reading}{axis} is read while the move at line {line} may still be "
                                              "running: add WAIT{axis} before reading it (L2706)"},
      words={"position": "P", "encoder": "E"},
      options={"anchor": "reading"})
