"""A hypothesis strategy for random *valid* IR programs (not text): the verifier accepts every one.

Programs are a main routine of blocks that only jump forward (so every run ends), with a
subroutine it may call; operations draw from assignments with int32 arithmetic, motion settings in
the IR's units, absolute and relative moves on one or two axes, waits, delays, outputs and prints.
"""

from __future__ import annotations

from hypothesis import strategies as st

from mcc.compiler import ir

U = ir.Unit
VARS = ("V1", "V2", "V3")
AXES = ("X", "Y")


def const(value, unit=U.NONE) -> ir.Const:
    return ir.Const(value, unit)


@st.composite
def exprs(draw, depth: int = 2):
    leaves = st.one_of(st.integers(-1000, 1000).map(const), st.sampled_from(VARS).map(ir.Var))
    if depth <= 0:
        return draw(leaves)
    return draw(st.one_of(leaves, st.builds(ir.BinOp, st.sampled_from(["+", "-", "*", "/", "%", "&"]),
                                            exprs(depth - 1), exprs(depth - 1))))


@st.composite
def conds(draw):
    return ir.Compare(draw(st.sampled_from(["=", "!=", "<", ">=", ">"])), ir.Var(draw(st.sampled_from(VARS))),
                      const(draw(st.integers(-50, 50))))


@st.composite
def ops(draw, with_calls: bool):
    kind = draw(st.sampled_from(["assign", "assign", "speed", "accel", "move", "move2", "wait", "delay", "output",
                                 "print"] + (["call"] if with_calls else [])))
    if kind == "assign":
        return ir.Assign(ir.Var(draw(st.sampled_from(VARS))), draw(exprs()))
    axis = draw(st.sampled_from(AXES))
    if kind == "speed":
        return ir.SetMotion(ir.MotionParam.MAX_SPEED, axis, const(draw(st.integers(100, 20000)), U.STEPS_PER_S))
    if kind == "accel":
        param = draw(st.sampled_from([ir.MotionParam.ACCEL, ir.MotionParam.DECEL]))
        return ir.SetMotion(param, axis, const(draw(st.integers(100, 100000)), U.STEPS_PER_S2))
    if kind in ("move", "move2"):
        mode = draw(st.sampled_from([ir.MoveMode.ABSOLUTE, ir.MoveMode.RELATIVE]))
        axes = AXES if kind == "move2" else (axis,)
        return ir.Move(mode, tuple((a, const(draw(st.integers(-20000, 20000)), U.STEPS)) for a in axes))
    if kind == "wait":
        return ir.WaitMotion(axis)
    if kind == "delay":
        return ir.Delay(const(draw(st.integers(1, 2000)) / 1000, U.S))
    if kind == "output":
        return ir.SetOutput(draw(st.integers(1, 4)), const(draw(st.integers(0, 1))))
    if kind == "print":
        return ir.Print((ir.Text("v="), ir.Var(draw(st.sampled_from(VARS)))))
    return ir.Call("S1")


@st.composite
def modules(draw, dialect: str = "arcus", steps_per_rev: int = 4000):
    count = draw(st.integers(1, 5))
    blocks = []
    for n in range(count):
        body = draw(st.lists(ops(True), max_size=6))
        later = [f"b{k}" for k in range(n + 1, count)]
        if not later:
            term = ir.End()
        elif draw(st.booleans()):
            term = ir.Jump(draw(st.sampled_from(later)))
        else:
            term = ir.Branch(draw(conds()), draw(st.sampled_from(later)), draw(st.sampled_from(later)))
        blocks.append(ir.Block(f"b{n}", body, term))
    sub = ir.Routine("S1", ir.RoutineKind.SUBROUTINE, [ir.Block("s1", draw(st.lists(ops(False), max_size=4)),
                                                                ir.Return())], number=1)
    main = ir.Routine("main", ir.RoutineKind.MAIN, blocks)
    variables = {name: ir.Variable(name, ir.VarType.INT32) for name in VARS}
    return ir.Module(dialect, "pmx-4ex-sa" if dialect == "arcus" else "", variables, [main, sub],
                     steps_per_rev=steps_per_rev)


def scaled(module: ir.Module, factor: int) -> ir.Module:
    """The same program with a step `factor` times smaller: every step quantity times `factor`."""
    def fix(expr):
        if isinstance(expr, ir.Const) and expr.unit in (U.STEPS, U.STEPS_PER_S, U.STEPS_PER_S2):
            return ir.Const(expr.value * factor, expr.unit)
        return expr

    def op_copy(op):
        if isinstance(op, ir.Move):
            return ir.Move(op.mode, tuple((a, fix(e)) for a, e in op.targets))
        if isinstance(op, ir.SetMotion):
            return ir.SetMotion(op.param, op.axis, fix(op.value))
        return op

    routines = [ir.Routine(r.name, r.kind, [ir.Block(b.label, [op_copy(o) for o in b.ops], b.terminator)
                                            for b in r.blocks], number=r.number) for r in module.routines]
    return ir.Module(module.dialect, module.profile, dict(module.variables), routines,
                     steps_per_rev=module.steps_per_rev * factor)
