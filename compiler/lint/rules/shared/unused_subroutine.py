"""The shared rule `unused-subroutine`: a numbered routine nothing in the file runs.

Each dialect that has it gives it a code, a page and its messages in a module of its own
package (`speak`); the function's docstring names the fields, options and hooks it reads.
"""

from __future__ import annotations

from mcc.compiler import ir
from mcc.compiler.lint.rules import Context
from mcc.compiler.lint.rules.shared.voice import Voice


NAME = "unused-subroutine"


def unused_subroutine(ctx: Context, voice: Voice) -> None:
    """A numbered routine (a subroutine or a stored program) that nothing in the file calls,
    transfers to or installs as a handler, from the symbol table. Hooks: `dynamic(ctx)` answers
    True when the file chooses routines at run time (then nothing is reported), `fix(ctx, routine)`.
    Field: number."""
    if voice.hook("dynamic", lambda ctx: False)(ctx):
        return
    symbols = ctx.analysis.symbols.routines
    make_fix = voice.hook("fix", lambda ctx, routine: None)
    entry = voice.hook("entry", lambda ctx, routine: False)  # the device itself runs it (an error handler)
    for routine in ctx.module.routines:
        if routine.number is None or routine.kind not in (ir.RoutineKind.SUBROUTINE, ir.RoutineKind.MAIN):
            continue
        if entry(ctx, routine):
            continue
        if symbols[routine.name].used:
            continue
        ctx.report(routine.span or ctx.source.line_span(1), voice.say("unused-subroutine", number=routine.number),
                   fix=make_fix(ctx, routine))
