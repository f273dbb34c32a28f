"""Making the virtual device of a dialect (for `mcc device` and the tests)."""

from __future__ import annotations

from mcc.link.device.faults import Faults
from mcc.link.device.machine import RUN_LIMIT


def make_device(dialect: str, faults: Faults | None = None, addresses: tuple[str, ...] = ("1", "2", "3", "4"),
                program_lines: int = 1500, sequence_bytes: int = 8000, program: str | None = None,
                address: str = "00", party: tuple[str, ...] = (), run_limit: float = RUN_LIMIT,
                profile: str | None = None):
    if dialect == "mcode":
        from mcc.link.device.mcode import MCodeBus, MCodeDevice

        if party:
            return MCodeBus(party, faults, program_lines=program_lines, run_limit=run_limit, profile=profile)
        return MCodeDevice(faults, program_lines=program_lines, run_limit=run_limit, profile=profile)
    if dialect == "x150":
        from mcc.link.device.x150 import X150Device

        return X150Device(faults, addresses=addresses, capacity=sequence_bytes, run_limit=run_limit)
    from mcc.link.device.arcus import ArcusDevice

    device = ArcusDevice(faults, address=address, run_limit=run_limit)
    if program:
        with open(program, encoding="utf-8", errors="replace") as handle:
            device.load_program(handle.read(), program)
    return device
