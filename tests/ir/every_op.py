"""Hypothesis strategies for every IR operation and terminator, derived from the operation table
(compiler/ir_ops.py): a field's kind says what values it takes, so an operation added to the table is
generated here without a line more. The values are any the text form can state (not only valid
programs): the printer and the reader are tested on them, not the simulator.

What the text form cannot tell apart is left out on purpose (docs/IR.md, "Reading IR text"): a
variable named like a reading, a handler routine named "", an expression used where a condition
is printed inside an operator."""

from __future__ import annotations

from hypothesis import strategies as st

from mcc.compiler import ir, ir_names, ir_ops
from mcc.compiler.ir_ops import Kind

VARS = ("V1", "V2", "R1", "%L1", "counter")
AXES = ("X", "Y", "1", "12", "*", "")
ROUTINES = ("S1", "K1", "SEQ3@1")
LABELS = ("%1", "K2", "N5")
UNITS = tuple(ir.Unit)
WORDS = ("EO", "S", "PR", "switch", "index", "mcode", "x150")
FORMATS = ("fixed 3", "fixed 0 magnitude", "bits 10", "pad 2", "")


def numbers():
    return st.one_of(st.integers(-2 ** 31, 2 ** 31), st.floats(allow_nan=False, allow_infinity=False, width=32),
                     st.sampled_from([0, 1, -1, 0.25, 1e16, 1e-05, 2.5]))


def atoms():
    return st.one_of(
        st.builds(ir.Const, numbers(), st.sampled_from(UNITS)),
        st.builds(ir.Var, st.sampled_from(VARS)),
        st.builds(ir.Status, st.sampled_from(sorted(ir_names.STATUS)), st.sampled_from(AXES),
                  st.one_of(st.none(), st.integers(0, 16))),
        st.builds(ir.DeviceRef, st.sampled_from(["mcode", "arcus", "x150"]), st.sampled_from(["P", "MSTX", "POS"]),
                  axis=st.sampled_from(AXES), index=st.one_of(st.none(), st.integers(0, 9))),
        st.builds(ir.LabelRef, st.sampled_from(LABELS + ROUTINES + ("100",))),
        st.builds(ir.Text, st.text(max_size=8)),
        st.builds(ir.Pattern, st.text("01X", min_size=1, max_size=8)),
    )


def expressions():
    return EXPRESSIONS


def _expressions():
    return st.recursive(atoms(), lambda inner: st.one_of(
        st.builds(ir.BinOp, st.sampled_from(sorted(ir_names.BINARY_OPS)), inner, inner),
        st.builds(ir.UnOp, st.sampled_from(sorted(ir_names.UNARY_OPS)), inner),
        st.builds(ir.Func, st.sampled_from(sorted(ir_names.FUNCTIONS)), st.lists(inner, max_size=2).map(tuple)),
    ), max_leaves=6)


def conditions():
    return CONDITIONS


def _conditions():
    simple = st.one_of(
        st.builds(ir.Compare, st.sampled_from(sorted(ir_names.COMPARE_OPS)), expressions(), expressions()),
        st.builds(ir.Truth, expressions()),
        st.builds(ir.InputMatch, st.builds(ir.Pattern, st.text("01X", min_size=1, max_size=8))),
    )
    return st.recursive(simple, lambda inner: st.one_of(
        st.builds(ir.Logic, st.sampled_from(sorted(ir_names.LOGIC_OPS)), inner, inner),
        st.builds(ir.Not, inner),
    ), max_leaves=4)


# Built once: making a recursive strategy anew for every field was most of the test's time.
EXPRESSIONS = _expressions()
CONDITIONS = _conditions()


def axes():
    return st.sampled_from(AXES)


def axis_exprs(min_size: int):
    return st.lists(st.tuples(st.sampled_from(AXES + ("p2",)), expressions()),
                    min_size=min_size, max_size=3).map(tuple)


def field_values(definition: ir_ops.OpDef, f: ir_ops.Field):
    """The values field `f` of `definition` can hold, by its kind (and its choices when it has some)."""
    kind = f.kind
    if f.choices is not None and kind is Kind.NAME:
        values = st.sampled_from(sorted(f.choices))
    elif kind is Kind.EXPR:
        values = expressions()
    elif kind is Kind.COND:
        values = conditions()
    elif kind is Kind.ARGS:
        values = st.lists(st.one_of(expressions(), conditions()), max_size=3).map(tuple)
    elif kind is Kind.ITEMS:
        values = st.lists(expressions(), max_size=3).map(tuple)
    elif kind is Kind.FORMATS:
        values = st.lists(st.sampled_from(FORMATS), max_size=3).map(tuple)
    elif kind is Kind.EXPR_PAIR:
        values = st.tuples(expressions(), expressions())
    elif kind is Kind.AXIS:
        values = axes()
    elif kind is Kind.AXIS_PAIR:
        values = st.tuples(st.sampled_from(AXES[:4]), st.sampled_from(AXES[:4]))
    elif kind is Kind.AXIS_EXPRS:
        values = axis_exprs(0 if f.name == "options" else 1)
    elif kind is Kind.VAR:
        values = st.builds(ir.Var, st.sampled_from(VARS))
    elif kind is Kind.ENUM:
        values = st.sampled_from(list(f.enum))
    elif kind is Kind.NAME:
        values = st.sampled_from(WORDS + ("",))
    elif kind is Kind.ROUTINE:
        values = st.sampled_from(ROUTINES)
    elif kind is Kind.LABEL:
        values = st.sampled_from(LABELS)
    elif kind in (Kind.SIGN, Kind.SIGNED):
        values = st.sampled_from([-1, 0, 1])
    elif kind is Kind.INT:
        values = st.integers(0, 64)
    elif kind in (Kind.BOOL, Kind.FLAG):
        values = st.booleans()
    elif kind is Kind.QUOTED:
        values = st.sampled_from(["", "=", " ", "number", 'a "quoted" text'])
    else:  # pragma: no cover - a new kind must be generated: this test fails until it is
        raise AssertionError(f"every_op.py does not generate fields of kind {kind.value}")
    return st.one_of(st.none(), values) if f.optional else values


def instances(definition: ir_ops.OpDef):
    """Objects of one table entry, every field drawn by its kind."""
    fields = {f.name: field_values(definition, f) for f in definition.fields}
    return st.builds(definition.cls, **fields)


_OPERATIONS = st.one_of(*[instances(d) for d in ir_ops.OPERATIONS])
_TERMINATORS = st.one_of(*[instances(d) for d in ir_ops.TERMINATORS])


def operations():
    return _OPERATIONS


def terminators():
    return _TERMINATORS


@st.composite
def modules(draw):
    """A module of one routine whose blocks hold drawn operations (the reader does not need a valid
    program: jumps may go anywhere)."""
    blocks = []
    for n, label in enumerate(LABELS[:draw(st.integers(1, 3))]):
        ops = draw(st.lists(operations(), max_size=4))
        for index, op in enumerate(ops):
            op.span = None if draw(st.booleans()) else ir.Span("t.ir", n * 10 + index + 1, 1, 1, 1)
        blocks.append(ir.Block(label, ops, draw(st.one_of(st.none(), terminators())), named=draw(st.booleans())))
    variables = {name: ir.Variable(name, draw(st.sampled_from(list(ir.VarType))),
                                   draw(st.one_of(st.none(), expressions())), draw(st.sampled_from(["global", "local"])))
                 for name in draw(st.lists(st.sampled_from(VARS), unique=True, max_size=2))}
    routine = ir.Routine("main", draw(st.sampled_from(list(ir.RoutineKind))), blocks,
                         number=draw(st.one_of(st.none(), st.integers(0, 99))),
                         origin=draw(st.one_of(st.none(), st.integers(0, 999))))
    return ir.Module("arcus", "pmx-4ex-sa", variables, [routine], steps_per_rev=draw(st.integers(0, 51200)))
