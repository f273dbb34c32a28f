"""The shared rule `move-before-speed`: a move before the speed settings it uses are set on every path.

Each dialect that has it gives it a code, a page and its messages in a module of its own
package (`speak`); the function's docstring names the fields, options and hooks it reads.
"""

from __future__ import annotations

from mcc.compiler import ir
from mcc.compiler.lint import flow
from mcc.compiler.lint.rules import Context
from mcc.compiler.lint.rules.shared.helpers import MOTION, motion_axes, walk
from mcc.compiler.lint.rules.shared.voice import Voice


NAME = "move-before-speed"


def move_before_speed(ctx: Context, voice: Voice) -> None:
    """Option `params`: the motion settings a move needs (`ir.MotionParam`s), `kinds`: the operations
    that use them (default: moves, arcs, slews, homing); hooks `facts(item)`
    and `needs(item)` add settings only the dialect has (X150's distance register), `moves(item)`
    recognises a move the dialect keeps native. Fields: axis, names (the missing settings in the
    dialect's words, ", "), verb ("is" or "are"). One finding per routine: its first such move."""
    options = voice.options["move-before-speed"]
    params = tuple(options["params"])
    kinds = tuple(options.get("kinds", MOTION))
    extra_facts = voice.hook("facts", lambda item: ())
    extra_needs = voice.hook("needs", lambda item: ())
    native_move = voice.hook("moves", lambda item: False)

    def gen(item):
        facts = [(item.param, item.axis)] if isinstance(item, ir.SetMotion) and item.param in params else []
        return facts + list(extra_facts(item))

    facts = flow.MustFacts(ctx.module, gen)
    entries = flow.stream_entries(ctx.module, facts.transfer, frozenset.intersection, subroutines=False)
    for name, states in facts.states(entries).items():
        routine = ctx.module.routine(name)
        for item, state in walk(routine, states, facts.transfer):
            axes = motion_axes(item) if isinstance(item, kinds) else \
                (item.axis,) if native_move(item) else ()
            missing: list = []
            for axis in axes:
                needed = list(params) + list(extra_needs(item))
                missing = [p for p in needed if (p, axis) not in state and (p, ir.ALL_AXES) not in state]
                if missing:
                    names = ", ".join(voice.word(p.value if isinstance(p, ir.MotionParam) else p) for p in missing)
                    ctx.report(item.span, voice.say("move-before-speed", axis=axis, names=names,
                                                    verb="is" if len(missing) == 1 else "are"))
                    break
            if missing:
                break
