"""Routine names of X150 programs in the IR, shared by the frontend, the checks and the backend.

X150 has no labels: the unit of code is the sequence 1-64 (XDn ... XT), stored per device. A
routine's name says which sequence and which device:

- ``SEQ5``     sequence 5 defined without an address (every device in the chain stores it);
- ``SEQ5@2``   sequence 5 defined with `2XD5` (only device 2 stores it);
- ``SEQ5~2``   a second definition of the same sequence in one file (X132);
- ``immediate``, ``immediate.2``: the stretches of commands sent outside any sequence, in stream
  order; ``immediate@3`` when every command of the stretch is addressed to device 3.

A routine whose name carries ``@a`` holds commands for device `a` only: the backend writes `a` in
front of each of them. Everything else keeps its own address on its operations (the axis).
"""

from __future__ import annotations

import re

NAME = re.compile(r"(?P<base>[^@~]+)(?:@(?P<device>[0-9]+))?(?:~(?P<copy>[0-9]+))?\Z")


def sequence_name(number: int, device: int | None, copy: int = 1) -> str:
    name = f"SEQ{number}"
    if device is not None:
        name += f"@{device}"
    if copy > 1:
        name += f"~{copy}"
    return name


def immediate_name(index: int, device: int | None) -> str:
    name = "immediate" if index == 1 else f"immediate.{index}"
    return name + (f"@{device}" if device is not None else "")


def device_of(name: str) -> int | None:
    """The device address a routine's commands are for (None: as written on each operation)."""
    match = NAME.match(name)
    if match is None or match.group("device") is None:
        return None
    return int(match.group("device"))


def sequence_number(name: str) -> int | None:
    match = NAME.match(name)
    if match is None:
        return None
    base = match.group("base")
    if base.startswith("SEQ") and base[3:].isdigit():
        return int(base[3:])
    return None


def candidates(number: int, device: int | None) -> tuple[str, ...]:
    """Routine names a command `[device]XRn` may run, best first.

    A call addressed to device a runs a's own sequence n, or the one every device stored; an
    unaddressed call runs sequence n wherever it is stored (the broadcast definition first).
    """
    if device is not None:
        return (sequence_name(number, device), sequence_name(number, None))
    return (sequence_name(number, None),)
