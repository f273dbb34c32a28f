"""The comment block that heads a program compiled from another dialect: the assumptions of the
conversion, so that whoever loads it onto a controller can check them.

It says where the program came from, the steps per revolution on both sides (and so how positions
and speeds were scaled), the ABS/INC mode assumed at power-up, and that ramp times were computed
from the source's accelerations with the speeds in force. Comments are on their own line, as the
standalone language wants (L1725), and cost no assembly line.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from mcc.backends.arcus.legalize import lowest_speed
from mcc.compiler import in_force, ir
from mcc.compiler.profiles import Profile

if TYPE_CHECKING:
    from mcc.backends.arcus.context import Context


def lines(module: ir.Module, profile: Profile, ctx: "Context") -> list[str]:
    if module.dialect == "arcus":
        return []
    source, target = module.steps_per_rev, profile.steps_per_rev
    if source > 0 and target > 0:
        scale = f"{source} source steps per revolution -> {target} pulses per revolution (profile {profile.name})"
    else:
        unknown = "the target's is" if source > 0 else "the source's is" if target > 0 else "both are"
        scale = (f"steps per revolution: source {source or 'not set'}, target {target or 'not set'}; {unknown} "
                 "unknown, so one source step is one pulse")
    boot = str(profile.get("arcus.boot_move_mode", "abs")).upper()
    axes = ", ".join(f"{name or '(unnamed)'}->{letter}" for name, letter in ctx.axes.map.items()) or "none"
    found = [
        f"; compiled by mcc from {module.dialect} ({module.path or 'source'}, profile {module.profile})",
        f"; {scale}",
        f"; axes: {axes}; move mode at power-up assumed {boot}; ACC ramp times from the source's "
        "accelerations and the speeds in force",
    ]
    if (ir.MotionParam.INITIAL_SPEED, ir.ALL_AXES) in in_force.FIXED.get(module.dialect, {}):
        found.append(f"; {module.dialect} starts every move from standstill: LSPD is set to its lowest, "
                     f"{lowest_speed():g} pulse/s")
    return found
