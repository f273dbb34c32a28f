r"""# M313 continuous-move-never-stopped

A move with parameter 3 = 1, or `SL` at a velocity other than 0, keeps running, and nothing in the program stops it.

- kind: lint
- default severity: warning
- dialects: mcode
- fix available: no
- manual: L4108-L4118, L4255-L4264, L5393-L5404

## What it means

`MA <pos>,<p2>,1` and `MR <dist>,<p2>,1` "continue moving after position is reached"
(L4117, L4264); the move only ends with `SL 0` or `ESC` (L4108). `SL <velocity>` "slews the axis
at the commanded velocity" (L5393-L5404) until another `SL` changes it. A program with such motion
and no `SL 0` anywhere (nor an `SL` from a variable, which may be 0, nor an input set up as soft
stop with `IS=<n>,5`) leaves the axis running until a limit, an error or the operator stops it.
The rule is written once for every dialect (docs/LINT.md, motion-never-stopped; Arcus A314, X150
X307); the `SL` case is reported since that rule was shared.

## Bad

```
PG 1
LB G1
  MA 51200,0,1
  E
PG
```

## Good

```
PG 1
LB G1
  MA 51200,0,1
LB W1
  BR W1,I1=0
  SL 0
  H
  E
PG
```
"""

from __future__ import annotations

from mcc.compiler.lint.rules.shared import motion_never_stopped
from mcc.compiler.lint.rules.shared.voice import speak


speak(__name__, motion_never_stopped,
      messages={"motion-never-stopped.move": "this move keeps running after it reaches its position (parameter 3 = 1) "
                                             "and no `SL 0` stops it anywhere in the program",
                "motion-never-stopped.slew": "SL keeps the axis running at this velocity and no `SL 0` stops it "
                                             "anywhere in the program"})
