r"""# X302 endless-loop

`L` without a count loops forever, and nothing in the program ends it.

- kind: lint
- default severity: warning
- dialects: x150
- fix available: no
- manual: L2326-L2334, L2089, L5492-L5495

## What it means

"If L is entered with no number following it or if n = 0, the commands will be repeated
indefinitely" (L2326-L2328). Such a loop ends at the end of a pass when `Y` is received (L5494), when
an input with function M is activated (L2089), or by a stop, kill or jump out of the loop. Without
any of those in the program, only an operator can stop the axis. Give the loop a count, configure a
loop-end input (`IN<n>M`), or leave the loop with `XG`/`XRT` on a condition.

## Bad

```
1XE5
1XD5
1A10
1V5
1L
1D100
1G
1N
1XT
```

## Good

```
1IN5M
1XE5
1XD5
1A10
1V5
1L
1D100
1G
1N
1XT
```
"""

from __future__ import annotations

from mcc.compiler.lint.rules import Context, rule
from mcc.compiler.lint.rules.x150.helpers import meaning
from mcc.compiler.x150 import syntax as st


LOOP_EXIT_IRS = ("stop", "kill", "goto", "return")
LOOP_EXIT_NAMES = ("Y", "HALT", "OFF")  # L5494, L1883, L2800


def loop_end_input(tree: st.SyntaxTree) -> bool:
    """An input configured with function M ends loops (L2089)."""
    return any(isinstance(c.arg, st.IoFunction) and c.arg.function.upper() == "M" and c.mnemonic == "IN"
               for c in tree.commands())


def endless(command: st.Command) -> bool:
    if command.mnemonic != "L":
        return False
    return command.arg is None or isinstance(command.arg, st.Number) and command.arg.value == 0


def exits_loop(command: st.Command) -> bool:
    return command.mnemonic in LOOP_EXIT_NAMES or meaning(command.mnemonic) in LOOP_EXIT_IRS


@rule
def endless_loop(ctx: Context) -> None:
    if loop_end_input(ctx.tree) or any(c.mnemonic == "Y" for c in ctx.tree.commands()):
        return  # an input with function M, or a Y sent by the host, ends the loop (L2089, L5494)
    stack: list[tuple[st.Command, bool]] = []  # (L command, has an exit)
    for command in ctx.tree.commands():
        if command.mnemonic in ("XD", "XT"):
            stack.clear()
        elif command.mnemonic == "L":
            stack.append((command, False))
        elif command.mnemonic == "N" and stack:
            opener, exited = stack.pop()
            if endless(opener) and not exited:
                ctx.report(opener.span, "this loop repeats forever and nothing in the program ends it: give L a "
                                        "count, or end it with Y, an input with function M (L2089) or a jump")
        elif exits_loop(command) and stack:
            stack = [(opener, True) for opener, _ in stack]
