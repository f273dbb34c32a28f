r"""# A127 apostrophe-comment

An apostrophe comment, as the DXF converter writes them.

- kind: semantic
- default severity: warning
- dialects: arcus
- fix available: no
- manual: L1197-L1222, L1721-L1729

## What it means

The standalone language's comment starts with ';' (L1721). The DXF converter's generated program
uses "'" (L1201); mcc reads those as comments so that converter output can be checked, but the
controller's compiler may not. Replace "'" by ';'. Set `apostrophe_comments` in the profile's
`[arcus]` table to "error" or "ignore" to change this finding. mcc never writes comments.

## Bad

```
GOSUB 1 '***Pen Up
```

## Good

```
GOSUB 1 ;***Pen Up
```
"""

from __future__ import annotations

from mcc.compiler.checks import Context, check
from mcc.compiler.diagnostics import Severity


@check(needs=("apostrophe comments reported",))
def apostrophe_comment(ctx: Context) -> None:
    """"'" comments are what the DXF converter writes (L1201); the language's comment is ';' (L1721).
    One diagnostic for the file, on the first, with the count of the others; a warning or an error
    as the profile's `arcus.apostrophe_comments` says."""
    found = [c for c in ctx.program.tree.comments() if c.text.startswith("'")]
    if not found:
        return
    first = found[0]
    notes = (f"{len(found) - 1} more \"'\" comment{'s' if len(found) > 2 else ''} in this file",) if len(found) > 1 else ()
    policy = str(ctx.profile.get("arcus.apostrophe_comments", "warn"))
    ctx.report(first.span, "\"'\" starts a comment only in the DXF converter's output: the standalone language uses "
                           "';' (L1721); replace \"'\" by ';'", notes=notes,
               severity=Severity.ERROR if policy == "error" else None)
