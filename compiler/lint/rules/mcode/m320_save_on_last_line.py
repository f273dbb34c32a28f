r"""# M320 save-on-last-line

`S` is the last line of the file, so its line end may never be sent.

- kind: lint
- default severity: warning
- dialects: mcode
- fix available: yes
- manual: L5266-L5278

## What it means

"The line following the S should have a comment line to guarantee the <CR/LF> after the S"
(L5269): a downloader may not send the last line's terminator, and a command without its
terminator is never executed. The fix (safe) adds a comment line after `S`.

## Bad

```
PG 1
LB G1
  E
PG
S
```

## Good

```
PG 1
LB G1
  E
PG
S
' keep this line
```
"""

from __future__ import annotations

from mcc.compiler.diagnostics import Fix
from mcc.compiler.lint.edits import insert_after_line
from mcc.compiler.lint.rules import Context, rule
from mcc.compiler.lint.rules.mcode.helpers import comment_marker


@rule
def save_on_last_line(ctx: Context) -> None:
    content = [line for line in ctx.tree.lines if line.statement is not None or line.comment is not None or line.error]
    if not content:
        return
    last = content[-1]
    stmt = last.statement
    if stmt is None or stmt.head.key != "S" or stmt.args:
        return
    marker = comment_marker(ctx)
    fix = Fix("add a comment line after S",
              (insert_after_line(ctx.source, last.number, f"{marker} keep this line: it ends the S\n"),))
    ctx.report(stmt.span, "S is the last line: add a comment line after it so its line end is sent (L5269)", fix=fix)
