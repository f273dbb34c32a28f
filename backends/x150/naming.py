"""What an X150 routine name says about where its code lives (the backend's side of the names).

The X150 frontend names the routines of an X150 program after their sequence and device: `SEQ5@2`
is sequence 5 stored on device 2 only, `immediate@3` a stretch of commands all sent to device 3
(docs/dialects/x150.md, "Routine names"). The name is the IR's routine-level device address: the
backend reads it here and writes the address in front of each command of such a routine. Routines
of other dialects carry no `@`: their commands go to the axes the operations name.
"""

from __future__ import annotations

import re

NAME = re.compile(r"(?P<base>[^@~]+)(?:@(?P<device>[0-9]+))?(?:~(?P<copy>[0-9]+))?\Z")


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
