r"""# M110 comment-overflows-line

The statement fits in 64 characters, but not with its trailing comment.

- kind: semantic
- default severity: warning
- dialects: mcode
- fix available: no
- manual: L626

## What it means

Downloaders differ in whether they send comments to the device. One that does sends more than the
64-character buffer holds and the device reports Error 20 for the line. Move the comment to its own
line or shorten it. The profile key `mcode.comment_line_policy` ("warn", "error", "ignore")
changes this; comment-only lines are not reported unless `mcode.comment_only_lines = "warn"`.

## Bad

```
MA 512000   ` move ten revolutions forward to the pick position above the tray
```

## Good

```
` move ten revolutions forward to the pick position above the tray
MA 512000
```
"""

from __future__ import annotations

from mcc.compiler.checks import Context, check
from mcc.compiler.checks.mcode.helpers import line_limit
from mcc.compiler.diagnostics import Severity


@check(needs=("long lines", "comment overflow reported"))
def comment_overflows_line(ctx: Context) -> None:
    """A line over the limit only with its comment (a longer statement is M109). Whether that is a
    warning, an error or nothing is the profile's `mcode.comment_line_policy`; a line that is only
    a comment follows `mcode.comment_only_lines` (docs/dialects/mcode.md)."""
    source = ctx.program.source
    limit = line_limit(ctx.program)
    policy = ctx.profile.get("mcode.comment_line_policy", "warn")
    comment_only = ctx.profile.get("mcode.comment_only_lines", "ignore")
    for line in ctx.program.tree.lines:
        text = source.line_text(line.number)
        if len(text) <= limit:
            continue
        stmt = line.statement
        if stmt is not None and len(source.text[stmt.span.start:stmt.span.end]) > limit:
            continue  # M109
        if stmt is None and comment_only == "ignore":
            continue
        if len(text.strip()) > limit:
            ctx.report(source.line_span(line.number),
                       f"the line is {len(text.strip())} characters with its comment; downloaders that send "
                       f"comments overflow the {limit}-character buffer: shorten the comment or move it to its own "
                       "line", severity=None if policy == "warn" else Severity.ERROR)
