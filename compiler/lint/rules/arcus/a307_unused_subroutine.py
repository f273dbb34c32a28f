r"""# A307 unused-subroutine

A `SUB` that no `GOSUB` of the program calls.

- kind: lint
- default severity: warning
- dialects: arcus
- fix available: yes
- manual: L823, L2176-L2192, L2619-L2631

## What it means

A subroutine costs program memory (each line is 1-4 of the 3230 assembly lines, L827) and is only
run by `GOSUB n` (L2176-L2192). One that nothing calls is usually left over, or its `GOSUB` has
the wrong number. A host can still run it with the ASCII command `GS n` (L823): suppress the
finding on the `SUB` line in that case. The fix (unsafe) deletes the subroutine.

## Bad

```
GOSUB 1
END
SUB 1
DO1=1
ENDSUB
SUB 2
DO2=1
ENDSUB
```

## Good

```
GOSUB 1
GOSUB 2
END
SUB 1
DO1=1
ENDSUB
SUB 2
DO2=1
ENDSUB
```
"""

from __future__ import annotations

from mcc.compiler import ir
from mcc.compiler.diagnostics import Fix
from mcc.compiler.lint.edits import line_bounds, replace
from mcc.compiler.lint.rules import Context
from mcc.compiler.lint.rules.shared import unused_subroutine
from mcc.compiler.lint.rules.shared.voice import speak


def error_subroutine(ctx, routine) -> bool:
    """The subroutine the controller jumps to on an error (`[arcus] error_subroutine`: SUB 31 on
    the PMX-2ED-SA, p.43 §7.19.5, and the ACE-SDE, p.48 §6.21.5): no GOSUB needs to call it."""
    return routine.number is not None and routine.number == ctx.profile.get("arcus.error_subroutine")


def unused_sub_fix(ctx: Context, routine: ir.Routine) -> Fix | None:
    """Delete `SUB n` ... `ENDSUB` (the routine's span to its last return)."""
    last = routine.blocks[-1].terminator if routine.blocks else None
    if routine.span is None or not isinstance(last, ir.Return) or last.span is None \
            or last.span.line <= routine.span.line:
        return None
    start, _ = line_bounds(ctx.source, routine.span.line)
    _, end = line_bounds(ctx.source, last.span.line)
    return Fix("delete the subroutine", (replace(ctx.source.span(start, end), ""),), safe=False)


speak(__name__, unused_subroutine,
      messages={"unused-subroutine": "no GOSUB calls SUB {number}: remove it, or call it (a host can run it with "
                                     "GS{number}, L823)"},
      hooks={"fix": unused_sub_fix, "entry": error_subroutine})
