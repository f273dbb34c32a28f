"""What the rules written once over the IR share: the readings and operations they follow, and
the walk over a routine's reachable operations with the data-flow state before each.
"""

from __future__ import annotations

from typing import Any, Iterable

from mcc.compiler import ir
from mcc.compiler.lint import flow

# Readings of whether an axis still moves (polling one is a way of waiting).
MOTION_FLAGS = ("moving", "moving_to_position", "motor_status")
MOTION = (ir.Move, ir.Arc, ir.Slew, ir.Home)
TERMINATORS = (ir.Branch, ir.Jump, ir.Return, ir.End, ir.FallOff, ir.GotoRoutine)


def reads(item) -> Iterable:
    if item is None:
        return ()
    return flow.term_reads(item) if isinstance(item, TERMINATORS) else flow.op_reads(item)


def const(expr) -> float | None:
    return expr.value if isinstance(expr, ir.Const) else None


def motion_axes(op) -> tuple[str, ...]:
    """The axes an operation sets moving."""
    if isinstance(op, ir.Move):
        return tuple(axis for axis, _ in op.targets)
    if isinstance(op, ir.Arc):
        return op.axes
    if isinstance(op, (ir.Slew, ir.Home)):
        return (op.axis,)
    return ()


def same_axis(a: str, b: str) -> bool:
    """Two axis names that may be the same axis: equal, or one of them every axis / unaddressed."""
    return a == b or a in (ir.ALL_AXES, "") or b in (ir.ALL_AXES, "")


def walk(routine: ir.Routine, states: dict, transfer) -> Iterable[tuple[object, Any]]:
    """Every reachable operation and terminator of a routine with the state just before it."""
    for block in routine.blocks:
        if block.label in states:
            yield from flow.replay(block, states[block.label], transfer)
