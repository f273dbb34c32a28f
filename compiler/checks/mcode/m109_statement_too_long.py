r"""# M109 statement-too-long

The statement is longer than the device's 64-character line buffer.

- kind: semantic
- default severity: error
- dialects: mcode
- fix available: no
- manual: L626, L4897

## What it means

The device buffers at most 64 characters per line, including spaces (L626, L4897). A longer line
overflows: the device answers Error 20 and the statement is lost. Shorten names or texts, or split
the work over two statements.

## Bad

```
PR "The axis has reached the end of its travel, please reset the machine now"
```

## Good

```
PR "End of travel reached."
PR "Reset the machine."
```
"""

from __future__ import annotations

from mcc.compiler.checks import Context, check
from mcc.compiler.checks.mcode.helpers import line_limit


@check(needs=("long lines",))
def statement_too_long(ctx: Context) -> None:
    """The device buffers 64 characters per line, comments and spaces included (L626, L4897): a
    statement longer than that is cut whatever is done with the comments (a line that is long only
    with its comment is M110)."""
    source = ctx.program.source
    limit = line_limit(ctx.program)
    for line in ctx.program.tree.lines:
        stmt = line.statement
        if stmt is None or len(source.line_text(line.number)) <= limit:
            continue
        body = source.text[stmt.span.start:stmt.span.end]
        if len(body) > limit:
            ctx.report(stmt.span, f"this statement is {len(body)} characters; the device accepts {limit} per line "
                                  "(Error 20): shorten names or split the work over two statements")
