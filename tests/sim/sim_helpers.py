"""Small builders for hand-written IR programs in the simulator's tests."""

from __future__ import annotations

from mcc.compiler import ir
from mcc.compiler.span import Span

U = ir.Unit
P = ir.MotionParam


def at(line: int) -> Span:
    return Span("prog", line, 1, line, 10)


def c(value, unit=U.NONE) -> ir.Const:
    return ir.Const(value, unit)


def steps(value) -> ir.Const:
    return ir.Const(value, U.STEPS)


def speed(axis: str, value, line: int = 1) -> ir.SetMotion:
    return ir.SetMotion(P.MAX_SPEED, axis, ir.Const(value, U.STEPS_PER_S), at(line))


def accel(axis: str, value, line: int = 1) -> list[ir.SetMotion]:
    return [ir.SetMotion(P.ACCEL, axis, ir.Const(value, U.STEPS_PER_S2), at(line)),
            ir.SetMotion(P.DECEL, axis, ir.Const(value, U.STEPS_PER_S2), at(line))]


def move(axis: str, target, mode=ir.MoveMode.ABSOLUTE, line: int = 1) -> ir.Move:
    return ir.Move(mode, ((axis, steps(target)),), span=at(line))


def inp(n: int) -> ir.Status:
    return ir.Status("input", index=n)


def eq(left, right) -> ir.Compare:
    return ir.Compare("=", left, right if not isinstance(right, int) else c(right))


def module(*blocks, routines=(), dialect: str = "arcus", variables=None, steps_per_rev: int = 4000) -> ir.Module:
    """A module whose main routine is `blocks`: each a (label, ops, terminator) triple, or a list
    of operations (one block ending the program)."""
    made = []
    for n, item in enumerate(blocks):
        if isinstance(item, tuple):
            label, ops, term = item
        else:
            label, ops, term = f"m{n}", item, ir.End()
        made.append(ir.Block(label, list(ops), term))
    main = ir.Routine("main", ir.RoutineKind.MAIN, made)
    vars_ = {name: ir.Variable(name, vtype) for name, vtype in (variables or {}).items()}
    return ir.Module(dialect, "", vars_, [main, *routines], steps_per_rev=steps_per_rev)


def sub(name: str, ops, term=None, kind=ir.RoutineKind.SUBROUTINE) -> ir.Routine:
    return ir.Routine(name, kind, [ir.Block(f"{name}_0", list(ops), term or ir.Return())])


def kinds(trace, *wanted: str) -> list:
    return [e for e in trace.events if e.kind in wanted]
