"""The shared rule `motion-never-stopped`: motion that only ends when stopped, on an axis nothing in
the program stops.

Each dialect that has it gives it a code, a page and its messages in a module of its own
package (`speak`); the function's docstring names the fields, options and hooks it reads.
"""

from __future__ import annotations

from mcc.compiler import ir
from mcc.compiler.lint import flow
from mcc.compiler.lint.rules import Context
from mcc.compiler.lint.rules.shared.helpers import const, same_axis
from mcc.compiler.lint.rules.shared.voice import Voice


NAME = "motion-never-stopped"
# the message variants (`"motion-never-stopped.<variant>"`) each dialect that has the rule gives
VARIANTS = ('slew', 'move')


def endless(op) -> str:
    """The kind of motion that runs until something stops it: "slew" (a jog, or a constant velocity
    known not to be 0), "move" (a move that keeps running at its target), or ""."""
    if isinstance(op, ir.Slew):
        return "slew" if op.velocity is None or const(op.velocity) not in (None, 0) else ""
    if isinstance(op, ir.Move) and any(key == "continuous" and const(value) == 1 for key, value in op.options):
        return "move"
    return ""


def stopped_axis(op) -> str | None:
    """The axis an operation may stop: a stop, a slew at a velocity that is (or may be) 0, or an
    input set up as a soft stop (the operator's switch stops the motion)."""
    if isinstance(op, ir.Stop):
        return op.axis
    if isinstance(op, ir.Slew) and op.velocity is not None and const(op.velocity) in (None, 0):
        return op.axis
    if isinstance(op, ir.Setting) and op.name == "input_function" and isinstance(op.value, ir.Text) \
            and op.value.value == "soft_stop":
        return op.axis
    return None


def motion_never_stopped(ctx: Context, voice: Voice) -> None:
    """Motion that only ends when stopped, on an axis nothing in the program stops. Hooks:
    `endless(op)` names the kind of a native endless move, `stops(op)` the axis a native command
    stops (or None). Message variants `.slew`, `.move` and the hook's kinds; field: axis. Option
    `once`: kinds reported once per file (a native move whose mode is only possibly endless)."""
    native_endless = voice.hook("endless", lambda op: "")
    native_stop = voice.hook("stops", lambda op: None)
    once = set(voice.options.get("motion-never-stopped", {}).get("once", ()))
    stopped: set[str] = set()
    moving: list[tuple[object, str]] = []
    for _, _, op in flow.ops(ctx.module):
        kind = endless(op) or native_endless(op)
        if kind:
            moving.append((op, kind))
        axis = stopped_axis(op)
        if axis is None:
            axis = native_stop(op)
        if axis is not None:
            stopped.add(axis)
    reported: set[str] = set()
    for op, kind in moving:
        axis = getattr(op, "axis", "") or (op.targets[0][0] if isinstance(op, ir.Move) and op.targets else "")
        if any(same_axis(axis, other) for other in stopped) or kind in reported:
            continue
        if kind in once:
            reported.add(kind)
        ctx.report(op.span, voice.say(f"motion-never-stopped.{kind}", axis=axis))
