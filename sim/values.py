"""Each dialect's arithmetic on the IR's values.

A value is an `int` (an int32 variable, an integer constant), a `float` (a float64 variable, a
reading or a constant with a fraction) or a `Decimal` (an X150 decimal variable). The operators
mean what `ir_names.BINARY_OPS` says:

- `/` of two integers truncates toward zero (`%` keeps the dividend's sign), or rounds down where
  the product's profile says `integer_division = "floor"` (MCode, lexium-mcode.txt L1249);
- an expression assigned to a float64 variable computes in floating point (`real`);
- an int32 variable wraps to 32 bits when it is assigned (two's complement);
- decimal values compute exactly (Python's `decimal`, 28 digits) and are rounded to
  `DECIMAL_PLACES` when stored, so `10 / 3` is `3.333333` in an X150 variable;
- X150's strict left-to-right evaluation is already the shape of the expression tree its frontend
  builds: the interpreter evaluates a tree as written, left operand first.
"""

from __future__ import annotations

import math
from decimal import Decimal, InvalidOperation

from mcc.compiler.ir import VarType

Number = int | float | Decimal
DECIMAL_PLACES = Decimal("0.000001")
INT32_MIN, INT32_MAX = -(2 ** 31), 2 ** 31 - 1


class ArithmeticFault(Exception):
    """A runtime arithmetic error (division by zero, an undefined function value)."""


def wrap32(value: int) -> int:
    return (value + 2 ** 31) % 2 ** 32 - 2 ** 31


def store(value: Number, vtype: VarType) -> Number:
    """The value as a variable of `vtype` holds it."""
    if vtype is VarType.INT32:
        if isinstance(value, float) and not math.isfinite(value):
            raise ArithmeticFault(f"{value} does not fit an int32 variable")
        return wrap32(int(value))
    if vtype is VarType.DECIMAL:
        try:
            return Decimal(str(value) if isinstance(value, float) else value).quantize(DECIMAL_PLACES)
        except InvalidOperation:
            raise ArithmeticFault(f"{value} does not fit a decimal variable") from None
    return float(value)


def _pair(a: Number, b: Number) -> tuple[Number, Number]:
    """Bring two operands to a common kind: float wins, then Decimal, then int."""
    if isinstance(a, float) or isinstance(b, float):
        return float(a), float(b)
    if isinstance(a, Decimal) or isinstance(b, Decimal):
        return Decimal(a), Decimal(b)
    return a, b


def real(value: Number) -> Number:
    """An operand of a floating-point expression (one assigned to a float64 variable)."""
    return float(value) if isinstance(value, int) else value


def float_text(value: float, fmt, pad: bool = False) -> str:
    """A float as the product prints it with the format `fmt` = [width, decimals, notation,
    justification] (MCode PF, lexium-mcode.txt L4744-L4777; default 10,6,0,0 prints 1.2 as
    `1.200000`, PF=8,4,1,1 prints 0 as `0.0000E+00`). `pad`: fill to the width, right- or
    left-justified; the manual's examples show no padding, so the profiles leave it off."""
    width, decimals, notation, justify = (list(fmt) + [10, 6, 0, 0][len(fmt):])[:4]
    text = f"{value:.{int(decimals)}{'E' if notation else 'f'}}"
    if pad:
        text = text.ljust(int(width)) if justify else text.rjust(int(width))
    return text


def float_format(text) -> list[int] | None:
    """A float format given as text `width,decimals,notation,justification` (MCode `PF=8,4,1,1`,
    lexium-mcode.txt L4744-L4777): the numbers, or None when the text is not such a format. A
    missing part keeps the default (10,6,0,0)."""
    try:
        parts = [int(p) for p in str(text).split(",") if p.strip()]
    except ValueError:
        return None
    if not 0 < len(parts) <= 4 or any(not 0 <= p <= 32 for p in parts):
        return None
    return parts + [10, 6, 0, 0][len(parts):]


def binary(op: str, a: Number, b: Number, division: str = "truncate") -> Number:
    """`a op b`. `division`: how an integer quotient rounds, "truncate" (toward zero) or "floor"
    (rounded down, toward minus infinity: MCode, lexium-mcode.txt L1249); the remainder `%` goes
    with it (a - quotient * b)."""
    if op in ("&", "|", "^", "<<", ">>"):
        x, y = int(a), int(b)
        if op == "&":
            return wrap32(x & y)
        if op == "|":
            return wrap32(x | y)
        if op == "^":
            return wrap32(x ^ y)
        if y < 0 or y > 63:
            raise ArithmeticFault(f"shift by {y}")
        return wrap32(x << y) if op == "<<" else wrap32(x) >> y
    x, y = _pair(a, b)
    if op == "+":
        return x + y
    if op == "-":
        return x - y
    if op == "*":
        return x * y
    if op in ("/", "%"):
        if y == 0:
            raise ArithmeticFault("division by zero")
        if isinstance(x, int):
            if division == "floor":
                quotient = x // y
            else:
                quotient = abs(x) // abs(y) * (1 if (x >= 0) == (y >= 0) else -1)
            return quotient if op == "/" else x - quotient * y
        if op == "/":
            return x / y
        return math.fmod(x, y) if isinstance(x, float) else x % y  # Decimal % keeps the sign too
    raise ArithmeticFault(f"unknown operator '{op}'")


def unary(op: str, a: Number) -> Number:
    if op == "-":
        return -a
    if op == "~":
        return wrap32(~int(a))
    if op == "!":
        return 1 if a == 0 else 0
    raise ArithmeticFault(f"unknown operator '{op}'")


def function(name: str, args: list[Number], radians: bool = False) -> Number:
    """`name(args)`; `radians`: the trigonometric functions take and give radians, not degrees
    (the setting `trig_radians`: MCode RA, default radians, lexium-mcode.txt L5107)."""
    if name == "pi":
        return math.pi
    if not args:
        raise ArithmeticFault(f"{name}() needs an argument")
    x = args[0]
    if name == "abs":
        return abs(x)
    if name == "int":
        return int(x)
    v = float(x)
    try:
        if name == "sqrt":
            return math.sqrt(v)
        if name in ("sin", "cos", "tan"):
            return getattr(math, name)(v if radians else math.radians(v))
        if name in ("asin", "acos", "atan"):
            angle = getattr(math, name)(v)
            return angle if radians else math.degrees(angle)
        if name == "log":
            return math.log(v)
        if name == "log10":
            return math.log10(v)
        if name == "log2":
            return math.log2(v)
        if name == "exp":
            return math.exp(v)
    except (ValueError, OverflowError):
        raise ArithmeticFault(f"{name}({x}) is undefined") from None
    raise ArithmeticFault(f"unknown function '{name}'")


def compare(op: str, a: Number, b: Number) -> bool:
    x, y = _pair(a, b)
    if op == "=":
        return x == y
    if op == "!=":
        return x != y
    if op == "<":
        return x < y
    if op == "<=":
        return x <= y
    if op == ">":
        return x > y
    if op == ">=":
        return x >= y
    raise ArithmeticFault(f"unknown comparison '{op}'")


def plain(value: Number) -> int | float:
    """A JSON-friendly number: Decimal becomes float (or int when whole)."""
    if isinstance(value, Decimal):
        return int(value) if value == value.to_integral_value() else float(value)
    return value


def formatted(value: Number, spec: str, signed: bool = False) -> str:
    """`value` printed in the print format `spec` (ir_names.PRINT_FORMATS; docs/IR.md, "Print
    formats"): `fixed p` keeps p digits after the point and drops the others (toward zero),
    `magnitude` leaves the sign out, `signed` writes it always (`+` for zero and positive
    numbers); `bits n` is n binary digits, bit 0 first; `pad n` an integer with leading zeros."""
    words = spec.split()
    kind, size = words[0], int(words[1])
    if kind == "bits":
        mask = int(value)
        return "".join("1" if mask >> bit & 1 else "0" for bit in range(size))
    if kind == "pad":
        number = int(value)
        text = str(abs(number)).rjust(size, "0")
        return ("-" if number < 0 else "+" if signed else "") + text
    exact = Decimal(str(value)) if isinstance(value, float) else Decimal(value)
    kept = exact.quantize(Decimal(1).scaleb(-size), rounding="ROUND_DOWN")
    text = f"{abs(kept):f}"
    if "magnitude" in words[2:]:
        return text
    negative = kept < 0
    return ("-" if negative else "+" if signed else "") + text
