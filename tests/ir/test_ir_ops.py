"""The operation table (compiler/ir_ops.py) is complete and agrees with the dataclasses and with the
code that is not yet derived from it; the printer derived from it writes what the hand-written
printer wrote (tests/ir/printer_before.py), byte for byte."""

from __future__ import annotations

import dataclasses
import typing

import pytest
from hypothesis import given, settings

import every_op
import printer_before
from ir_programs import modules_of
from mcc.compiler import ir, ir_ops
from mcc.compiler.ir_print import op_text, term_text

DIALECTS = ("mcode", "arcus", "x150")


def test_every_operation_and_terminator_has_one_record():
    assert [d.cls for d in ir_ops.OPERATIONS] == list(typing.get_args(ir.Op))
    assert [d.cls for d in ir_ops.TERMINATORS] == list(typing.get_args(ir.Terminator))


@pytest.mark.parametrize("definition", ir_ops.TABLE.values(), ids=lambda d: d.name)
def test_a_record_names_every_field_once_and_its_template_writes_each(definition):
    declared = [f.name for f in dataclasses.fields(definition.cls) if f.name != "span"]
    assert sorted(f.name for f in definition.fields) == sorted(declared)
    written = ir_ops.referenced(ir_ops.PIECES[definition.cls])
    # every field but the print formats (written by the items they format) appears in the template
    expected = {f.name for f in definition.fields if f.kind is not ir_ops.Kind.FORMATS}
    assert set(written) == expected
    hints = typing.get_type_hints(definition.cls)
    for f in definition.fields:
        may_be_none = type(None) in typing.get_args(hints[f.name])
        assert f.optional == may_be_none, f"{definition.name}.{f.name}: optional says {f.optional}"
        if f.kind is ir_ops.Kind.ENUM:
            assert hints[f.name] is f.enum


def test_terminators_and_only_they_end_a_block():
    assert set(ir_ops.with_trait(ir_ops.Trait.ENDS_BLOCK)) == {d.cls for d in ir_ops.TERMINATORS}


def test_settled_ops_starts_motion_where_the_table_says_an_operation_may():
    """`ir.settled_ops` (hand-written) treats an operation as one that may leave a move running; the
    table's traits say the same: it moves an axis or calls a routine (a stop and a pause stop motion,
    a handler runs later)."""
    from mcc.compiler.ir import Arc, Call, Home, Move, Native, Slew

    may_move = {d.cls for d in ir_ops.OPERATIONS
                if d.traits & {ir_ops.Trait.MOVES_AXIS, ir_ops.Trait.CALLS}} - {ir.Stop, ir.Pause, ir.SetHandler}
    assert may_move == {Move, Arc, Slew, Home, Call, Native}


def exprs_from_table(op) -> tuple:
    """The expressions and conditions an operation reads, by its fields' kinds."""
    found: list = []
    for f in ir_ops.TABLE[type(op)].fields:
        value = getattr(op, f.name)
        if value is None:
            continue
        if f.kind in (ir_ops.Kind.EXPR, ir_ops.Kind.COND):
            found.append(value)
        elif f.kind in (ir_ops.Kind.ARGS, ir_ops.Kind.ITEMS, ir_ops.Kind.EXPR_PAIR):
            found += list(value)
        elif f.kind is ir_ops.Kind.AXIS_EXPRS:
            found += [e for _, e in value]
    return tuple(found)


@settings(max_examples=300, deadline=None)
@given(every_op.operations())
def test_the_expression_walk_reads_the_fields_the_table_says_hold_expressions(op):
    """`ir.op_exprs` is still hand-written (compiler/ir.py is kept small for import speed); it must
    read exactly the expression fields of the table, in any order."""
    assert sorted(map(repr, ir.op_exprs(op))) == sorted(map(repr, exprs_from_table(op)))


@settings(max_examples=500, deadline=None)
@given(every_op.operations())
def test_the_derived_printer_writes_every_operation_as_before(op):
    assert op_text(op) == printer_before.op_text(op)


@settings(max_examples=100, deadline=None)
@given(every_op.terminators())
def test_the_derived_printer_writes_every_terminator_as_before(term):
    assert term_text(term) == printer_before.term_text(term)
    assert term_text(None) == printer_before.term_text(None)


@pytest.mark.parametrize("dialect", DIALECTS)
def test_the_derived_printer_writes_every_sample_and_golden_program_as_before(dialect):
    compared = 0
    for path, module in modules_of(dialect):
        for _routine, block in module.blocks():
            for op in block.ops:
                assert op_text(op) == printer_before.op_text(op), path
            assert term_text(block.terminator) == printer_before.term_text(block.terminator), path
        compared += 1
    assert compared >= 10


def test_docs_print_the_table():
    from pathlib import Path

    page = (Path(__file__).resolve().parents[2] / "docs" / "IR.md").read_text(encoding="utf-8")
    assert ir_ops.markdown() in page, "docs/IR.md: paste ir_ops.markdown() into \"The operation table\""
