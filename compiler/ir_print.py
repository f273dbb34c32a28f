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

from mcc.compiler import ir


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


def op_text(op: ir.Op) -> str:  # noqa: C901 - one case per operation kind, flat on purpose
    if isinstance(op, ir.Assign):
        return f"{op.target.name} = {expr_text(op.value)}"
    if isinstance(op, ir.SetMotion):
        return f"set {op.param.value} {op.axis} = {expr_text(op.value)}"
    if isinstance(op, ir.Move):
        options = f" with {_axes(op.options)}" if op.options else ""
        return f"move {op.mode.value} {_axes(op.targets)}{options}"
    if isinstance(op, ir.Arc):
        turn = "cw" if op.clockwise else "ccw"
        centre = ", ".join(expr_text(c) for c in op.center)
        angle = f" angle {expr_text(op.angle)}" if op.angle is not None else " full circle"
        return f"arc {turn} {op.axes[0]},{op.axes[1]} centre ({centre}){angle}"
    if isinstance(op, ir.Slew):
        if op.velocity is not None:
            return f"slew {op.axis} velocity {expr_text(op.velocity)}"
        return f"jog {op.axis} {'+' if op.direction >= 0 else '-'}"
    if isinstance(op, ir.Home):
        mode = f" mode {expr_text(op.mode)}" if op.mode is not None else ""
        speed = f" speed {expr_text(op.speed)}" if op.speed is not None else ""
        creep = ""
        if op.creep:
            creep = f" creep {op.creep:+d}" + (f" at {expr_text(op.creep_speed)}" if op.creep_speed is not None else "")
        accel = f" accel {expr_text(op.accel)}" if op.accel is not None else ""
        needs = " needs home input" if op.needs_input else ""
        return (f"home {op.axis} {op.method} direction {op.direction:+d}{speed}{accel}{creep} zero {op.zero}"
                f"{needs}{mode}")
    if isinstance(op, ir.Stop):
        return f"stop {op.axis} {'ramp' if op.ramp else 'abort'}"
    if isinstance(op, ir.SetPosition):
        return f"set position {op.axis} = {expr_text(op.value)}"
    if isinstance(op, ir.WaitMotion):
        return f"wait motion {op.axis}"
    if isinstance(op, ir.Delay):
        return f"delay {expr_text(op.duration)}"
    if isinstance(op, ir.SetOutput):
        where = "outputs" if op.index is None else f"output {op.index}"
        return f"{where} = {expr_text(op.value)}"
    if isinstance(op, ir.WaitInput):
        return f"wait until {cond_text(op.cond)}"
    if isinstance(op, ir.Print):
        formats = list(op.formats) + [""] * (len(op.items) - len(op.formats))
        items = ", ".join(expr_text(item) + (f" as {spec}" if spec else "") for item, spec in zip(op.items, formats))
        device = f" on {op.axis}" if op.axis else ""
        traced = " if tracing" if op.traced else ""
        return f"print{device} {items}{'' if op.newline else ' no-newline'}{' signed' if op.signed else ''}{traced}"
    if isinstance(op, ir.DriveEnable):
        return f"enable {op.axis} = {expr_text(op.on)}"
    if isinstance(op, ir.Call):
        cond = f" if {cond_text(op.cond)}" if op.cond is not None else ""
        return f"call {op.routine}{cond}"
    if isinstance(op, ir.SetHandler):
        args = ", ".join(_any_text(a) for a in op.args)
        target = f" -> {op.routine}" if op.routine else " off"
        facts = "".join(f" {word}" for word, on in (("once", op.once), ("gated", op.gated),
                                                     ("takes-over", op.takes_over)) if on)
        return f"on {op.event}({args}){target}{facts}"
    if isinstance(op, ir.Setting):
        line = f"[{op.index}]" if op.index is not None else ""  # the input or output the setting is for
        return f"setting {op.name}{line} {op.axis} = {expr_text(op.value)}"
    if isinstance(op, ir.Save):
        return "save"
    if isinstance(op, ir.Pause):
        return f"pause {op.axis}{' stop motion' if op.stop_motion else ''}"
    if isinstance(op, ir.Resume):
        return f"resume {op.axis}"
    if isinstance(op, ir.Step):
        return f"step {op.axis} {expr_text(op.count)}"
    if isinstance(op, ir.Native):
        args = ", ".join(_any_text(a) for a in op.args)
        axis = f" axis={op.axis}" if op.axis else ""
        form = f" form={json.dumps(op.form)}" if op.form else ""
        return f"native {op.dialect} {op.mnemonic}{axis}{form} ({args})"
    return f"<{type(op).__name__}>"


def term_text(term: ir.Terminator | None) -> str:
    if term is None:
        return "<no terminator>"
    if isinstance(term, ir.Jump):
        return f"jump {term.target}"
    if isinstance(term, ir.Branch):
        return f"branch {cond_text(term.cond)} ? {term.then} : {term.otherwise}"
    if isinstance(term, ir.Return):
        return "return"
    if isinstance(term, ir.End):
        return "end"
    if isinstance(term, ir.GotoRoutine):
        return f"goto routine {term.routine}"
    if isinstance(term, ir.FallOff):
        return "fall off"
    return f"<{type(term).__name__}>"


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
