r"""# M306 unused-variable

A variable is declared with `VA` but its value is never read.

- kind: lint
- default severity: warning
- dialects: mcode
- fix available: yes
- manual: L537, L543-L555, L6022-L6036

## What it means

Each user variable takes one of the 192 entries of the name table it shares with labels (L537,
L6029). A variable that is only declared, or only written (`Q1=5`, `IC Q1`), does nothing for the
program. A global variable (declared outside `PG`) may be read by a host with `PR`; suppress the
finding there. The fix (unsafe) deletes the declaration when the variable is not used at all.

## Bad

```
VA Q1
VA Q2
PG 1
LB G1
  Q2=5
  E
PG
```

## Good

```
VA Q2
PG 1
LB G1
  Q2=5
  PR Q2
  E
PG
```
"""

from __future__ import annotations

from mcc.compiler import ir
from mcc.compiler.lint.rules import Context
from mcc.compiler.lint.rules.shared import unused_variable
from mcc.compiler.lint.rules.shared.voice import speak
from mcc.compiler.mcode import syntax as st


def declared_name(ctx: Context, var: ir.Variable):
    """The span of the name in `VA <name>` (the IR keeps the whole statement's span)."""
    span = var.span
    for stmt in ctx.tree.statements():
        if stmt.span.line == span.line and stmt.head.key == "VA" and stmt.args:
            arg = stmt.args[0]
            return (arg.left if isinstance(arg, st.Comparison) else arg).span
    return span


def declaration_lines(ctx: Context, var: ir.Variable) -> list[int]:
    """Every `VA <name>` line of the variable (a repeated VA is M141's error; deleting the variable
    deletes them all at once)."""
    lines = []
    for stmt in ctx.tree.statements():
        if stmt.head.key == "VA" and stmt.args:
            arg = stmt.args[0]
            name = arg.left if isinstance(arg, st.Comparison) else arg
            if isinstance(name, st.Name) and name.key == var.name.upper():
                lines.append(stmt.span.line)
    return lines or [var.span.line]


speak(__name__, unused_variable,
      messages={"unused-variable.never": "variable {name} is never used{host}",
                "unused-variable.written": "variable {name} is only written, never read{host}",
                "unused-variable.host": " (if a host reads it with PR, suppress this line)"},
      hooks={"name_span": declared_name, "declaration_lines": declaration_lines})
