"""Faults a virtual device can be told to inject, counted in commands received (1-based)."""

from __future__ import annotations

from dataclasses import dataclass


@dataclass
class Faults:
    drop_reply: int = 0    # the device executes command n but its reply is lost
    garble: int = 0        # command n arrives with one character changed (line noise)
    close: int = 0         # the connection drops when command n arrives (before it is executed)

    @classmethod
    def parse(cls, spec: str) -> "Faults":
        """`drop_reply=3,garble=7` (the --fault option of `mcc device`)."""
        faults = cls()
        for part in filter(None, (p.strip() for p in spec.split(","))):
            name, _, value = part.partition("=")
            name = name.strip().replace("-", "_")
            if name not in cls.__dataclass_fields__ or not value.strip().isdigit():
                raise ValueError(f"unknown fault {part!r}: use drop_reply=N, garble=N or close=N")
            setattr(faults, name, int(value))
        return faults
