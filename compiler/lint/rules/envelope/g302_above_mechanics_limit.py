r"""# G302 above-mechanics-limit

A speed or acceleration setting is above the mechanics' `max-speed` or `max-accel`.

- kind: lint
- default severity: error
- dialects: mcode, x150, arcus
- fix available: no
- manual: lexium-mcode.txt L3935, parker-x150.md L2382

## What it means

The envelope's `max-speed` (steps/s, or mm/s, deg/s with a scale) and `max-accel` are what the
mechanics (screw, belt, load) stand; a drive happily runs faster. A setting of the maximum or
initial speed above `max-speed`, or of the acceleration or deceleration above `max-accel`, is an
error when every value the analysis finds is above it and a warning when some may be. A slew's
velocity and a homing's own speed are checked against `max-speed`; an acceleration given as a ramp
time (Arcus ACC) is checked at each move as the maximum speed less the initial speed in force over
the ramp time.
The limit switch response (lexium-mcode.txt L3935, parker-x150.md L2382) is the last line of
defence, not the design.

## Configuration

The examples are checked with this pyproject.toml:

```toml
[tool.mcc.axes.1]
max-speed = 100000
```

## Bad

```
PG 100
VM 200000
MA 20000
H
E
PG
```

## Good

```
PG 100
VM 50000
MA 20000
H
E
PG
```
"""

from __future__ import annotations

import math

from mcc.compiler import ir
from mcc.compiler.diagnostics import Severity
from mcc.compiler.lint.rules import Context, rule
from mcc.compiler.lint.rules.envelope.helpers import analysis, envelope_of

# the setting -> (the envelope field that limits it, what it is called, its unit)
SPEEDS = {ir.MotionParam.MAX_SPEED: ("max_speed", "speed", "steps/s"),
          ir.MotionParam.INITIAL_SPEED: ("max_speed", "speed", "steps/s"),
          ir.MotionParam.ACCEL: ("max_accel", "acceleration", "steps/s²"),
          ir.MotionParam.DECEL: ("max_accel", "deceleration", "steps/s²")}


@rule
def above_mechanics(ctx: Context) -> None:
    """A speed or acceleration setting above the mechanics' limit in the envelope."""
    result = analysis(ctx)
    if result is None:
        return
    envs = envelope_of(ctx)
    for op, value in result.settings:
        if op.param not in SPEEDS or op.span is None:
            continue
        field_name, what, unit = SPEEDS[op.param]
        for axis in envs if op.axis in (ir.ALL_AXES, "") else [a for a in envs if a == op.axis]:
            limit = getattr(envs[axis], field_name)
            if limit is None or value.hi <= limit or math.isinf(value.hi):
                continue
            every = value.lo > limit
            ctx.diagnostics.add(ctx.code, op.span,
                                f"this {what} ({value.text()} {unit}) is above the mechanics' limit of axis {axis} "
                                f"({limit:g} {unit}, [tool.mcc.axes.{axis}]): lower it"
                                + ("" if every else " (on some paths)"),
                                severity=Severity.ERROR if every else Severity.WARNING)
            break
    seen: set[tuple[int, str]] = set()
    for op, axis, quantity, value in result.motion:
        field_name, unit = ("max_speed", "steps/s") if quantity == "speed" else ("max_accel", "steps/s²")
        limit = getattr(envs[axis], field_name)
        if limit is None or value.hi <= limit or op.span is None or (id(op), quantity) in seen:
            continue
        seen.add((id(op), quantity))
        what = f"runs axis {axis} at {value.text()} {unit}" if quantity == "speed" else \
            f"ramps axis {axis} at {value.text():s} {unit} (the maximum speed less the initial speed over the ramp time)"
        every = value.lo > limit
        ctx.diagnostics.add(ctx.code, op.span,
                            f"this motion {what}, above the mechanics' limit of {limit:g} {unit} "
                            f"([tool.mcc.axes.{axis}]): lower the speed or lengthen the ramp"
                            + ("" if every else " (on some paths)"),
                            severity=Severity.ERROR if every else Severity.WARNING)
