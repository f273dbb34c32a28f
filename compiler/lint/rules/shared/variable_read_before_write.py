"""The shared rule `variable-read-before-write`: a variable read on a path where nothing has written it
yet.

Each dialect that has it gives it a code, a page and its messages in a module of its own
package (`speak`); the function's docstring names the fields, options and hooks it reads.
"""

from __future__ import annotations

from mcc.compiler import ir
from mcc.compiler.lint import flow
from mcc.compiler.lint.rules import Context
from mcc.compiler.lint.rules.shared.helpers import reads, walk
from mcc.compiler.lint.rules.shared.voice import Voice


NAME = "variable-read-before-write"


def variable_read_before_write(ctx: Context, voice: Voice) -> None:
    """A variable read on a path where nothing has written it yet (once per routine and variable).
    Only variables the def-use chains show read are followed. Field: name."""
    defuse = ctx.analysis.defuse
    if not defuse.uses:
        return

    def gen(item):
        return (item.target.name,) if isinstance(item, ir.Assign) else ()

    facts = flow.MustFacts(ctx.module, gen)
    seen: set[tuple[str, str]] = set()
    for name, states in facts.states().items():
        routine = ctx.module.routine(name)
        for item, written in walk(routine, states, facts.transfer):
            for node in reads(item):
                if isinstance(node, ir.Var) and node.name not in written and (name, node.name) not in seen:
                    seen.add((name, node.name))
                    ctx.report(node.span or item.span, voice.say("variable-read-before-write", name=node.name))
