r"""# M301 position-read-while-moving

The position is read after a move starts and before `H` waits for it to finish.

- kind: lint
- default severity: warning
- dialects: mcode
- fix available: no
- manual: L3044-L3048, L4084-L4134

## What it means

`MA` and `MR` start a move and the program goes on at once; `H` (without a time) suspends the
program until the motion completes, and "a Hold should always follow" a move (L3048). Reading the
position (`P`, `C1`, `C2`) in between — `PR P`, `R1=P`, `BR G1,P>1000` — gives wherever the axis
happens to be in the middle of the move, which changes from run to run.

The rule follows the program's flow (branches, calls) from each move to each read of the
position. Polling the moving flags (`MV`, `MP`) counts as waiting.

## Bad

```
PG 1
LB G1
  MA 51200
  PR P
  E
PG
```

## Good

```
PG 1
LB G1
  MA 51200
  H
  PR P
  E
PG
```
"""

from __future__ import annotations

from mcc.compiler.lint.rules.shared import position_read_while_moving
from mcc.compiler.lint.rules.shared.voice import speak


speak(__name__, position_read_while_moving,
      messages={"position-read-while-moving": "the position is read while the move at line {lines} may still be "
                                              "running: add `H` after the move so the program waits for it to finish"},
      words={"position": "P", "encoder": "C2"},
      # H is a program instruction (L4207): typed or downloaded outside a program there is no H to add
      options={"anchor": "operation", "skip_immediate": True})
