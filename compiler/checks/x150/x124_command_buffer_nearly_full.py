r"""# X124 command-buffer-nearly-full

One sequence is close to (or over) the 2,000-byte command buffer it is downloaded through.

- kind: semantic
- default severity: warning
- dialects: x150
- fix available: no
- manual: L241, L4904

## What it means

XDn "clears the command buffer and all subsequent commands will be stored in the buffer until
receipt of an XT": a sequence is received through the 2,000-byte command buffer, so a very long
one may not download. mcc warns from 90% of the buffer (`x150.buffer_warn_ratio`). Split the work
into sequences that call each other with XR.

## Bad

```
; one sequence of 1,900 bytes
```

## Good

```
; two sequences of 950 bytes, the first ending with XR2
```
"""

from __future__ import annotations

from mcc.compiler.checks import Context, check
from mcc.compiler.checks.x150.helpers import limits, sizes


@check(needs=("sequences",))
def command_buffer_nearly_full(ctx: Context) -> None:
    """From the profile's `x150.buffer_warn_ratio` of the command buffer on (0.9 by default)."""
    found = limits(ctx.program)
    for unit, size in sizes(ctx.program):
        if size >= found.buffer_ratio * found.buffer:
            over = "more than" if size > found.buffer else "close to"
            ctx.report(unit.start.span, f"sequence {unit.number} is {size} bytes, {over} the {found.buffer}-byte "
                                        "command buffer it is downloaded through (L241, L4904): split it into "
                                        "sequences that call each other")
