"""Making the virtual device of a dialect (for `mcc device` and the tests).

The device is the dialect's own (`Dialect.device`, compiler/<dialect>/dialect.py): its module's
`make(faults, options)` builds it from the options below, taking those that apply to it.
"""

from __future__ import annotations

from dataclasses import dataclass

from mcc.compiler import dialects
from mcc.link.device.faults import Faults
from mcc.link.device.machine import RUN_LIMIT


@dataclass(frozen=True)
class DeviceOptions:
    """What `mcc device` may ask of a virtual device; each dialect's device takes what it has
    (addresses and a sequence store on a multi-drop bus, a party of named devices, a program image
    loaded at start, the product profile whose identity it reports)."""

    addresses: tuple[str, ...] = ("1", "2", "3", "4")
    program_lines: int = 1500
    sequence_bytes: int = 8000
    program: str | None = None
    address: str = "00"
    party: tuple[str, ...] = ()
    run_limit: float = RUN_LIMIT
    profile: str | None = None


def make_device(dialect: str, faults: Faults | None = None, addresses: tuple[str, ...] = ("1", "2", "3", "4"),
                program_lines: int = 1500, sequence_bytes: int = 8000, program: str | None = None,
                address: str = "00", party: tuple[str, ...] = (), run_limit: float = RUN_LIMIT,
                profile: str | None = None):
    options = DeviceOptions(addresses, program_lines, sequence_bytes, program, address, party, run_limit, profile)
    return dialects.get(dialect).load_device().make(faults, options)
