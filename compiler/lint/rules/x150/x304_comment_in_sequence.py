r"""# X304 comment-in-sequence

A comment is written between `XD` and `XT`, where it is not stored.

- kind: lint
- default severity: info
- dialects: x150
- fix available: no
- manual: L5528-L5540

## What it means

"Comments cannot be stored in a sequence" (L5534). A comment inside a definition documents the
source file only: uploading the sequence (`XU`) shows it without comments, and a download tool that
sends the file as it is must strip them. mcc's writer drops them. Put the explanation before the
`XD` line if it must survive next to the sequence.

## Bad

```
1XE1
1XD1
1T1      ; wait a second
1XT
```

## Good

```
; sequence 1 waits a second
1XE1
1XD1
1T1
1XT
```
"""

from __future__ import annotations

from mcc.compiler.lint.rules import Context, rule
from mcc.compiler.x150 import syntax as st


@rule
def comment_in_sequence(ctx: Context) -> None:
    inside = False
    first: st.Comment | None = None
    count = 0
    for line in ctx.tree.lines:
        for command in line.commands:
            if command.mnemonic == "XD":
                inside, first, count = True, None, 0
            elif command.mnemonic == "XT":
                if first is not None:
                    report_comments(ctx, first, count)
                inside, first = False, None
        ends_here = any(c.mnemonic == "XT" for c in line.commands)
        if inside and not ends_here and line.comment is not None:
            first = first or line.comment
            count += 1
    if inside and first is not None:
        report_comments(ctx, first, count)


def report_comments(ctx: Context, first: st.Comment, count: int) -> None:
    notes = (f"{count - 1} more comment{'s' if count > 2 else ''} in this sequence",) if count > 1 else ()
    ctx.report(first.span, "comments between XD and XT are not stored with the sequence (L5534)", notes=notes)
