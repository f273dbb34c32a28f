"""Redundant motion settings.

What it does: a speed, acceleration, ramp time or device setting that sets the value already in
force is removed (`HSPD=5000` twice around a move keeps the first). A setting on `*` (every
axis) is redundant only when no single axis was set since the same `*` setting. -O1 looks within each block;
-O2 uses the values in force on every path (compiler/in_force.py, `redundant`), across blocks and
calls, for one axis and for `*` alike. Where an axis's own settings are a set of their own
(`Module.axis_sets`, Arcus HSPDa/LSPDa/ACCa, L447-L457), a write is redundant only when its own
register already holds the value: `HSPDX=1000` after `HSPD=1000` is not, since without it the
axis's set is incomplete and the axis runs with the global LSPD and ACC.

Why it is safe: setting a value already in force changes nothing on the device. The values in
force are known only where every path agrees; a call forgets what the callee may set; an event
handler starts knowing nothing. When any event handler changes a motion setting (it may run
between any two operations) the pass removes nothing. Move modes are not settings in the IR (each
move says absolute or relative); the backends write the fewest mode switches themselves.

Needs: values in force (at -O2).
"""

from __future__ import annotations

from mcc.compiler import in_force, ir
from mcc.compiler.opt.common import handler_writes, key

NAME = "settings"
NEEDS = ("in_force",)


def run(module: ir.Module, context) -> int:
    _, handlers_change_motion = handler_writes(module)
    if handlers_change_motion:
        return 0
    removed = local(module)
    if context.global_scope:
        removed += across(module, context)
    return removed


def local(module: ir.Module) -> int:
    removed = 0
    for _, block in module.blocks():
        last: dict[tuple, object] = {}
        kept = []
        for op in block.ops:
            if isinstance(op, (ir.SetMotion, ir.Setting)) and isinstance(op.value, ir.Const):
                slot = slot_of(op)
                value = key(op.value)
                if last.get(slot) == value:
                    removed += 1
                    continue
                if op.axis == ir.ALL_AXES:  # every axis now has this value
                    last = {k: v for k, v in last.items() if k[0] != slot[0]}
                else:  # the axes no longer all agree: a later `*` setting is not redundant
                    last.pop(all_axes(slot), None)
                last[slot] = value
            elif isinstance(op, (ir.SetMotion, ir.Setting)):
                last = {k: v for k, v in last.items() if k[0] != slot_of(op)[0]}
            elif isinstance(op, (ir.Call, ir.Native, ir.Pause)):  # the host may set anything while paused
                last.clear()
            kept.append(op)
        block.ops[:] = kept
    return removed


def all_axes(slot: tuple) -> tuple:
    return (slot[0], ir.ALL_AXES) + slot[2:]


def slot_of(op) -> tuple:
    if isinstance(op, ir.SetMotion):
        return (op.param.value, op.axis)
    return ("setting:" + op.name, op.axis, op.index)


def across(module: ir.Module, context) -> int:
    analysis = context.in_force()
    found: set[int] = set()
    for routine in module.routines:
        for _, _, op, state in analysis.walk(routine):
            if in_force.redundant(state, op):
                found.add(id(op))
    for _, block in module.blocks():
        block.ops[:] = [op for op in block.ops if id(op) not in found]
    return len(found)
