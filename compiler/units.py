"""Conversions between the dialects' units and the IR's, in one place.

The IR counts positions in steps of `Module.steps_per_rev` per revolution, speeds in steps/s,
accelerations in steps/s², times in seconds (docs/ARCHITECTURE.md, "Units"). The dialects do not:

| dialect | position | speed | acceleration | times |
|---|---|---|---|---|
| MCode | microsteps (MS per full step) | steps/s | steps/s² | ms (`H 100`) |
| X150 | user steps (CUR per rev) | rev/s | rev/s² | s |
| Arcus | pulses | pulses/s | a ramp time in ms (`ACC`) | ms |

Frontends convert into the IR with these functions and backends convert back with their target
profile. A conversion that cannot be exact (a position that falls between two target steps) is
reported by the caller with the value, never rounded silently: `scale_steps` says whether it is.
"""

from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction

MS_PER_S = 1000


@dataclass(frozen=True)
class Scaled:
    value: int | float
    exact: bool


def revs_to_steps(revs: float, steps_per_rev: int) -> float:
    return revs * steps_per_rev


def steps_to_revs(steps: float, steps_per_rev: int) -> float:
    return steps / steps_per_rev


def ms_to_s(ms: float) -> float:
    return ms / MS_PER_S


def s_to_ms(seconds: float) -> float:
    return seconds * MS_PER_S


def ratio(source_steps_per_rev: int, target_steps_per_rev: int) -> Fraction:
    """How many target steps one source step is (1 when either side is unknown: no scaling)."""
    if source_steps_per_rev <= 0 or target_steps_per_rev <= 0:
        return Fraction(1)
    return Fraction(target_steps_per_rev, source_steps_per_rev)


def scale_steps(value: int | float, factor: Fraction) -> Scaled:
    """A position or distance in target steps; `exact` is False when it falls between steps."""
    if factor == 1:
        return Scaled(value, True)
    if isinstance(value, int) or float(value).is_integer():
        scaled = Fraction(int(value)) * factor
        if scaled.denominator == 1:
            return Scaled(int(scaled), True)
        return Scaled(round(scaled), False)
    scaled_float = float(value) * float(factor)
    return Scaled(round(scaled_float), False)


def scale_rate(value: float, factor: Fraction) -> float:
    """A speed or acceleration in target steps per second (per second): rates scale linearly."""
    return float(value) * float(factor) if factor != 1 else value


def accel_from_ramp(ramp_s: float, initial: float, maximum: float) -> float | None:
    """The acceleration (steps/s²) of a ramp from `initial` to `maximum` speed taking `ramp_s`.

    None when the ramp time is zero or negative (an instant change has no finite acceleration).
    """
    if ramp_s <= 0:
        return None
    return abs(maximum - initial) / ramp_s


def ramp_from_accel(accel: float, initial: float, maximum: float) -> float | None:
    """The time (s) to ramp from `initial` to `maximum` speed at `accel` steps/s²."""
    if accel <= 0:
        return None
    return abs(maximum - initial) / accel


def round_to(value: float, step: float) -> float:
    """`value` on a grid of `step` (a device's resolution: 1 step/s, 0.0001 rev/s ...)."""
    if step <= 0:
        return value
    return round(round(value / step) * step, 10)


# ---------------------------------------------------------------------------------------------
# Quantities that are expressions: a delay of `R1` milliseconds is `R1 * 0.001 s` in the IR.


def to_ir(expr, factor: float, unit):
    """`expr` (in a dialect's unit) as an IR quantity: `factor` IR units per dialect unit.

    A constant is converted; any other expression becomes `expr * factor` carrying the unit on
    the factor, which `from_ir` recognises so a backend of the same dialect writes `expr` back.
    """
    from mcc.compiler import ir

    if isinstance(expr, ir.Const):
        value = expr.value * factor
        if isinstance(value, float) and value.is_integer() and isinstance(expr.value, int) and factor >= 1:
            value = int(value)
        return ir.Const(_tidy(value), unit, expr.span)
    return ir.BinOp("*", expr, ir.Const(factor, unit), getattr(expr, "span", None))


def from_ir(expr, factor: float):
    """The inverse of `to_ir`: `expr` in the dialect's unit when `factor` IR units make one.

    Returns a constant, the original expression of a `to_ir` product, or `expr / factor`.
    """
    from mcc.compiler import ir

    if isinstance(expr, ir.Const):
        return ir.Const(_tidy(expr.value / factor), ir.Unit.NONE, expr.span)
    if isinstance(expr, ir.BinOp) and expr.op == "*" and isinstance(expr.right, ir.Const) \
            and expr.right.value == factor:
        return expr.left
    return ir.BinOp("/", expr, ir.Const(factor), getattr(expr, "span", None))


def _tidy(value: int | float) -> int | float:
    """Drop float noise from a unit conversion (0.1 * 1000 = 100.00000000000001 -> 100)."""
    if isinstance(value, float):
        rounded = round(value, 9)
        return int(rounded) if rounded.is_integer() and abs(rounded) < 2 ** 53 else rounded
    return value


def typed_compare(compare):
    """A comparison whose one side is a reading with a unit (a position, a speed) and whose other
    side is a plain constant: the constant takes the reading's unit, so a backend that scales
    positions scales it too (`P > 1000` compares 1000 steps)."""
    from mcc.compiler import ir
    from mcc.compiler.ir_names import status_unit

    left, right = compare.left, compare.right
    if isinstance(left, ir.Status) and isinstance(right, ir.Const) and right.unit is ir.Unit.NONE:
        right = ir.Const(right.value, status_unit(left.meaning), right.span)
    elif isinstance(right, ir.Status) and isinstance(left, ir.Const) and left.unit is ir.Unit.NONE:
        left = ir.Const(left.value, status_unit(right.meaning), left.span)
    else:
        return compare
    return ir.Compare(compare.op, left, right, compare.span)
