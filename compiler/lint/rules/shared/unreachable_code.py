"""The shared rule `unreachable-code`: code no path from its routine's entry reaches.

Each dialect that has it gives it a code, a page and its messages in a module of its own
package (`speak`); the function's docstring names the fields, options and hooks it reads.
"""

from __future__ import annotations

from mcc.compiler import ir
from mcc.compiler.lint import flow
from mcc.compiler.lint.rules import Context
from mcc.compiler.lint.rules.shared.voice import Voice


NAME = "unreachable-code"


def unreachable_code(ctx: Context, voice: Voice) -> None:
    """A block no path from its routine's entry reaches, that is not a label and that nothing
    jumps to; the conventional lone end after an endless main loop is not reported. Option
    `skip_immediate`. No fields."""
    module = ctx.module
    skip_immediate = voice.options.get("unreachable-code", {}).get("skip_immediate", False)
    targeted = {label for _, block in module.blocks() for label in ir.successors(block.terminator)}
    for routine in module.routines:
        if routine.kind is ir.RoutineKind.IMMEDIATE and skip_immediate:
            continue
        live = {b.label for b in flow.reachable(routine)}
        for block in routine.blocks:
            if block.label in live or block.named or block.label in targeted:
                continue
            if not block.ops and isinstance(block.terminator, (ir.End, ir.FallOff)):
                continue
            first = block.ops[0] if block.ops else block.terminator
            ctx.report(first.span, voice.say("unreachable-code"))
