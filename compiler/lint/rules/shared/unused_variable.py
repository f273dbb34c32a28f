"""The shared rule `unused-variable`: a declared variable nothing reads.

Each dialect that has it gives it a code, a page and its messages in a module of its own
package (`speak`); the function's docstring names the fields, options and hooks it reads.
"""

from __future__ import annotations

from mcc.compiler.diagnostics import Fix
from mcc.compiler.lint.edits import delete_line
from mcc.compiler.lint.rules import Context
from mcc.compiler.lint.rules.shared.voice import Voice


NAME = "unused-variable"
# the message variants (`"unused-variable.<variant>"`) each dialect that has the rule gives
VARIANTS = ('never', 'written')


def unused_variable(ctx: Context, voice: Voice) -> None:
    """A declared variable (`Module.variables` with a span) whose value nothing reads, from the
    def-use chains; updating a variable from itself (`IC Q1`) is not a read. Variants `.never`
    (nothing mentions it: the fix deletes the declaration's line) and `.written`; fields: name (as
    written), host (the `.host` message for a global variable, which a host may read). Hook
    `name_span(ctx, variable)`: the span of the declared name; hook `declaration_lines(ctx, variable)`:
    every line that declares it (a file may declare it again, which the device refuses), all deleted
    by the one fix."""
    defuse = ctx.analysis.defuse
    name_span = voice.hook("name_span", lambda ctx, var: var.span)
    for name, var in ctx.module.variables.items():
        if var.span is None or defuse.read(name):
            continue
        mentioned = defuse.mentioned(name)
        lines = voice.hook("declaration_lines", lambda ctx, var: [var.span.line])(ctx, var)
        fix = None if mentioned else Fix("delete the declaration",
                                         tuple(delete_line(ctx.source, line) for line in lines), safe=False)
        where = name_span(ctx, var)
        written = ctx.source.text[where.start:where.end] if where is not var.span else name
        host = voice.say("unused-variable.host") if var.scope == "global" and "unused-variable.host" in \
            voice.messages else ""
        ctx.report(where, voice.say("unused-variable." + ("written" if mentioned else "never"), name=written,
                                    host=host), fix=fix)
