r"""# G301 travel-exceeded

A move's target leaves the axis's travel (`min`/`max` in `[tool.mcc.axes]`).

- kind: lint
- default severity: error
- dialects: mcode, x150, arcus
- fix available: no
- manual: lexium-mcode.txt L3935, parker-x150.md L2382, L2400, arcus-pmx-4ex-sa.txt L333

## What it means

Every device stops an axis that reaches its end of travel at a limit switch (lexium-mcode.txt
L3935: LM, the response when a limit is reached; parker-x150.md L2382, L2400: the deceleration
after a limit switch and the end-of-travel limits; arcus-pmx-4ex-sa.txt L333: +limit and -limit
inputs on every axis). mcc finds it before a motor moves: an interval analysis of each routine
(compiler/envelope/intervals.py) bounds every axis's position and every variable that feeds a move
(loops extrapolated by their count, or widened; calls summarised callee first; inputs unknown).
A move whose target is beyond the travel on every path that reaches it is an error; a move that
may leave it on some path (a branch or a loop pass decides) is a warning, with the loops in its
notes. A target mcc cannot bound at all (an input read from the host) is not reported, and one
that grows without bound in a loop is G303's. The axis is assumed to start anywhere in its travel;
a relative move made while nothing has anchored the axis yet (no absolute move, homing or position
set on the paths before it) is not reported, since where it ends depends only on where the machine
was left: declare `must-home = true` to have such moves reported (G304).

## Configuration

The examples are checked with this pyproject.toml:

```toml
[tool.mcc.axes.1]
min = 0
max = 10000
```

## Bad

```
PG 100
MA 20000
H
E
PG
```

## Good

```
PG 100
MA 8000
H
E
PG
```
"""

from __future__ import annotations

import math

from mcc.compiler import ir
from mcc.compiler.diagnostics import Severity
from mcc.compiler.envelope.intervals import Result
from mcc.compiler.lint.rules import Context, rule
from mcc.compiler.lint.rules.envelope.helpers import analysis, envelope_of


@rule
def travel_exceeded(ctx: Context) -> None:
    """A move whose target leaves the axis's travel: an error when every path does, a warning when
    some path may (a bound the analysis could not keep finite is G303's, or an unknown input's)."""
    result = analysis(ctx)
    if result is None:
        return
    envs = envelope_of(ctx)
    seen: set[tuple[int, str]] = set()
    for check in result.checks:
        env = envs[check.axis]
        key = (id(check.op), check.axis)
        if key in seen or check.op.span is None or id(check.op) in result.unbounded:
            continue
        low = env.min if env.min is not None else -math.inf
        high = env.max if env.max is not None else math.inf
        t = check.target
        call = isinstance(check.op, ir.Call)
        subject = f"this call of {check.op.routine} (its relative moves)" if call else "this move"
        where = f"takes axis {check.axis} to {t.text()}"
        notes = [*check.loops]
        if t.lo > high or t.hi < low:
            seen.add(key)
            side = f"above its travel's max {env.shown(high)}" if t.lo > high else f"below its travel's min {env.shown(low)}"
            ctx.report(check.op.span, f"{subject} {where}, {side} on every path that reaches it: the axis "
                       "would run into its end of travel; change the target or the travel in [tool.mcc.axes]",
                       notes=notes)
            continue
        if check.relative and check.anchored.lo < 1:
            continue  # where it starts is unknown (nothing anchored the axis yet): G304's question, not a path's
        over = t.hi > high and not math.isinf(t.hi)
        under = t.lo < low and not math.isinf(t.lo)
        if over or under:
            seen.add(key)
            bound = f"above the max {env.shown(high)}" if over else f"below the min {env.shown(low)}"
            why = "a branch or a loop pass decides which"
            if not call:
                notes += feeding(result, check.op, axis_expr(check), low, high)
            notes += [f"line {line}: a branch that decides the path" for line in check.branches]
            ctx.diagnostics.add(ctx.code, check.op.span,
                                f"{subject} may take axis {check.axis} {bound} (target {t.text()}): some paths "
                                f"leave the travel ({why}); bound the target or home the axis first",
                                notes=notes, severity=Severity.WARNING)


def axis_expr(check):
    return next((expr for axis, expr in check.op.targets if axis == check.axis), check.op.targets[0][1])


def feeding(result: Result, op, expr, low: float, high: float) -> list[str]:
    """Notes naming the assignments that feed a move's target, marking those whose value is
    beyond the travel: the path that leaves it."""
    names = sorted({node.name for node in walk_expr(expr) if isinstance(node, ir.Var)})
    notes = []
    for name in names:
        for assign, value in result.assigns.get(name, ()):
            if assign.span is None:
                continue
            beyond = value.hi > high or value.lo < low
            notes.append(f"line {assign.span.line}: {name} = {value.text()}"
                         + (": on this path the target leaves the travel" if beyond else ""))
    return notes[:8]


def walk_expr(expr):
    yield expr
    for child in (getattr(expr, "left", None), getattr(expr, "right", None), getattr(expr, "operand", None)):
        if child is not None:
            yield from walk_expr(child)
    for child in getattr(expr, "args", ()) or ():
        yield from walk_expr(child)
