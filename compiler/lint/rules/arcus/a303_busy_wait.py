r"""# A303 busy-wait

A `WHILE` loop only tests a condition again and again, with no `DELAY` or `WAIT` in it.

- kind: lint
- default severity: warning
- dialects: arcus
- fix available: no
- manual: L793, L1868-L1876, L2720-L2741

## What it means

The standalone program is a single thread (there is no multi-threading, spec §1.3): a loop like
`WHILE DI1=0` / `ENDWHILE` spins as fast as the controller can run it and competes with the USB
host, which is served in the same firmware (the timer register is explicitly less accurate while
a PC polls, L793). Put `DELAY=<ms>` in the loop (the manual's own polling interval, L1868-L1876),
or use `WAIT[axis]` to wait for a move.

## Bad

```
WHILE DI1=0
ENDWHILE
DO1=1
END
```

## Good

```
WHILE DI1=0
DELAY=10
ENDWHILE
DO1=1
END
```
"""

from __future__ import annotations

from mcc.compiler.lint.rules.shared import busy_wait
from mcc.compiler.lint.rules.shared.voice import speak


speak(__name__, busy_wait,
      messages={"busy-wait": "this loop only tests its condition again and again: add DELAY=<ms> inside it (L1868), or "
                             "WAIT[axis] to wait for a move"})
