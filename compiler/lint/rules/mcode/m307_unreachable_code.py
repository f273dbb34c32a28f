r"""# M307 unreachable-code

Statements after an unconditional `BR`, `RT` or `E` that no label makes reachable.

- kind: lint
- default severity: warning
- dialects: mcode
- fix available: no
- manual: L1789-L1807, L2523-L2531, L7643

## What it means

After `BR <label>` without a condition, `RT` or `E`, execution never falls through to the next
line (L1789-L1807, L2523-L2531); the following statements run only if a label in front of them is
the target of a branch or call. Without one they are dead code that still occupies program memory.
A lone `E` after the main loop, as in every sample of the manual (L7643), is the conventional end
marker and is not reported.

## Bad

```
PG 1
LB G1
  BR G1,I1=0
  BR G1
  MA 1000
  H
  E
PG
```

## Good

```
PG 1
LB G1
  BR G1,I1=0
  MA 1000
  H
  BR G1
  E
PG
```
"""

from __future__ import annotations

from mcc.compiler.lint.rules.shared import unreachable_code
from mcc.compiler.lint.rules.shared.voice import speak


speak(__name__, unreachable_code,
      messages={"unreachable-code": "this line can never run: the line before it always branches, returns or ends and "
                                    "no label leads here"},
      # commands outside a program (typed, or downloaded outside PG) run one after the other: not judged
      options={"skip_immediate": True})
