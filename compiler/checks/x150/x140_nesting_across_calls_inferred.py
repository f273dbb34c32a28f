r"""# X140 nesting-across-calls-inferred

Constructs open around an XR call plus those of the called sequence exceed 16 (inferred limit).

- kind: semantic
- default severity: warning
- dialects: x150
- fix available: no
- manual: L1750, L2011, L2332, L3441, L4849, L5140

## What it means

The manual limits each construct (L..N, IF..NIF, WHILE..NWHILE, REPEAT..UNTIL) to 16 nested levels
(L2011, L2332, L3441, L4849) and sequence calls to 16 nested sequences (L1750, L5140). It does not
say whether the loops open in a sequence count against the same 16 levels as the loops open in the
sequence that called it. mcc infers that they do (one controller, one stack per construct) and
warns when the sum passes the limit; the message says it is inferred. If your controller runs
such a program, ignore X140 (`ignore = ["X140"]`). A chain of calls deeper than 16 is X110, an
error: that limit is the manual's own.

## Bad

```
; ten loops open around XR2, and sequence 2 opens eight more: 18 > 16
1XE2
1XD2
1L2 1L2 1L2 1L2 1L2 1L2 1L2 1L2
1G
1N 1N 1N 1N 1N 1N 1N 1N
1XT
1XE1
1XD1
1L2 1L2 1L2 1L2 1L2 1L2 1L2 1L2 1L2 1L2
1XR2
1N 1N 1N 1N 1N 1N 1N 1N 1N 1N
1XT
```

## Good

```
; the loops around the call reduced to two: 10 levels in all
1XE2
1XD2
1L2 1L2 1L2 1L2 1L2 1L2 1L2 1L2
1G
1N 1N 1N 1N 1N 1N 1N 1N
1XT
1XE1
1XD1
1L2 1L2
1XR2
1N 1N
1XT
```
"""

from __future__ import annotations

from mcc.compiler.checks import Context, check
from mcc.compiler.checks.x150.helpers import nesting


@check(needs=("sequence calls",), also=("X110",))
def nesting_across_calls_inferred(ctx: Context) -> None:
    """Sequence calls nest at most 16 deep (L1750, L5140): X110, whose page is shared with the local
    nesting the lowering checks. That the construct stacks are shared by a sequence and the
    sequences it calls is mcc's inference, reported as the warning X140. One of each per called
    sequence and kind, in the order the walk finds them."""
    limit = ctx.lowering.nesting
    reported: set[tuple[str, str]] = set()
    for found in nesting(ctx.program):
        site, target, context = found.site, found.target, found.context
        if context["call"] > limit and (target, "call") not in reported:
            reported.add((target, "call"))
            ctx.report(site.command.span,
                       f"{site.command.text} nests sequence calls more than {limit} deep (through the calls of this "
                       "file; a sequence that calls itself never stops): the controller allows "
                       f"{limit} (L1750, L5140)", code="X110")
        for kind, depth in found.inside.items():
            total = context.get(kind, 0) + depth
            if total > limit and (target, kind) not in reported:
                reported.add((target, kind))
                ctx.report(site.command.span,
                           f"{site.command.text} runs sequence {site.number}, which opens {kind} {depth} deep, "
                           f"while {context[kind]} are already open: {total} > {limit} if the controller "
                           "counts a called sequence's constructs with its caller's. This is inferred, not "
                           f"stated: the manual limits {kind} nesting to {limit} (L2011, L2332, L3441, L4849) "
                           "and sequence calls to 16 (L1750, L5140), but not the two together; move loops out "
                           "of the called sequence to be safe, or ignore X140 if your controller runs it")
