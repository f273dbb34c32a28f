"""The printer's operations and terminators as they were written by hand before the operation
table (compiler/ir_ops.py) derived them from its syntax templates (issue 26): the oracle that shows
the derived printer writes every operation byte for byte as before (tests/ir/test_ir_table_print.py).
Expressions and conditions are still printed by compiler/ir_print.py, which did not change."""

from __future__ import annotations

import json

from mcc.compiler import ir
from mcc.compiler.ir_print import _any_text, _axes, cond_text, expr_text


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


