"""Breakpoint conditions, hit counts and watch expressions, evaluated on a paused simulator.

An expression is written the way the three dialects agree on: the program's variables by name
(`Q1`, `V3`, `VAR1`, case-insensitive), numbers, + - * / %, comparisons (= or ==, <> or !=, <,
<=, >, >=), AND / OR / NOT (either case), parentheses, and what the machine shows:

    time            the virtual time in seconds
    input(n)        input n's logic state (1 active), through the polarity in force
    output(n)       output n (0 or 1)
    position(a)     axis a's position in steps (position(X), position(1))
    speed(a)        axis a's speed in steps/s

Python's `ast` parses it after the dialect spellings are turned into Python's; only the nodes
above are evaluated, so an expression cannot call or import anything else.
"""

from __future__ import annotations

import ast
import operator
import re
from dataclasses import dataclass

OPERATORS = {ast.Add: operator.add, ast.Sub: operator.sub, ast.Mult: operator.mul, ast.Div: operator.truediv,
             ast.Mod: operator.mod, ast.FloorDiv: operator.floordiv}
COMPARISONS = {ast.Eq: operator.eq, ast.NotEq: operator.ne, ast.Lt: operator.lt, ast.LtE: operator.le,
               ast.Gt: operator.gt, ast.GtE: operator.ge}
FUNCTIONS = ("input", "output", "position", "speed")


class ExpressionError(Exception):
    """An expression that cannot be read or evaluated: the message says what to write instead."""


def to_python(text: str) -> str:
    """The dialects' spellings (`=`, `<>`, AND/OR/NOT) in Python's."""
    text = re.sub(r"<>", "!=", text)
    text = re.sub(r"(?<![<>!=])=(?!=)", "==", text)
    return re.sub(r"\b(AND|OR|NOT)\b", lambda m: m.group(1).lower(), text, flags=re.IGNORECASE)


@dataclass
class Machine:
    """What an expression may read: the simulator's state at the pause."""

    simulator: object

    def variable(self, name: str):
        variables = self.simulator.vars
        if name in variables:
            return variables[name]
        for key, value in variables.items():
            if key.lower() == name.lower():
                return value
        if name.lower() in ("time", "t"):
            return self.simulator.now
        raise ExpressionError(f"'{name}' is not a variable of the program (the Variables view lists them; "
                              f"the machine is read with {', '.join(f + '(...)' for f in FUNCTIONS)} or time)")

    def call(self, name: str, argument):
        sim = self.simulator
        if name == "input":
            return sim.input_logic(int(argument))
        if name == "output":
            return int(sim.machine.outputs.get(int(argument), 0))
        axis = sim.machine.axes.get(str(argument))
        if axis is None:
            known = ", ".join(sorted(sim.machine.axes)) or "none yet"
            raise ExpressionError(f"no axis '{argument}' (axes: {known})")
        return axis.at(sim.now) if name == "position" else axis.speed(sim.now)


def evaluate(text: str, machine: Machine):
    """The value of `text`; ExpressionError when it cannot be read or evaluated."""
    try:
        tree = ast.parse(to_python(text.strip()), mode="eval")
    except (SyntaxError, ValueError, RecursionError, MemoryError):
        raise ExpressionError(f"cannot read '{text}': write e.g. Q1 > 3 AND input(1) = 1") from None
    try:
        return _eval(tree.body, machine)
    except ZeroDivisionError:
        raise ExpressionError(f"'{text}' divides by zero") from None
    except (TypeError, ValueError, ArithmeticError, RecursionError) as exc:
        raise ExpressionError(f"cannot evaluate '{text}': {exc}") from None


def _eval(node: ast.AST, machine: Machine):
    if isinstance(node, ast.Constant) and isinstance(node.value, (int, float)) and not isinstance(node.value, bool):
        return node.value
    if isinstance(node, ast.Name):
        return machine.variable(node.id)
    if isinstance(node, ast.BinOp) and type(node.op) in OPERATORS:
        return OPERATORS[type(node.op)](_num(_eval(node.left, machine)), _num(_eval(node.right, machine)))
    if isinstance(node, ast.UnaryOp) and isinstance(node.op, (ast.USub, ast.UAdd, ast.Not)):
        value = _eval(node.operand, machine)
        if isinstance(node.op, ast.Not):
            return int(not value)
        return -_num(value) if isinstance(node.op, ast.USub) else _num(value)
    if isinstance(node, ast.BoolOp):
        values = [_eval(v, machine) for v in node.values]
        return int(all(values) if isinstance(node.op, ast.And) else any(values))
    if isinstance(node, ast.Compare):
        left = _num(_eval(node.left, machine))
        for op, right_node in zip(node.ops, node.comparators):
            right = _num(_eval(right_node, machine))
            if type(op) not in COMPARISONS or not COMPARISONS[type(op)](left, right):
                return 0
            left = right
        return 1
    if isinstance(node, ast.Call) and isinstance(node.func, ast.Name) and node.func.id.lower() in FUNCTIONS \
            and len(node.args) == 1 and not node.keywords:
        arg = node.args[0]
        value = arg.id if isinstance(arg, ast.Name) else _eval(arg, machine)
        return machine.call(node.func.id.lower(), value)
    raise ExpressionError(f"'{ast.unparse(node)}' is not allowed here: use variables, numbers, arithmetic, "
                          f"comparisons, AND/OR/NOT and {', '.join(f + '(...)' for f in FUNCTIONS)}")


def _num(value):
    from decimal import Decimal

    return float(value) if isinstance(value, Decimal) else value


HIT = re.compile(r"\s*(==|>=|>|%)?\s*(\d+)\s*\Z")


def hit_condition_error(text: str) -> str | None:
    """Why a hit condition cannot be read, or None."""
    return None if HIT.match(text) else (f"hit count '{text}' is not understood: write N (stop at the Nth hit), "
                                          ">= N, > N or % N (every Nth hit)")


def hit_matches(text: str, hits: int) -> bool:
    """Whether the `hits`-th hit stops: 'N' and '== N' the Nth, '>= N', '> N', '% N' every Nth."""
    found = HIT.match(text)
    if found is None:
        return True
    op, n = found.group(1) or "==", int(found.group(2))
    if op == "%":
        return n > 0 and hits % n == 0
    return {"==": hits == n, ">=": hits >= n, ">": hits > n}[op]
