"""Divisions whose quotient the target would round otherwise than the source (issue 23).

The products round an integer quotient differently: MCode rounds down (lexium-mcode.txt L1249:
-7/2 is -4), Arcus truncates toward zero (a decision, docs/decisions/0008), X150 variables hold
decimals and keep the fraction (parker-x150.md L4569-L4573: -7/2 is -3.5). Each profile says its
rule in `[machine.arithmetic] integer_division`; a dialect whose variables are decimal computes a
quotient exactly. A backend writes `a / b` as it is, so a conversion between two rules would write
a program that computes another value. This module finds those divisions before anything is
written and refuses each one (G040) on its line, unless the two rules give the same quotient:

- the rules agree (same product family, or a same-dialect compile);
- between `floor` and `truncate`: both operands are provably non-negative (constants, `abs`);
- between an exact (decimal) rule and an integer one: the quotient is a whole number by
  construction (the divisor is the constant 1 or -1, or both operands are constants that divide).

The remainder `%` goes with the quotient (`a - (a / b) * b`, sim/values.py), so between `floor`
and `truncate` it is checked the same way. An expression computed in floating point (assigned to
a float64 variable, or reading one: MCode F1-F8) keeps the fraction as a decimal one does, so it
follows the `exact` rule.

Rewriting a division so that the target computes the source's rounding with its own operators
(docs/CROSS.md, "Integer division") is not done: it needs statements inserted around an
expression in each backend; the refusal says how to make the program convertible instead.
"""

from __future__ import annotations

from dataclasses import dataclass

from mcc.compiler import ir
from mcc.compiler.span import Span

CODE = "G040"
EXACT = "exact"
# What each rule does to -7/2, for the message.
EXAMPLE = {"floor": "-4 (rounded down)", "truncate": "-3 (truncated toward zero)", EXACT: "-3.5 (kept exact)"}


def rounding(profile, dialect: str) -> str:
    """How the product rounds an integer quotient: the profile's `[machine.arithmetic]
    integer_division` (`floor`, `truncate`, or `exact` for decimal variables, the X150's), else
    `truncate` (the simulator's default, sim/interpreter.py). `dialect` names the product's
    language for the messages; the rule itself is the profile's data."""
    table = profile.get("machine.arithmetic", {}) if profile is not None else {}
    rule = table.get("integer_division") if isinstance(table, dict) else None
    return str(rule) if rule in ("floor", "truncate", EXACT) else "truncate"


@dataclass(frozen=True)
class Refusal:
    span: Span | None
    message: str


def non_negative(expr) -> bool:
    """Whether `expr` is provably >= 0 by its shape alone: a constant, `abs(...)`, or a sum,
    product or quotient of such. (There is no sign analysis of variables in compiler/.)"""
    if isinstance(expr, ir.Const):
        return isinstance(expr.value, (int, float)) and expr.value >= 0
    if isinstance(expr, ir.Func):
        return expr.name == "abs"
    if isinstance(expr, ir.BinOp) and expr.op in ("+", "*", "/"):
        return non_negative(expr.left) and non_negative(expr.right)
    return False


def constant(expr) -> int | float | None:
    """The value of a constant operand (a negated constant too), else None."""
    if isinstance(expr, ir.Const) and isinstance(expr.value, (int, float)):
        return expr.value
    if isinstance(expr, ir.UnOp) and expr.op == "-":
        inner = constant(expr.operand)
        return -inner if inner is not None else None
    return None


def whole_quotient(node: ir.BinOp) -> bool:
    """Whether the quotient has no fraction whatever the operands' values are: a divisor of 1 or
    -1, or two constants that divide exactly."""
    divisor, dividend = constant(node.right), constant(node.left)
    if divisor in (1, -1):
        return True
    return divisor not in (None, 0) and dividend is not None and float(dividend / divisor).is_integer()


def same_quotient(node: ir.BinOp, source: str, target: str) -> bool:
    """Whether the two rounding rules give the same value for this division or remainder."""
    if source == target or whole_quotient(node):
        return True
    signless = non_negative(node.left) and non_negative(node.right)
    if EXACT not in (source, target):  # floor and truncate differ only below zero
        return signless
    if node.op == "%" and source != EXACT:
        # an integer remainder in decimals keeps the dividend's sign, as truncation does
        return source == "truncate" or signless
    return False  # a quotient's fraction (or a decimal remainder) is kept on one side only


def is_float(module: ir.Module, expr, context: ir.VarType | None) -> bool:
    """Whether the expression computes in floating point: it is assigned to a float64 variable or
    reads one (sim/values.py, `real`)."""
    if context is ir.VarType.FLOAT64:
        return True
    return any(isinstance(n, ir.Var) and module.type_of(n.name) is ir.VarType.FLOAT64
               for n in ir.walk_expr(expr))


def divisions(module: ir.Module):
    """(division node, the span of the statement it is in, the assigned variable's type) for each
    `/` and `%` in the module."""
    for routine in module.routines:
        for block in routine.blocks:
            for op in block.ops:
                context = module.type_of(op.target.name) if isinstance(op, ir.Assign) else None
                for expr in ir.op_exprs(op):
                    for node in ir.walk_expr(expr):
                        if isinstance(node, ir.BinOp) and node.op in ("/", "%"):
                            yield node, getattr(op, "span", None), context, expr
            for expr in ir.term_exprs(block.terminator):
                for node in ir.walk_expr(expr):
                    if isinstance(node, ir.BinOp) and node.op in ("/", "%"):
                        yield node, getattr(block.terminator, "span", None), None, expr


def refusals(module: ir.Module, source_profile, target_profile, target: str) -> list[Refusal]:
    """One refusal per division (or remainder) of `module` whose value the `target` product would
    compute otherwise than the source's product."""
    source_rule = rounding(source_profile, module.dialect)
    target_rule = rounding(target_profile, target)
    if source_rule == target_rule and module.dialect == target:
        return []
    found: list[Refusal] = []
    for node, span, context, expr in divisions(module):
        # an expression in floating point (MCode F1-F8) keeps the quotient's fraction, as decimals do
        rule = EXACT if is_float(module, expr, context) else source_rule
        if same_quotient(node, rule, target_rule):
            continue
        what = "quotient" if node.op == "/" else "remainder"
        exact = EXACT in (rule, target_rule)
        condition = "the quotient is not known to be a whole number" if exact else "an operand may be negative"
        advice = ("divide by 1 or by a constant that divides a constant exactly" if exact else
                  "make both operands non-negative, e.g. divide abs(...) and set the sign apart")
        found.append(Refusal(node.span or span, (
            f"this division's {what} is computed otherwise in {target} than in {module.dialect}: "
            f"{module.dialect} gives -7/2 = {EXAMPLE[rule]}, {target} gives "
            f"{EXAMPLE[target_rule]}, and {condition}; nothing was written ({advice}, "
            f"or compile to {module.dialect})")))
    return found
