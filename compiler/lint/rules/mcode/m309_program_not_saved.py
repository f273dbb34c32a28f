r"""# M309 program-not-saved

The file stores a program but never saves it with `S` after the final `PG`.

- kind: lint
- default severity: warning
- dialects: mcode
- fix available: yes
- manual: L5259-L5278

## What it means

Lines between `PG <address>` and `PG` are stored in RAM; `S` copies them and all settings to
non-volatile memory, and unsaved changes are lost at power-off (L5259-L5265). The manual's tip:
"Programs may be automatically saved on load by adding an S after the final PG" (L5269). The fix
(unsafe, because saving changes what a download does to the device) adds `S` and a comment line
after the final `PG`.

## Bad

```
PG 1
LB G1
  MA 1000
  H
  E
PG
```

## Good

```
PG 1
LB G1
  MA 1000
  H
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
from mcc.compiler.mcode import syntax as st


def statement_lines(ctx: Context) -> list[st.Line]:
    return [line for line in ctx.tree.lines if line.statement is not None]


@rule
def program_not_saved(ctx: Context) -> None:
    lines = statement_lines(ctx)
    last_pg = None
    for line in lines:
        if line.statement.head.key == "PG":
            last_pg = line
    if last_pg is None:
        return
    after = [line for line in lines if line.number > last_pg.number]
    if any(line.statement.head.key == "S" and not line.statement.args for line in after):
        return
    marker = comment_marker(ctx)
    fix = Fix("add S and a comment line after the final PG",
              (insert_after_line(ctx.source, last_pg.number, f"S\n{marker} keep this line: it ends the S\n"),),
              safe=False)
    ctx.report(last_pg.statement.span, "the program is stored but never saved: add `S` after the final PG, or it is "
                                       "lost at power-off (L5269)", fix=fix)
