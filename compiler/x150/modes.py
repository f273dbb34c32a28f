"""Modal state (MPA/MPI, MN/MC/MQ) followed per device in source order.

The lowering gives each Move the position mode in force before it, and the writer follows the
same state while writing to decide when a Move from another dialect needs an MPA or MPI first.
Both use these two functions, so a program's Moves and its mode commands always agree.
A mode set without an address ("*") applies to every device and replaces per-device settings.
"""

from __future__ import annotations

from mcc.compiler.ir import ALL_AXES


def set_mode(table: dict, axis: str, value) -> None:
    if axis == ALL_AXES:
        table.clear()
    table[axis] = value


def get_mode(table: dict, axis: str):
    return table.get(axis, table.get(ALL_AXES))
