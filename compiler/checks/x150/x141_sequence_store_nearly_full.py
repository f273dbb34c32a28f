r"""# X141 sequence-store-nearly-full

A device's sequences fill most of its 8,000-byte sequence store.

- kind: semantic
- default severity: warning
- dialects: x150
- fix available: no
- manual: L241, L4871

## What it means

The sequences defined for one device take more than `x150.store_warn_ratio` (90 %) of its sequence
store (8,000 bytes, L4871), counted as the backend writes them: one byte per character and
delimiter (L241, an assumption of mcc: the manual does not say how the store counts). A program
this close to the limit may not fit after the next change, or if the controller counts otherwise.
Over the limit is the error X123. `mcc check --format json` shows the count (`"memory"`).
"""

from __future__ import annotations

from mcc.compiler.checks import Context, check
from mcc.compiler.checks.x150.helpers import limits, stores


@check(needs=("sequences",))
def sequence_store_nearly_full(ctx: Context) -> None:
    """On a device's last sequence, from the profile's `x150.store_warn_ratio` of the store on (0.9
    by default), when they still fit (else X123)."""
    found_limits = limits(ctx.program)
    store = found_limits.store
    for found in stores(ctx.program):
        if not found.full and found.total > found_limits.store_ratio * store:
            ctx.report(found.unit.start.span,
                       f"the sequences for {found.who} need {found.total} of the {store} bytes of the sequence store "
                       f"({100 * found.total / store:.1f} %, L4871): little room is left for changes; the count "
                       "assumes 1 byte per character and delimiter (L241)")
