r"""# G303 relative-move-unbounded-loop

A relative move repeats in a loop whose count nothing bounds: the axis creeps to its end of travel.

- kind: lint
- default severity: warning
- dialects: mcode, x150, arcus
- fix available: no
- manual: lexium-mcode.txt L3935, arcus-pmx-4ex-sa.txt L333

## What it means

A loop counted by one variable changed by a constant each pass and compared with a bound at the
loop's exit has a count mcc can bound; a relative move inside it moves the axis at most count times
its distance. A loop whose exit does not depend on such a counter (a loop that runs forever, or
until an input changes, or up to a count the host sets) gives the axis no bound: each pass adds
the relative move, and the axis ends at a limit switch (lexium-mcode.txt L3935, arcus-pmx-4ex-sa.txt
L333). Move absolutely, or count the loop with a bound the program sets. Reported only when the
envelope gives the axis a travel.

## Configuration

The examples are checked with this pyproject.toml:

```toml
[tool.mcc.axes.1]
min = 0
max = 100000
```

## Bad

```
PG 100
LB K1
MR 1000
H
BR K1
PG
```

## Good

```
PG 100
LB K1
MA 1000
H
MA 0
H
BR K1
PG
```
"""

from __future__ import annotations

from mcc.compiler.lint.rules import Context, rule
from mcc.compiler.lint.rules.envelope.helpers import analysis, line_of


@rule
def relative_move_unbounded_loop(ctx: Context) -> None:
    """A relative move inside a loop whose count nothing bounds: the axis creeps without end."""
    result = analysis(ctx)
    if result is None:
        return
    for op, axis, note in sorted(result.unbounded.values(), key=lambda item: line_of(item[0])):
        if op.span is None:
            continue
        ctx.report(op.span, f"this relative move of axis {axis} repeats in a loop whose count mcc cannot bound, so "
                   "the axis's position has no bound: count the loop with a bound the program sets, or move "
                   "absolutely", notes=(f"{note} (header) repeats it; its exit test does not depend on one counter "
                                        "changed by a constant each pass",))
