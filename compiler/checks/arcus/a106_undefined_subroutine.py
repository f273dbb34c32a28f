r"""# A106 undefined-subroutine

GOSUB calls a subroutine that the file does not define.

- kind: semantic
- default severity: error
- dialects: arcus
- fix available: no
- manual: L2176-L2192, L823

## What it means

GOSUB n jumps to SUB n, which must be defined in the same program after END. Calling a subroutine
that does not exist is an error on the controller (the host GS command reports it, L823). The DXF
converter's output calls SUB 1 (pen up) and SUB 2 (pen down) without defining them (L1197-L1222):
add them before downloading.

## Bad

```
GOSUB 1
END
```

## Good

```
GOSUB 1
END
SUB 1
DO1=0
ENDSUB
```
"""

from __future__ import annotations

from mcc.compiler.checks import Context, check


@check(needs=("subroutine calls",))
def undefined_subroutine(ctx: Context) -> None:
    """Every GOSUB n needs a SUB n in the file: the controller stops in error otherwise (L823).
    One diagnostic per missing number, on its first call, the other calls in a note."""
    subs = ctx.lowering.program.subs
    missing: dict[int, list] = {}
    for call in ctx.lowering.program.calls:
        if call.valid and call.number not in subs:
            missing.setdefault(call.number, []).append(call)
    defined = ", ".join(str(n) for n in sorted(subs)) or "none"
    for number, calls in missing.items():
        first = calls[0]
        notes = (f"also called at line{'s' if len(calls) > 2 else ''} "
                 f"{', '.join(str(c.span.line) for c in calls[1:])}",) if len(calls) > 1 else ()
        ctx.report(first.number_span or first.span,
                   f"GOSUB {number}: there is no SUB {number} in this file (defined: {defined}); "
                   f"add SUB {number} ... ENDSUB after END", notes=notes)
