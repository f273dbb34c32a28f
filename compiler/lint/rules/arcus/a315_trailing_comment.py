r"""# A315 trailing-comment

A comment follows a statement on the same line.

- kind: lint
- default severity: info
- dialects: arcus
- fix available: yes
- opt-in: off unless selected by its code (`extend-select = ["A315"]`)
- manual: L1721-L1736

## What it means

The language specification says "In programming, comment must be in its own line" (L1725),
although the manual's examples put comments after statements (e.g. L1864, L1906, L2230), and so do
real programs. mcc reads both, and the controllers the manual describes do too, so this rule is
opt-in: it runs only when selected by its code (`extend-select = ["A315"]` in the configuration, or
`mcc lint --extend-select A315`), for a project whose download tool follows the specification. The
fix (safe) moves the comment onto its own line above the statement.

## Bad

```
X1000 ;***move X
END
```

## Good

```
;***move X
X1000
END
```
"""

from __future__ import annotations

from mcc.compiler.diagnostics import Fix
from mcc.compiler.lint.edits import line_bounds, replace
from mcc.compiler.lint.rules import Context, rule


@rule
def trailing_comment(ctx: Context) -> None:
    for line in ctx.tree.lines:
        if line.statement is None or line.comment is None:
            continue
        text = ctx.source.line_text(line.number)
        indent = text[:len(text) - len(text.lstrip())]
        start, _ = line_bounds(ctx.source, line.number)
        code_end = line.statement.span.end
        comment = line.comment
        fix = Fix("move the comment to its own line", (
            replace(ctx.source.span(start, start), f"{indent}{comment.text.rstrip()}\n"),
            replace(ctx.source.span(code_end, comment.span.end), ""),
        ))
        ctx.report(comment.span, "the specification wants comments on their own line (L1725)", fix=fix)
