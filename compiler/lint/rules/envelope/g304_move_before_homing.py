r"""# G304 move-before-homing

An axis whose envelope says `must-home = true` moves before any homing.

- kind: lint
- default severity: error
- dialects: mcode, x150, arcus
- fix available: no
- manual: parker-x150.md L2845, arcus-pmx-4ex-sa.txt L668

## What it means

An axis with an incremental position counter does not know where it is at power-up: its counter
means something only after a homing sets it (parker-x150.md L2845, arcus-pmx-4ex-sa.txt L668: the
counters reset at the home trigger). With `must-home = true` in the axis's envelope, a move on a
path that has not homed the axis yet is an error when no path homes it first, and a warning when
some path does not.

## Configuration

The examples are checked with this pyproject.toml:

```toml
[tool.mcc.axes.1]
must-home = true
```

## Bad

```
PG 100
MA 2000
H
E
PG
```

## Good

```
PG 100
HM 1
H
MA 2000
H
E
PG
```
"""

from __future__ import annotations

from mcc.compiler.diagnostics import Severity
from mcc.compiler.lint.rules import Context, rule
from mcc.compiler.lint.rules.envelope.helpers import analysis, envelope_of


@rule
def move_before_homing(ctx: Context) -> None:
    """A move of an axis the envelope says must be homed first (`must-home`), before any homing."""
    result = analysis(ctx)
    if result is None:
        return
    envs = envelope_of(ctx)
    seen: set[int] = set()
    for check in result.checks:
        if not envs[check.axis].must_home or id(check.op) in seen or check.op.span is None:
            continue
        if check.homed.hi < 1:
            seen.add(id(check.op))
            ctx.report(check.op.span, f"axis {check.axis} moves before any homing (must-home = true in its "
                       "envelope): home it first")
        elif check.homed.lo < 1:
            seen.add(id(check.op))
            ctx.diagnostics.add(ctx.code, check.op.span, f"axis {check.axis} may move before it is homed: some path "
                                "reaches this move without a homing (must-home = true); home it on every path",
                                notes=check.loops, severity=Severity.WARNING)
