"""Constants a 32-bit target variable cannot hold (issue 23's fuzz finding "X150 decimals vs 32-bit
wrap").

An X150 variable holds a decimal number (parker-x150.md L4569-L4573) with no 32-bit limit in the
manual; MCode's user variables are 32-bit integers (lexium-mcode.txt VA), as are the PMX-4EX-SA's
(V1-V100, arcus-pmx-4ex-sa.txt). A value written as constants (`VAR4=46341+2147483000`) that falls
outside that range wraps on the target and keeps its value on the source: the backends refuse it
at its line, upfront, rather than leave it to the validation (S010). A value computed from
variables at run time is the validation's to compare."""
from __future__ import annotations

from mcc.backends import division
from mcc.compiler import ir

INT32 = (-2**31, 2**31 - 1)


def constant(expr) -> int | float | None:
    """The value of an expression made of constants and + - *, else None (a constant operand is
    division.constant's)."""
    if isinstance(expr, ir.UnOp) and expr.op == "-":
        inner = constant(expr.operand)
        return -inner if inner is not None else None
    if isinstance(expr, ir.BinOp) and expr.op in ("+", "-", "*"):
        left, right = constant(expr.left), constant(expr.right)
        if left is None or right is None:
            return None
        return left + right if expr.op == "+" else left - right if expr.op == "-" else left * right
    return division.constant(expr)


def overflow(module: ir.Module, op: ir.Assign) -> str | None:
    """Why the target cannot hold what `op` assigns, where the source holds a decimal there."""
    if module.type_of(op.target.name) is not ir.VarType.DECIMAL:
        return None
    value = constant(op.value)
    if value is None or INT32[0] <= value <= INT32[1]:
        return None
    text = str(int(value)) if float(value).is_integer() else str(value)
    return (f"the value {text}, outside the 32-bit whole numbers a variable of the target holds "
            f"({INT32[0]} to {INT32[1]}; the source keeps it as a decimal: keep it in range)")
