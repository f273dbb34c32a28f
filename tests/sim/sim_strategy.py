"""A hypothesis strategy for random *valid* IR programs (not text): the verifier accepts every one.

Programs are a main routine of blocks that only jump forward (so every run ends), with a
subroutine it may call; operations draw from assignments with int32 arithmetic, motion settings in
the IR's units, absolute and relative moves on one or two axes, waits, delays, outputs and prints.

`Shape` narrows the programs to what one target can write, so a round trip through its backend
tests the translation rather than the refusals (the test still counts what is refused): MCode
drives one axis, evaluates left to right and has no `%`; X150 moves one axis per device and
accepts accelerations from 0.06 rev/s²; Arcus prints nothing.
"""

from __future__ import annotations

from dataclasses import dataclass

from hypothesis import strategies as st

from mcc.compiler import ir

U = ir.Unit
VARS = ("V1", "V2", "V3")
AXES = ("X", "Y")


@dataclass(frozen=True)
class Shape:
    axes: tuple[str, ...] = AXES
    operators: tuple[str, ...] = ("+", "-", "*", "/", "%", "&")
    nested_right: bool = True  # a right operand may itself be an operation (needs parentheses)
    outputs: int = 4
    prints: bool = True
    initial_speed: bool = False  # also set initial speeds (Arcus ramps need them with accelerations)
    # main starts by setting both speeds and the acceleration of every axis, as programs do (an Arcus
    # axis uses its own speeds only once all of HSPDa, LSPDa and ACCa are set, L447-L457)
    prologue: bool = False
    one_ramp: bool = False  # an acceleration is set with an equal deceleration (Arcus ACC, X150 A)
    speeds: tuple[int, int] = (100, 20000)  # steps/s
    initial_speeds: tuple[int, int] = (0, 90)  # steps/s
    accels: tuple[int, int] = (100, 100000)  # steps/s²
    steps_per_rev: int = 4000


SHAPES = {
    "any": Shape(),
    # LSPD takes 1..6,000,000 pps (arcus-pmx-4ex-sa.txt L1574-L1576): no initial speed of 0
    "arcus": Shape(prints=False, initial_speed=True, prologue=True, one_ramp=True, initial_speeds=(1, 90)),
    # the same speeds at MCode's 51200 steps/rev (12.8 times 4000)
    "mcode": Shape(axes=("X",), operators=("+", "-", "*", "/", "&"), nested_right=False, outputs=3,
                   initial_speed=True, speeds=(1280, 256000), initial_speeds=(0, 1150), accels=(1280, 1280000),
                   steps_per_rev=51200),
    "x150": Shape(axes=("X",), operators=("+", "-", "*", "/"), nested_right=False, outputs=4, prints=False,
                  accels=(240, 100000), one_ramp=True),
}


def const(value, unit=U.NONE) -> ir.Const:
    return ir.Const(value, unit)


@st.composite
def exprs(draw, depth: int = 2, shape: Shape = SHAPES["any"]):
    leaves = st.one_of(st.integers(-1000, 1000).map(const), st.sampled_from(VARS).map(ir.Var))
    if depth <= 0:
        return draw(leaves)
    right = exprs(depth - 1, shape) if shape.nested_right else leaves
    return draw(st.one_of(leaves, st.builds(ir.BinOp, st.sampled_from(shape.operators),
                                            exprs(depth - 1, shape), right)))


@st.composite
def conds(draw):
    return ir.Compare(draw(st.sampled_from(["=", "!=", "<", ">=", ">"])), ir.Var(draw(st.sampled_from(VARS))),
                      const(draw(st.integers(-50, 50))))


@st.composite
def ops(draw, with_calls: bool, shape: Shape = SHAPES["any"]):
    kinds = ["assign", "assign", "speed", "accel", "move", "wait", "delay", "output"]
    kinds += ["move2"] if len(shape.axes) > 1 else []
    kinds += ["print"] if shape.prints else []
    kinds += ["initial"] if shape.initial_speed else []
    kind = draw(st.sampled_from(kinds + (["call"] if with_calls else [])))
    if kind == "assign":
        return ir.Assign(ir.Var(draw(st.sampled_from(VARS))), draw(exprs(shape=shape)))
    axis = draw(st.sampled_from(shape.axes))
    if kind == "speed":
        return ir.SetMotion(ir.MotionParam.MAX_SPEED, axis, const(draw(st.integers(*shape.speeds)), U.STEPS_PER_S))
    if kind == "initial":
        return ir.SetMotion(ir.MotionParam.INITIAL_SPEED, axis, const(draw(st.integers(*shape.initial_speeds)), U.STEPS_PER_S))
    if kind == "accel":
        param = draw(st.sampled_from([ir.MotionParam.ACCEL, ir.MotionParam.DECEL]))
        return ir.SetMotion(param, axis, const(draw(st.integers(*shape.accels)), U.STEPS_PER_S2))
    if kind in ("move", "move2"):
        mode = draw(st.sampled_from([ir.MoveMode.ABSOLUTE, ir.MoveMode.RELATIVE]))
        axes = shape.axes if kind == "move2" else (axis,)
        return ir.Move(mode, tuple((a, const(draw(st.integers(-20000, 20000)), U.STEPS)) for a in axes))
    if kind == "wait":
        return ir.WaitMotion(axis)
    if kind == "delay":
        return ir.Delay(const(draw(st.integers(1, 2000)) / 1000, U.S))
    if kind == "output":
        return ir.SetOutput(draw(st.integers(1, shape.outputs)), const(draw(st.integers(0, 1))))
    if kind == "print":
        return ir.Print((ir.Text("v="), ir.Var(draw(st.sampled_from(VARS)))))
    return ir.Call("S1")


@st.composite
def modules(draw, dialect: str = "arcus", steps_per_rev: int | None = None, shape: Shape = SHAPES["any"]):
    steps_per_rev = steps_per_rev or shape.steps_per_rev
    count = draw(st.integers(1, 5))
    blocks = []
    for n in range(count):
        body = draw(st.lists(ops(True, shape), max_size=6))
        later = [f"b{k}" for k in range(n + 1, count)]
        if not later:
            term = ir.End()
        elif draw(st.booleans()):
            term = ir.Jump(draw(st.sampled_from(later)))
        else:
            term = ir.Branch(draw(conds()), draw(st.sampled_from(later)), draw(st.sampled_from(later)))
        if n == 0 and shape.prologue:
            body = [ir.SetMotion(param, axis, const(draw(st.integers(*bounds)), unit))
                    for axis in shape.axes
                    for param, bounds, unit in ((ir.MotionParam.INITIAL_SPEED, shape.initial_speeds, U.STEPS_PER_S),
                                                (ir.MotionParam.MAX_SPEED, shape.speeds, U.STEPS_PER_S),
                                                (ir.MotionParam.ACCEL, shape.accels, U.STEPS_PER_S2),
                                                (ir.MotionParam.DECEL, shape.accels, U.STEPS_PER_S2))] + body
        blocks.append(ir.Block(f"b{n}", paired(body) if shape.one_ramp else body, term))
    sub_ops = draw(st.lists(ops(False, shape), max_size=4))
    sub = ir.Routine("S1", ir.RoutineKind.SUBROUTINE, [ir.Block("s1", paired(sub_ops) if shape.one_ramp else sub_ops,
                                                                ir.Return())], number=1)
    main = ir.Routine("main", ir.RoutineKind.MAIN, blocks)
    variables = {name: ir.Variable(name, ir.VarType.INT32) for name in VARS}
    return ir.Module(dialect, "pmx-4ex-sa" if dialect == "arcus" else "", variables, [main, sub],
                     steps_per_rev=steps_per_rev)


def paired(body: list[ir.Op]) -> list[ir.Op]:
    """Every acceleration followed by the same deceleration, as a one-ramp target needs."""
    out: list[ir.Op] = []
    for op in body:
        if isinstance(op, ir.SetMotion) and op.param is ir.MotionParam.DECEL:
            op = ir.SetMotion(ir.MotionParam.ACCEL, op.axis, op.value)
        out.append(op)
        if isinstance(op, ir.SetMotion) and op.param is ir.MotionParam.ACCEL:
            out.append(ir.SetMotion(ir.MotionParam.DECEL, op.axis, op.value))
    return out


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
