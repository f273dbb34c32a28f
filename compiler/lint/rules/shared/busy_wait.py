"""The shared rule `busy-wait`: a loop that only computes: it spins the controller instead of waiting.

Each dialect that has it gives it a code, a page and its messages in a module of its own
package (`speak`); the function's docstring names the fields, options and hooks it reads.
"""

from __future__ import annotations

from mcc.compiler import ir
from mcc.compiler.lint import flow
from mcc.compiler.lint.rules import Context
from mcc.compiler.lint.rules.shared.voice import Voice


NAME = "busy-wait"


def busy_wait(ctx: Context, voice: Voice) -> None:
    """A loop whose blocks (inner loops included) only compute: no delay, wait, motion, output,
    call or native command. Reported at the loop's test. No fields."""
    for routine in ctx.module.routines:
        forest = flow.loop_forest(routine)  # innermost first, each block in one loop: linear
        idle: dict[str, bool] = {}
        for loop in forest:
            idle[loop.header.label] = all(isinstance(op, ir.Assign) for block in loop.blocks for op in block.ops) \
                and all(idle[inner.header.label] for inner in loop.inner)
        for loop in forest:
            if isinstance(loop.header.terminator, ir.Branch) and idle[loop.header.label]:
                ctx.report(loop.header.terminator.span, voice.say("busy-wait"))
