"""The machine's envelope, one rule per question (issue 27, docs/LINT.md "Envelope"): does a move
leave the travel (G301), is a speed or acceleration above the mechanics' limit (G302), does a
relative move repeat in a loop whose count nothing bounds (G303), does an axis move before it is
homed when it must be (G304). Each reads the envelope of `[tool.mcc.axes]` and the profile's
`[envelope]` (compiler/envelope/axes.py) and the interval analysis of compiler/envelope/intervals.py;
without an envelope they report nothing. They are the same for every dialect.
"""

from __future__ import annotations

import math

from mcc.compiler import dialects, ir
from mcc.compiler.diagnostics import Severity
from mcc.compiler.envelope.axes import AxisEnvelope, envelopes
from mcc.compiler.envelope.intervals import Analyzer, Result
from mcc.compiler.lint.rules import Context, rule

ALL = tuple(dialects.names())
SPEEDS = {ir.MotionParam.MAX_SPEED: ("max_speed", "speed", "steps/s"),
          ir.MotionParam.INITIAL_SPEED: ("max_speed", "speed", "steps/s"),
          ir.MotionParam.ACCEL: ("max_accel", "acceleration", "steps/s²"),
          ir.MotionParam.DECEL: ("max_accel", "deceleration", "steps/s²")}


def envelope_of(ctx: Context) -> dict[str, AxisEnvelope]:
    configured = getattr(ctx.settings, "axes", ()) or ()
    return ctx.shared("envelope", lambda: envelopes(ctx.profile, configured))


def analysis(ctx: Context) -> Result | None:
    found = envelope_of(ctx)
    if not found:
        return None
    return ctx.shared("envelope-analysis", lambda: Analyzer(ctx.module, found, ctx.profile.axes).run())


def line_of(op) -> int:
    return op.span.line if op.span else 0


@rule("G301", *ALL)
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


@rule("G302", *ALL)
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


@rule("G303", *ALL)
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


@rule("G304", *ALL)
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
