"""The IR printer: a stable text form for people and golden tests, and a JSON form for tools.

The text form (documented in docs/IR.md) prints one routine after another, each block as a label
line followed by its operations, one per line, indented by two spaces, and the terminator last.
Every operation ends with `; L<line>` when it has a source position, so a dump reads side by side
with the source. Expressions print infix with full parentheses below the top level, constants with
their unit (`51200 steps`, `0.25 s`).

The JSON form (`mcc ir --format json`) is the dataclasses themselves: each operation is an object
with `"op"` naming its kind and one key per field, each expression an object with `"expr"`;
spans become `"line"` and `"col"`.
"""

from __future__ import annotations

import dataclasses
import json
from enum import Enum
from typing import Any

from mcc.compiler import ir, ir_ops


def to_text(module: ir.Module) -> str:
    lines = [f"module {module.dialect} profile={module.profile} steps_per_rev={module.steps_per_rev}"]
    for name, variable in module.variables.items():
        init = f" = {expr_text(variable.init)}" if variable.init is not None else ""
        scope = "" if variable.scope == "global" else f" {variable.scope}"
        lines.append(f"var {name}: {variable.type.value}{scope}{init}{_where(variable.span)}")
    for routine in module.routines:
        lines.append("")
        number = f" number={routine.number}" if routine.number is not None else ""
        origin = f" origin={routine.origin}" if routine.origin is not None else ""
        lines.append(f"routine {routine.name} ({routine.kind.value}){number}{origin}")
        for block in routine.blocks:
            lines.append(f"{block.label}:{' ; named' if block.named else ''}")
            lines.extend(f"  {op_text(op)}{_where(op.span)}" for op in block.ops)
            lines.append(f"  {term_text(block.terminator)}"
                         f"{_where(block.terminator.span if block.terminator else None)}")
    return "\n".join(lines) + "\n"


def _where(span) -> str:
    return f"  ; L{span.line}" if span is not None else ""


def _axes(targets) -> str:
    return " ".join(f"{axis}={expr_text(value)}" for axis, value in targets)


def op_text(op: ir.Op) -> str:
    """An operation as its syntax template in the operation table (compiler/ir_ops.py) writes it."""
    writer = _WRITERS.get(type(op))
    return writer(op) if writer is not None else f"<{type(op).__name__}>"


def term_text(term: ir.Terminator | None) -> str:
    if term is None:
        return "<no terminator>"
    return op_text(term)


def _items(op) -> str:
    """Print items, each with its format (`Print.formats`, by position) when it has one."""
    formats = list(op.formats) + [""] * (len(op.items) - len(op.formats))
    return ", ".join(expr_text(item) + (f" as {spec}" if spec else "") for item, spec in zip(op.items, formats))


# How each kind of field is written, as a Python expression of the field's value `{v}` (the reader,
# compiler/ir_read.py, reads the same forms).
FORMS = {
    ir_ops.Kind.EXPR: "expr_text({v})",
    ir_ops.Kind.COND: "cond_text({v})",
    ir_ops.Kind.ARGS: "', '.join([_any_text(a) for a in {v}])",
    ir_ops.Kind.ITEMS: "_items(op)",
    ir_ops.Kind.EXPR_PAIR: "', '.join([expr_text(c) for c in {v}])",
    ir_ops.Kind.AXIS: "{v}",
    ir_ops.Kind.AXIS_PAIR: "{v}[0] + ',' + {v}[1]",
    ir_ops.Kind.AXIS_EXPRS: "_axes({v})",
    ir_ops.Kind.VAR: "{v}.name",
    ir_ops.Kind.ENUM: "{v}.value",
    ir_ops.Kind.NAME: "{v}",
    ir_ops.Kind.ROUTINE: "{v}",
    ir_ops.Kind.LABEL: "{v}",
    ir_ops.Kind.SIGN: "('+' if {v} >= 0 else '-')",
    ir_ops.Kind.SIGNED: "format({v}, '+d')",
    ir_ops.Kind.INT: "str({v})",
    ir_ops.Kind.QUOTED: "json.dumps({v})",
}


def writer_source(definition: ir_ops.OpDef) -> str:
    """The Python expression that writes an operation of `definition` (`op`) by its template.
    Compiled once per operation: as quick as the hand-written cases it replaced."""

    def parts(pieces) -> str:
        out = []
        for piece in pieces:
            if isinstance(piece, ir_ops.Text):
                out.append(repr(piece.text))
            elif isinstance(piece, ir_ops.Ref):
                f = definition.field(piece.field)
                if f.kind is ir_ops.Kind.BOOL:
                    out.append(f"({f.words[0]!r} if op.{f.name} else {f.words[1]!r})")
                elif f.kind is not ir_ops.Kind.FLAG:
                    out.append(FORMS[f.kind].format(v=f"op.{f.name}"))
            else:
                # the group is written when its anchor is set: not None, not "", not its default
                default = definition.default(piece.anchor)
                value = f"op.{piece.anchor}"
                test = f"{value} is not None"
                if definition.field(piece.anchor).kind in ir_ops.TEXTS:
                    test += f" and {value} != ''"
                if default is not ir_ops.dataclasses.MISSING and default not in (None, ""):
                    test += f" and {value} != {default!r}"
                out.append(f"(({parts(piece.then)}) if {test} else ({parts(piece.otherwise)}))")
        return " + ".join(out) or "''"

    return parts(ir_ops.PIECES[definition.cls])


def _writer(definition: ir_ops.OpDef):
    source = f"lambda op: {writer_source(definition)}"
    names = {"expr_text": expr_text, "cond_text": cond_text, "_any_text": _any_text, "_items": _items,
             "_axes": _axes, "json": json}
    return eval(compile(source, f"<ir_ops {definition.name}>", "eval"), names)  # noqa: S307 - our own table


_WRITERS: dict = {}


def _writers() -> None:
    """Compile the writers once the functions they call exist (below)."""
    _WRITERS.update({cls: _writer(d) for cls, d in ir_ops.TABLE.items()})


def _any_text(node) -> str:
    if isinstance(node, (ir.Compare, ir.Logic, ir.Truth, ir.InputMatch, ir.Not)):
        return cond_text(node)
    return expr_text(node)


def expr_text(expr, top: bool = True) -> str:
    """An expression, infix; sub-expressions are parenthesised so precedence never matters."""
    if expr is None:
        return "<none>"
    if isinstance(expr, ir.Const):
        unit = f" {expr.unit.value}" if expr.unit.value else ""
        return f"{_number(expr.value)}{unit}"
    if isinstance(expr, ir.Var):
        return expr.name
    if isinstance(expr, ir.Status):
        index = f"[{expr.index}]" if expr.index is not None else ""
        axis = f"({expr.axis})" if expr.axis else ""
        return f"{expr.meaning}{axis}{index}"
    if isinstance(expr, ir.DeviceRef):
        index = f"[{expr.index}]" if expr.index is not None else ""
        axis = f"({expr.axis})" if expr.axis else ""
        return f"{expr.dialect}.{expr.name}{axis}{index}"
    if isinstance(expr, ir.LabelRef):
        return f"@{expr.name}"
    if isinstance(expr, ir.Text):
        return json.dumps(expr.value)
    if isinstance(expr, ir.Pattern):
        return f"pattern {expr.bits}"
    if isinstance(expr, ir.Func):
        return f"{expr.name}({', '.join(expr_text(a) for a in expr.args)})"
    # Operators: print iteratively down left-leaning chains so a long expression needs no deep
    # recursion (a chain of thousands of `+` is common in generated programs).
    return _operator_text(expr, top)


def _operator_text(expr, top: bool) -> str:
    if isinstance(expr, ir.UnOp):
        text = f"{expr.op}{expr_text(expr.operand, top=False)}"
        return text
    if isinstance(expr, ir.BinOp):
        chain = []
        node = expr
        while isinstance(node, ir.BinOp):
            chain.append(node)
            node = node.left
        text = expr_text(node, top=False)
        for link in reversed(chain):
            text = f"{text} {link.op} {expr_text(link.right, top=False)}"
            if link is not expr or not top:
                text = f"({text})"
        return text
    if isinstance(expr, (ir.Compare, ir.Logic, ir.Truth, ir.InputMatch, ir.Not)):
        return cond_text(expr)
    return f"<{type(expr).__name__}>"


def cond_text(cond) -> str:
    if isinstance(cond, ir.Compare):
        return f"{expr_text(cond.left, top=False)} {cond.op} {expr_text(cond.right, top=False)}"
    if isinstance(cond, ir.Logic):
        return f"({cond_text(cond.left)}) {cond.op} ({cond_text(cond.right)})"
    if isinstance(cond, ir.Truth):
        return f"truth {expr_text(cond.expr, top=False)}"
    if isinstance(cond, ir.InputMatch):
        return f"inputs match {cond.pattern.bits}"
    if isinstance(cond, ir.Not):
        return f"not ({cond_text(cond.cond)})"
    return expr_text(cond)


def _number(value) -> str:
    if isinstance(value, float):
        if value.is_integer() and abs(value) < 1e15:
            return f"{int(value)}.0"
        return repr(value)
    return str(value)


# ---------------------------------------------------------------------------------------------
# JSON

OPERATIONS = frozenset(t.__name__ for t in ir.Op.__args__)
TERMINATORS = frozenset(t.__name__ for t in ir.Terminator.__args__)


def to_json(module: ir.Module) -> dict:
    return {
        "dialect": module.dialect,
        "profile": module.profile,
        "steps_per_rev": module.steps_per_rev,
        "variables": [_node(v) for v in module.variables.values()],
        "routines": [{
            "name": r.name, "kind": r.kind.value, "number": r.number, "origin": r.origin,
            "blocks": [{"label": b.label, "named": b.named, "ops": [_node(op) for op in b.ops],
                        "terminator": _node(b.terminator)} for b in r.blocks],
        } for r in module.routines],
    }


def _node(value: Any) -> Any:
    """A dataclass tree as JSON data (iterative in spirit: IR expressions are shallow per node)."""
    if value is None or isinstance(value, (bool, int, float, str)):
        return value
    if isinstance(value, Enum):
        return value.value
    if isinstance(value, (tuple, list)):
        return [_node(v) for v in value]
    if dataclasses.is_dataclass(value):
        name = type(value).__name__
        key = "op" if name in OPERATIONS else "terminator" if name in TERMINATORS else "expr"
        out: dict[str, Any] = {key: name}
        for f in dataclasses.fields(value):
            item = getattr(value, f.name)
            if f.name == "span":
                if item is not None:
                    out["line"], out["col"] = item.line, item.column
                continue
            out[f.name] = _node(item)
        return out
    return str(value)


_writers()
