r"""# A302 move-before-speed

A move runs before the program sets the speeds and acceleration it uses.

- kind: lint
- default severity: warning
- dialects: arcus
- fix available: no
- manual: L449-L457, L684-L688, L833-L844

## What it means

High speed, low speed and acceleration are not kept in flash: the items stored are the device
number, baud rate, polarity and S-curve settings and the auto-run flag (L833-L844), so after a
power cycle they are whatever the firmware starts with. Moves, jogs and homing use "the previous
high speed, low speed, and acceleration setting" (L688, L2198, L2306). Set `HSPD`, `LSPD` and
`ACC` (or all three per axis, `HSPDX`, `LSPDX`, `ACCX`, L449-L457) before the first motion on every
path.

## Bad

```
X10000
WAITX
HSPD=20000
END
```

## Good

```
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
from mcc.compiler.lint.rules.shared import move_before_speed
from mcc.compiler.lint.rules.shared.voice import speak


speak(__name__, move_before_speed,
      messages={"move-before-speed": "this moves axis {axis} before {names} {verb} set on every path: speeds are not "
                                     "kept in flash (L833-L844); set them at the start of the program"},
      words={"max_speed": "HSPD", "initial_speed": "LSPD", "accel_time": "ACC"},
      options={"params": (ir.MotionParam.MAX_SPEED, ir.MotionParam.INITIAL_SPEED, ir.MotionParam.ACCEL_TIME)})
