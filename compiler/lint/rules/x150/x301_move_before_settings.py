r"""# X301 move-before-settings

`G` starts a move before this program has set the acceleration, velocity or distance it uses.

- kind: lint
- default severity: warning
- dialects: x150
- fix available: no
- manual: L1673-L1677, L817-L819, L219-L233, L4545-L4547

## What it means

`G` makes "a move using the previously entered parameters" (L1675): the A, V and D in force, whatever
set them last — the power-up values, another program, an operator at the terminal. A sequence that
moves without setting them first does something different on every machine. Set `A`, `V` and (in
preset modes) `D` before the first `G`, in the sequence or in the set-up lines sent before it; a
sequence run with `XR` or `GOSUB` starts with what holds at every call.

## Bad

```
1XE1
1XD1
1MN
1MPI
1D4000
1G
1XT
```

## Good

```
1XE1
1XD1
1MN
1MPI
1A10
1V5
1D4000
1G
1XT
```
"""

from __future__ import annotations

from mcc.compiler import ir
from mcc.compiler.lint.rules.shared import move_before_speed
from mcc.compiler.lint.rules.shared.voice import speak
from mcc.compiler.lint.rules.x150.helpers import native


def uses_distance(move: ir.Move) -> bool:
    """A `G` moving by a D not known where it runs (the lowering reads the register %D<device>)."""
    return any(isinstance(value, ir.Var) and value.name.startswith("%D") for _, value in move.targets)


def distance_facts(item) -> tuple:
    """D is its own setting on X150: a move with a known distance, or setting the register, sets it."""
    if isinstance(item, ir.Move) and not uses_distance(item):
        return tuple(("distance", axis) for axis, _ in item.targets)
    if isinstance(item, ir.Assign) and item.target.name.startswith("%D"):
        return (("distance", item.target.name[2:]),)
    return ()


def distance_needed(item) -> tuple:
    return ("distance",) if isinstance(item, ir.Move) and uses_distance(item) else ()


speak(__name__, move_before_speed,
      messages={"move-before-speed": "G moves with the {names} left by whatever ran before: set {names} before the "
                                     "first G (L1675)"},
      words={"accel": "A", "max_speed": "V", "distance": "D"},
      # GH homes at the speed it is given and with GA (L1701-L1711): only G uses A and V
      options={"params": (ir.MotionParam.ACCEL, ir.MotionParam.MAX_SPEED), "kinds": (ir.Move, ir.Slew)},
      hooks={"facts": distance_facts, "needs": distance_needed, "moves": lambda item: native(item, "G")})
