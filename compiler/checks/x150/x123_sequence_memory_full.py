r"""# X123 sequence-memory-full

The sequences of one device need more than the 8,000-byte sequence store.

- kind: semantic
- default severity: error
- dialects: x150
- fix available: no
- manual: L241, L4871, L5259-L5265

## What it means

All sequences of a device share 8,000 bytes; XSD reports 2 (buffer full) and the sequence is not
stored. mcc counts the canonical text it would download, one byte per character and delimiter as
the manual states for the command buffer (L241), including each sequence's XT; sequences defined
without an address count on every device. The budget is the profile's
`limits.sequence_store_bytes`.

## Bad

```
; 70 sequences of 120 bytes each
```

## Good

```
; fewer or shorter sequences
```
"""

from __future__ import annotations

from mcc.compiler.checks import Context, check
from mcc.compiler.checks.x150.helpers import limits, stores


@check(needs=("sequences",))
def sequence_memory_full(ctx: Context) -> None:
    """On the first sequence (in file order) with which a device's sequences no longer fit."""
    store = limits(ctx.program).store
    for found in stores(ctx.program):
        if found.full:
            ctx.report(found.unit.start.span,
                       f"with sequence {found.number} the sequences for {found.who} need {found.total} bytes; the "
                       f"sequence store holds {store} (L4871, 1 byte per character and delimiter, L241): shorten "
                       "or remove sequences")
