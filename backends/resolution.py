"""Choosing the target's step resolution so that a program's positions convert exactly (issue 24).

A program of another dialect counts positions in its own steps per revolution; the target counts
in its own. When the program does not fix its resolution (MCode `MS`, X150 `CUR`) and the
profile's resolution would put a position between two target steps, the backend may set a
resolution of its choosing that the target accepts (X150 CUR 1-32,767, parker-x150.md L734; MCode
MS one of its fixed codes, lexium-mcode.txt L4282-L4340): the motor's travel per revolution is the
same, only the unit changes. The choice, in order of preference:

1. the source's own steps per revolution: every position is the same number, even one computed at
   run time;
2. a resolution that is a whole multiple of the source's (factor 2, 3, ...): a position computed at
   run time is multiplied by a whole number, which the target can write;
3. (only when every position is a constant) a whole fraction of the source's (1/2, 1/3, ...,
   the finest first), else any that makes each constant whole, the nearest to the source's first.

Nothing is chosen (None) when the profile's resolution already converts everything exactly, or
when no legal value does: the backend then refuses each position with its line as before.
"""
from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction

from mcc.compiler import ir, units


@dataclass
class Positions:
    constants: list  # every constant in steps the program writes (targets, positions, comparisons)
    computed: bool  # a position computed at run time (a variable target, a position reading)
    fixed: bool  # the program sets its resolution itself (MS, CUR)


def positions(module: ir.Module) -> Positions:
    found = Positions([], False, False)
    for _, block in module.blocks():
        for op in block.ops:
            if isinstance(op, ir.SetMotion) and op.param is ir.MotionParam.RESOLUTION:
                found.fixed = True
            exprs = list(ir.op_exprs(op))
            for expr in exprs + list(ir.term_exprs(block.terminator)):
                for node in ir.walk_expr(expr):
                    if isinstance(node, ir.Const) and node.unit is ir.Unit.STEPS:
                        found.constants.append(node.value)
                    elif isinstance(node, ir.Status) and node.meaning in ("position", "encoder"):
                        found.computed = True
            if isinstance(op, (ir.Move, ir.SetPosition)) and any(not isinstance(e, ir.Const) for e in exprs):
                found.computed = True
    return found


def exact(found: Positions, factor: Fraction) -> bool:
    """Every position converts to whole target steps with `factor` (target/source)."""
    if found.computed and factor.denominator != 1:
        return False
    return all(units.scale_steps(v, factor).exact for v in found.constants)


def exact_at(found: Positions, source_spr: int, target_spr: int, whole: list[int] | None) -> bool:
    """`exact(found, units.ratio(source_spr, target_spr))` in integers, for the scan of every
    candidate (X150 CUR has 32,767: with Fractions the scan took about a second per compile, issue
    26). `whole`: the distinct constants as integers, None when one is not a whole number."""
    if source_spr <= 0 or target_spr <= 0 or source_spr == target_spr:
        return True  # a factor of 1: every position stays what it is
    if found.computed and target_spr % source_spr:
        return False
    if whole is None:
        return False  # a fraction of a step only converts exactly with a factor of 1
    return all(value * target_spr % source_spr == 0 for value in whole)


def whole_constants(found: Positions) -> list[int] | None:
    """The distinct constants as integers (as `units.scale_steps` reads them), None if one is not whole."""
    values = set()
    for value in found.constants:
        if not (isinstance(value, int) or float(value).is_integer()):
            return None
        values.add(int(value))
    return sorted(values, key=lambda v: (v == 0, v))  # a zero converts with any factor: last


def choose(source_spr: int, current: int, candidates: list[int], found: Positions) -> int | None:
    """A steps-per-revolution of `candidates` for the target, or None (keep `current`)."""
    if not source_spr or found.fixed or exact(found, units.ratio(source_spr, current)):
        return None
    whole = whole_constants(found)
    fitting = [c for c in candidates if exact_at(found, source_spr, c, whole)]
    if not fitting:
        return None

    def rank(spr: int) -> tuple:
        factor = units.ratio(source_spr, spr)
        return (factor != 1, factor.denominator != 1, factor.numerator != 1, abs(factor - 1), -spr)

    return min(fitting, key=rank)
