"""What several MCode rules (M3xx) share: the catalog's trip bits, the `TE=` writes, the trip
handlers, the file's comment marker. Facts about commands come from the catalog, never from tables
written here.
"""

from __future__ import annotations

from functools import lru_cache

from mcc.compiler import ir
from mcc.compiler.lint import flow
from mcc.compiler.lint.rules import Context
from mcc.compiler.mcode import catalog as mcat
from mcc.compiler.mcode.lower import TRIP_EVENTS


EVENT_TRIP = {event: name for name, event in TRIP_EVENTS.items()}  # "input" -> "TI"
SUBROUTINE_KINDS = (ir.RoutineKind.SUBROUTINE, ir.RoutineKind.HANDLER)


@lru_cache(maxsize=1)
def catalog() -> mcat.McodeCatalog:
    return mcat.load()


def trip_bit(event: str) -> int:
    """The TE bit of a trip event, from the catalog's `trip_bit` (TI 1, TP 2, ... TM 64)."""
    command = catalog().lookup(EVENT_TRIP.get(event, ""))
    return int(command.entry.get("trip_bit", 0)) if command is not None else 0


def is_te(op) -> bool:
    """A `TE=`: the neutral setting `handler_enable` (or a Native TE of an older lowering)."""
    return (isinstance(op, ir.Setting) and op.name == "handler_enable") or \
        (isinstance(op, ir.Native) and op.mnemonic == "TE" and bool(op.args))


def te_value(op):
    return op.value if isinstance(op, ir.Setting) else op.args[0]


def te_writes(module: ir.Module):
    """Every `TE=` of the module: (routine, block, op, constant value or None)."""
    for routine in module.routines:
        for block in routine.blocks:
            for op in block.ops:
                if is_te(op):
                    value = te_value(op)
                    yield routine, block, op, value.value if isinstance(value, ir.Const) else None


def handlers(module: ir.Module) -> list[ir.SetHandler]:
    return [op for _, _, op in flow.ops(module, ir.SetHandler)]


def line_of(span) -> int:
    return span.line if span is not None else 0


def comment_marker(ctx: Context) -> str:
    """The comment character the file already uses (backtick or apostrophe)."""
    for line in ctx.tree.lines:
        if line.comment is not None:
            return line.comment.text[0]
    return "'"
