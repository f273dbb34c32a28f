"""The X150's position report, defined once.

`aPR` answers "a number preceded by a sign and followed by a carriage return *(s)n[CR]"
(parker-x150.md L3141), e.g. `*-25600` (L3143). mcc's decisions (docs/dialects/x150.md, "Reports"):
the sign is always sent, `+` for zero and positive positions (`*+4000`, `*+0`): the manual says
"preceded by a sign", and "the sign indicates which side of the absolute zero position the motor
is on"; no spaces (the `* - 140000` of the IV example, L2216, is the typesetting of the same
report, whose own definition and example have none).

The lowering makes `aPR` this print, the X150 writer writes this print back as `PR` (and refuses a
position printed any other way: X150 has no other way to send it), and the virtual device answers
`PR` by running it on the simulator, so the text is the IR's and the simulator's alone.
"""

from __future__ import annotations

from mcc.compiler import ir
from mcc.compiler.span import Span

PREFIX = "*"  # every X150 report starts with it (L3141; `*R` L235, `*122` L289, `*0000000_...` L2134)


def position(axis: str, span: Span | None, sender: str = "") -> ir.Print:
    """`aPR`: the prefix, then the position counter with its sign, then a line end."""
    return ir.Print((ir.Text(PREFIX, span), ir.Status("position", axis, None, span)), True, span, sender, signed=True)


def position_axis(op: ir.Print) -> str | None:
    """The axis whose position `op` reports in the PR format, or None when it is another print."""
    items = op.items
    if op.signed and op.newline and len(items) == 2 and isinstance(items[0], ir.Text) and items[0].value == PREFIX \
            and isinstance(items[1], ir.Status) and items[1].meaning == "position" and items[1].index is None:
        return items[1].axis
    return None
