r"""# A314 jog-never-stopped

An axis is jogged and nothing in the program stops it.

- kind: lint
- default severity: warning
- dialects: arcus
- fix available: no
- manual: L684-L698, L2302-L2313, L2489-L2517

## What it means

`JOG[axis][+/-]` runs the axis continuously (L684-L688, L2302-L2313) until `STOP`/`STOP[axis]`
(decelerating, L2489-L2517), `ABORT` (immediate) or a limit or alarm. A program that jogs an axis
and never stops it relies on a limit switch to end the motion.

## Bad

```
HSPD=20000
LSPD=500
ACC=300
JOGX+
END
```

## Good

```
HSPD=20000
LSPD=500
ACC=300
JOGX+
WHILE DI1=0
DELAY=10
ENDWHILE
STOPX
END
```
"""

from __future__ import annotations

from mcc.compiler.lint.rules.shared import motion_never_stopped
from mcc.compiler.lint.rules.shared.voice import speak


speak(__name__, motion_never_stopped,
      messages={"motion-never-stopped.slew": "axis {axis} jogs until something stops it, and the program never does "
                                             "(STOP{axis}, STOP or ABORT)",
                "motion-never-stopped.move": "axis {axis} keeps moving after it reaches its target, and the program "
                                             "never stops it (STOP{axis}, STOP or ABORT)"})
