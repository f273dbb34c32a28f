"""The shared rule `division-by-zero`: `/` or `%` by the constant 0.

Each dialect that has it gives it a code, a page and its messages in a module of its own
package (`speak`); the function's docstring names the fields, options and hooks it reads.
"""

from __future__ import annotations

from mcc.compiler import ir
from mcc.compiler.lint.rules import Context
from mcc.compiler.lint.rules.shared.helpers import const, reads
from mcc.compiler.lint.rules.shared.voice import Voice


NAME = "division-by-zero"


def division_by_zero(ctx: Context, voice: Voice) -> None:
    """`/` or `%` by the constant 0. Field: op."""
    for _, block in ctx.module.blocks():
        for item in [*block.ops, block.terminator]:
            for node in reads(item):
                if isinstance(node, ir.BinOp) and node.op in ("/", "%") and const(node.right) == 0:
                    ctx.report(node.span or item.span, voice.say("division-by-zero", op=node.op))
