"""A hypothesis strategy that builds random valid IR modules (not text): straight-line operations
from a small vocabulary (so runs repeat and the passes have something to do), IF- and WHILE-shaped
control flow, calls to subroutines, settings on single axes and on `*`, and (MCode, X150) an event
handler that assigns a variable and may change a speed."""

from __future__ import annotations

from hypothesis import strategies as st

from mcc.compiler import ir

VARS = ("V1", "V2", "V3", "V4")
FLOAT_VAR = "F1"  # a float variable: a copy into or out of it converts the value
AXES = ("X", "Y", ir.ALL_AXES)


def steps(v):
    return ir.Const(v, ir.Unit.STEPS)


def var_or_const(draw):
    if draw(st.booleans()):
        return ir.Var(draw(st.sampled_from(VARS)))
    return ir.Const(draw(st.sampled_from([0, 1, 2, 5, 100])))


@st.composite
def expressions(draw):
    kind = draw(st.integers(0, 3))
    if kind == 0:
        return ir.Const(draw(st.sampled_from([0, 1, 3, 7, 1000, 2 ** 31 - 1])))
    if kind == 1:
        return ir.Var(draw(st.sampled_from(VARS + (FLOAT_VAR,))))
    op = draw(st.sampled_from(["+", "-", "*", "/", "&"]))
    return ir.BinOp(op, var_or_const(draw), var_or_const(draw))


@st.composite
def operations(draw, routines: tuple[str, ...]):
    kind = draw(st.integers(0, 11))
    if kind <= 2:
        return ir.Assign(ir.Var(draw(st.sampled_from(VARS + (FLOAT_VAR,)))), draw(expressions()))
    if kind == 3:
        speed = draw(st.sampled_from([1000, 5000]))
        return ir.SetMotion(ir.MotionParam.MAX_SPEED, draw(st.sampled_from(AXES)), ir.Const(speed, ir.Unit.STEPS_PER_S))
    if kind <= 5:
        axis = draw(st.sampled_from(("X", "Y")))
        target = steps(draw(st.sampled_from([0, 500, 1000]))) if draw(st.booleans()) else \
            ir.Var(draw(st.sampled_from(VARS)))
        return ir.Move(draw(st.sampled_from(list(ir.MoveMode)[:2])), ((axis, target),))
    if kind == 6:
        return ir.WaitMotion(draw(st.sampled_from(("X", "Y"))))
    if kind == 7:
        return ir.Delay(ir.Const(draw(st.sampled_from([0.1, 0.25])), ir.Unit.S))
    if kind == 8:
        return ir.SetOutput(draw(st.integers(1, 2)), var_or_const(draw))
    if kind == 9 and routines:
        return ir.Call(draw(st.sampled_from(routines)))
    if kind == 10:
        return ir.Native("arcus", "EO", (ir.Const(draw(st.integers(0, 3))),), form="=")
    return ir.Setting("run_current", draw(st.sampled_from(("X", ir.ALL_AXES))),
                      ir.Const(draw(st.sampled_from([50, 75])), ir.Unit.PERCENT))


@st.composite
def conditions(draw):
    left = draw(st.sampled_from([ir.Var(v) for v in VARS] + [ir.Status("input", index=1), ir.Const(1)]))
    return ir.Compare(draw(st.sampled_from(["=", "!=", "<", ">="])), left, ir.Const(draw(st.integers(0, 2))))


class Builder:
    """Blocks of one routine built from nested statement shapes."""

    def __init__(self, prefix: str):
        self.prefix, self.n, self.blocks, self.loops = prefix, 0, [], 0

    def label(self) -> str:
        self.n += 1
        return f"{self.prefix}{self.n}"

    def new(self) -> ir.Block:
        block = ir.Block(self.label())
        self.blocks.append(block)
        return block


@st.composite
def statements(draw, builder: Builder, current: ir.Block, routines: tuple[str, ...], depth: int) -> ir.Block:
    """Append random statements starting in `current`; returns the block control ends in."""
    for _ in range(draw(st.integers(1, 6))):
        shape = draw(st.integers(0, 9)) if depth < 2 else 0
        if shape <= 6:
            current.ops.extend(draw(st.lists(operations(routines), min_size=1, max_size=6)))
        elif shape <= 8:  # IF cond THEN ... [ELSE ...] ENDIF
            then, join = builder.new(), None
            otherwise = builder.new() if draw(st.booleans()) else None
            end_then = draw(statements(builder, then, routines, depth + 1))
            end_else = draw(statements(builder, otherwise, routines, depth + 1)) if otherwise else None
            join = builder.new()
            current.terminator = ir.Branch(draw(conditions()), then.label, (otherwise or join).label)
            end_then.terminator = ir.Jump(join.label)
            if end_else is not None:
                end_else.terminator = ir.Jump(join.label)
            current = join
        else:  # C = 0; WHILE C < n: ...; C = C + 1 (a counter nothing else assigns: it terminates)
            builder.loops += 1
            counter = ir.Var(f"C{builder.prefix}{builder.loops}")
            current.ops.append(ir.Assign(counter, ir.Const(0)))
            header, body, exit_ = builder.new(), builder.new(), None
            current.terminator = ir.Jump(header.label)
            end_body = draw(statements(builder, body, routines, depth + 1))
            end_body.ops.append(ir.Assign(counter, ir.BinOp("+", counter, ir.Const(1))))
            end_body.terminator = ir.Jump(header.label)
            exit_ = builder.new()
            header.terminator = ir.Branch(ir.Compare("<", counter, ir.Const(draw(st.integers(1, 3)))),
                                          body.label, exit_.label)
            current = exit_
    return current


@st.composite
def modules(draw, dialect: str = "arcus"):
    subs = tuple(f"S{i}" for i in range(1, draw(st.integers(0, 2)) + 1))
    routines = []
    for index, name in enumerate(subs):
        callees = subs[index + 1:]  # no recursion: a subroutine calls only later ones
        builder = Builder(f"{name.lower()}_")
        end = draw(statements(builder, builder.new(), callees, 1))
        end.terminator = ir.Return()
        routines.append(ir.Routine(name, ir.RoutineKind.SUBROUTINE, builder.blocks, number=index + 1))
    builder = Builder("m")
    end = draw(statements(builder, builder.new(), subs, 0))
    end.terminator = ir.End()
    main = ir.Routine("main", ir.RoutineKind.MAIN, builder.blocks)
    if dialect != "arcus":  # a trip or XWHEN handler: assigns a variable, maybe a speed
        target = ir.Var(draw(st.sampled_from(VARS[:2])))
        handler_ops = [ir.Assign(target, ir.BinOp("+", target, ir.Const(1)))]
        if draw(st.booleans()):
            handler_ops.append(ir.SetMotion(ir.MotionParam.MAX_SPEED, "X", ir.Const(1000, ir.Unit.STEPS_PER_S)))
        routines.append(ir.Routine("H1", ir.RoutineKind.HANDLER, [ir.Block("h1", handler_ops, ir.Return())]))
    variables = {FLOAT_VAR: ir.Variable(FLOAT_VAR, ir.VarType.FLOAT64)}
    profile = {"arcus": "pmx-4ex-sa", "mcode": "lmd-c", "x150": "x150-x150ds"}[dialect]
    return ir.Module(dialect, profile, variables, [main, *routines], steps_per_rev=4000)
