"""Serial settings, timeouts and retries of a link: from the profile's `[link]` table, then the
command line. One dataclass, so that every setting has one documented default (docs/LINK.md)."""

from __future__ import annotations

from dataclasses import dataclass, fields, replace

PARITIES = {"N": "none", "E": "even", "O": "odd", "M": "mark", "S": "space"}
LINE_ENDINGS = {"cr": "\r", "lf": "\n", "crlf": "\r\n"}


@dataclass(frozen=True)
class LinkSettings:
    baudrate: int = 9600
    parity: str = "N"
    bytesize: int = 8
    stopbits: float = 1
    line_ending: str = "cr"      # what mcc sends after a command: cr | lf | crlf
    address: str = ""            # MCode party name (DN), X150 device address, Arcus device number
    timeout: float = 2.0         # seconds to wait for the end of one reply
    retries: int = 2             # resends of a command whose reply was lost, garbled or NAKed
    echo: int = 0                # MCode EM the device is in (0 echo + prompt, 1 no echo, 2 no prompt)
    checksum: int = 0            # MCode CK the device is in (0 off, 1 ACK/NAK, 2 NAK only)
    party: bool = False          # MCode PY=1: every command prefixed with the address, LF-terminated
    pace: float = 0.0            # seconds to wait between commands (MCode manual L1581)

    @property
    def terminator(self) -> str:
        return LINE_ENDINGS[self.line_ending]

    def check(self) -> None:
        """Raise ValueError for a setting no port accepts."""
        if self.parity not in PARITIES:
            raise ValueError(f"parity must be one of {', '.join(PARITIES)}, not {self.parity!r}")
        if self.line_ending not in LINE_ENDINGS:
            raise ValueError(f"line_ending must be one of {', '.join(LINE_ENDINGS)}, not {self.line_ending!r}")
        if self.bytesize not in (5, 6, 7, 8):
            raise ValueError(f"bytesize must be 5-8, not {self.bytesize}")
        if self.stopbits not in (1, 1.5, 2):
            raise ValueError(f"stopbits must be 1, 1.5 or 2, not {self.stopbits}")
        if self.timeout <= 0:
            raise ValueError("timeout must be more than 0 seconds")
        if self.retries < 0:
            raise ValueError("retries cannot be negative")
        if self.echo not in (0, 1, 2, 3) or self.checksum not in (0, 1, 2):
            raise ValueError("echo must be 0-3 and checksum 0-2 (MCode EM and CK)")


KNOWN_KEYS = {f.name for f in fields(LinkSettings)}


def from_profile(profile, overrides: dict | None = None) -> LinkSettings:
    """The profile's `[link]` table, then the non-None `overrides` (command-line options)."""
    table = dict(profile.get("link", {}) or {}) if profile is not None else {}
    unknown = set(table) - KNOWN_KEYS
    if unknown:
        raise ValueError(f"profile {profile.name}: unknown [link] keys {', '.join(sorted(unknown))} "
                         f"(known: {', '.join(sorted(KNOWN_KEYS))})")
    settings = LinkSettings(**{k: (str(v) if k in ("address", "parity", "line_ending") else v)
                               for k, v in table.items()})
    chosen = {k: v for k, v in (overrides or {}).items() if v is not None}
    settings = replace(settings, **chosen)
    settings.check()
    return settings
