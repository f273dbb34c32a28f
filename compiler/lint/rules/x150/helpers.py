"""What several X150 rules (X3xx) share. An X150 file is a stream: set-up commands sent
immediately, sequences (`XDn ... XT`) stored for later, and commands that run them. The IR gives
each stretch of the stream and each sequence a routine; settings made by the stream persist on the
controller, so a sequence nothing in the file calls starts with what the whole stream set. What a
command *means* (stop, kill, goto, call) comes from the catalog's `ir` field.
"""

from __future__ import annotations

from functools import lru_cache

from mcc.compiler import ir
from mcc.compiler.lint import flow
from mcc.compiler.x150 import catalog as xcat


X150 = "x150"


@lru_cache(maxsize=1)
def catalog() -> xcat.X150Catalog:
    return xcat.load()


def meaning(mnemonic: str) -> str:
    entry = catalog().lookup(mnemonic)
    return entry.ir if entry is not None else ""


def native(item, *names: str) -> bool:
    return isinstance(item, ir.Native) and item.dialect == X150 and item.mnemonic in names


def const(expr) -> float | None:
    return expr.value if isinstance(expr, ir.Const) else None


def is_go(item) -> bool:
    """A move: a preset Move, or a G that stays Native (continuous mode, L2498)."""
    return isinstance(item, (ir.Move, ir.Slew)) or native(item, "G")


def axis_of(item) -> str:
    if isinstance(item, ir.Move):
        return item.targets[0][0] if item.targets else ""
    return getattr(item, "axis", "")


def any_op(module: ir.Module, wanted) -> bool:
    """Whether an operation of the module is `wanted`: a rule whose state only an operation of
    that kind starts has nothing to find without one, and skips its walk of every routine (the
    editor server runs the rules on every keystroke)."""
    return any(wanted(op) for _, _, op in flow.ops(module))


def forward_all(module: ir.Module, transfer):
    """(routine, item, state before it) for every reachable operation, with the stream's state."""
    entries = flow.stream_entries(module, transfer, frozenset.union, subroutines=True)
    for routine in module.routines:
        states = flow.forward(routine, entries[routine.name], transfer, frozenset.union)
        for block in routine.blocks:
            if block.label in states:
                for item, state in flow.replay(block, states[block.label], transfer):
                    yield routine, item, state
