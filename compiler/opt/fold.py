"""Constant folding and propagation (within each block).

What it does: an operator applied to constants becomes the constant (`V1 = 4 * 250` becomes
`V1 = 1000`), and a variable assigned a constant is read as that constant by the assignments,
outputs and branch conditions that follow it in the same block (`V1 = 1000` then `V2 = V1 + 1`
becomes `V2 = 1001`). Where the value carries a unit (a move target, a speed, a delay) a variable
is never replaced by a constant: the variable's plain number would have to become a constant in
steps, which a backend converting to another dialect scales where it would not scale the variable.

Why it is safe: folding only happens where every dialect computes the same result: integers whose
result fits in 32 bits without wrapping, an exact integer division, bitwise operators on integers,
and units that agree; floating-point results are never folded (the dialects round differently).
The arithmetic is the simulator's (`sim/values.py`). Only an int32 variable (the type the lowering
declares) is taken as a known constant: a float register holding 142.0 prints and divides as a
float (MCode F1-F8).
A known value is forgotten at a call or a native command (either may assign any variable), and a
variable an event handler assigns is never taken as known (a handler can run between any two
operations). The assignment itself stays: a host may read the variable.

Needs: nothing beyond the block itself. Keeps every analysis except values in force.
"""

from __future__ import annotations

from mcc.compiler import ir
from mcc.compiler.opt.common import clobbers_everything, handler_writes
from mcc.sim import values

NAME = "fold"
NEEDS = ()
INT32 = (-(2 ** 31), 2 ** 31 - 1)


def run(module: ir.Module, context) -> int:
    volatile, _ = handler_writes(module)
    changed = 0
    for _, block in module.blocks():
        known: dict[str, ir.Const] = {}
        for index, op in enumerate(block.ops):
            new = rewrite_op(op, known)
            if new is not op:
                block.ops[index] = new
                changed += 1
            op = block.ops[index]
            if clobbers_everything(op):
                known.clear()
            elif isinstance(op, ir.Assign):
                name = op.target.name
                known.pop(name, None)
                if isinstance(op.value, ir.Const) and name not in volatile and integer(module, name) and \
                        isinstance(op.value.value, int):
                    known[name] = op.value
        term = block.terminator
        if isinstance(term, ir.Branch):
            cond = fold_cond(term.cond, known)
            if cond is not term.cond:
                term.cond = cond
                changed += 1
    return changed


def integer(module: ir.Module, name: str) -> bool:
    """Whether `name` is an int32 variable or register (the type the lowering declares; a name the
    module does not type is an integer, as in every dialect's default). A float64 register (MCode
    F1-F8) holding 142.0 is not the integer 142: `PR F3` prints 142.000000, `F3/3` divides in floating
    point (lexium-mcode.txt L1249, L2802-L2815)."""
    vtype = module.type_of(name)
    return vtype is None or vtype is ir.VarType.INT32


def rewrite_op(op, known: dict[str, ir.Const]):
    """The operation with its expressions folded, or `op` itself when nothing changed."""
    if isinstance(op, ir.Native):
        return op
    if isinstance(op, ir.Assign):
        value = fold(op.value, known)
        return op if value is op.value else ir.Assign(op.target, value, op.span)
    if isinstance(op, (ir.SetMotion, ir.SetPosition, ir.Setting)):
        value = fold(op.value, unitless(known))
        if value is op.value:
            return op
        copy = _copy(op)
        copy.value = value
        return copy
    if isinstance(op, ir.Delay):
        value = fold(op.duration, unitless(known))
        return op if value is op.duration else ir.Delay(value, op.span)
    if isinstance(op, ir.Move):
        known = unitless(known)
        targets = tuple((axis, fold(v, known)) for axis, v in op.targets)
        if all(new is old for (_, new), (_, old) in zip(targets, op.targets)):
            return op
        return ir.Move(op.mode, targets, op.options, op.span)
    if isinstance(op, ir.SetOutput):
        value = fold(op.value, known)
        return op if value is op.value else ir.SetOutput(op.index, value, op.span)
    return op


def unitless(known: dict) -> dict:
    """What may be substituted where the value carries a unit (a move target, a speed, a delay):
    a variable holds a plain number read in the IR's unit at that place, but a constant there must
    carry the unit (a backend scales it to the target's steps), so only copies of variables are
    substituted, never constants."""
    if not known or not any(isinstance(v, ir.Const) for v in known.values()):
        return known
    return {k: v for k, v in known.items() if isinstance(v, ir.Var)}


def _copy(op):
    import copy
    return copy.copy(op)


def fold(expr, known: dict):
    """`expr` with known variables replaced (by a constant, or by the variable they copy) and
    constant operators computed (iterative)."""
    if isinstance(expr, ir.Var):
        found = known.get(expr.name)
        if isinstance(found, ir.Const):
            return ir.Const(found.value, found.unit, expr.span)
        if isinstance(found, ir.Var):
            return ir.Var(found.name, expr.span)
        return expr
    if not isinstance(expr, (ir.BinOp, ir.UnOp)):
        return expr
    # Post-order over the operator tree with an explicit stack (long generated expressions).
    results: dict[int, object] = {}
    stack: list[tuple[object, bool]] = [(expr, False)]
    while stack:
        node, done = stack.pop()
        if isinstance(node, ir.BinOp):
            if not done:
                stack += [(node, True), (node.right, False), (node.left, False)]
                continue
            left, right = results.pop(id(node.left), node.left), results.pop(id(node.right), node.right)
            results[id(node)] = combine(node, left, right)
        elif isinstance(node, ir.UnOp):
            if not done:
                stack += [(node, True), (node.operand, False)]
                continue
            operand = results.pop(id(node.operand), node.operand)
            results[id(node)] = negate(node, operand)
        elif isinstance(node, ir.Var):
            results[id(node)] = fold(node, known)
    return results.get(id(expr), expr)


def combine(node: ir.BinOp, left, right):
    if isinstance(left, ir.Const) and isinstance(right, ir.Const):
        value = compute(node.op, left, right)
        if value is not None:
            return ir.Const(value[0], value[1], node.span)
    if left is node.left and right is node.right:
        return node
    return ir.BinOp(node.op, left, right, node.span)


def compute(op: str, left: ir.Const, right: ir.Const):
    a, b = left.value, right.value
    if not (isinstance(a, int) and isinstance(b, int)) or isinstance(a, bool) or isinstance(b, bool):
        return None
    unit = unit_of(op, left.unit, right.unit)
    if unit is None:
        return None
    if op == "/" and (b == 0 or a % b != 0):
        return None  # only an exact quotient: the dialects round an inexact one differently
    if op not in ("+", "-", "*", "/") and not (op in ("&", "|", "^") and unit is ir.Unit.NONE):
        return None
    value = values.binary(op, a, b)  # the simulator's arithmetic (sim/values.py)
    if not INT32[0] <= value <= INT32[1]:
        return None
    return value, unit


def unit_of(op: str, left: ir.Unit, right: ir.Unit) -> ir.Unit | None:
    if op in ("+", "-", "&", "|", "^"):
        return left if left == right else None
    if op == "*":
        if left is ir.Unit.NONE:
            return right
        return left if right is ir.Unit.NONE else None
    if op == "/":
        if right is ir.Unit.NONE:
            return left
        return ir.Unit.NONE if left == right else None
    return None


def negate(node: ir.UnOp, operand):
    if node.op == "-" and isinstance(operand, ir.Const) and isinstance(operand.value, int) \
            and INT32[0] <= -operand.value <= INT32[1]:
        return ir.Const(-operand.value, operand.unit, node.span)
    return node if operand is node.operand else ir.UnOp(node.op, operand, node.span)


def fold_cond(cond, known):
    if isinstance(cond, ir.Compare):
        left, right = fold(cond.left, known), fold(cond.right, known)
        if left is cond.left and right is cond.right:
            return cond
        return ir.Compare(cond.op, left, right, cond.span)
    return cond


def decide(cond) -> bool | None:
    """The value of a comparison of two constants of the same unit, or None."""
    if isinstance(cond, ir.Compare) and isinstance(cond.left, ir.Const) and isinstance(cond.right, ir.Const) \
            and cond.left.unit == cond.right.unit:
        a, b = cond.left.value, cond.right.value
        return {"=": a == b, "!=": a != b, "<": a < b, "<=": a <= b, ">": a > b, ">=": a >= b}.get(cond.op)
    return None
