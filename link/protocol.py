"""What every dialect's host protocol provides, and the types the download and upload share.

A dialect module (link/mcode.py, link/x150.py, link/arcus.py) frames commands, reads replies,
turns a compiled listing into a plan of steps, and reads back what the device holds. The order of
a download (send, verify, then save and run) lives in link/download.py, once for all dialects.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from mcc.compiler.span import Span


@dataclass
class Reply:
    """One command's answer, decoded."""

    command: str
    ok: bool
    lines: list[str] = field(default_factory=list)  # data the device printed
    error: str = ""        # the device's error code or text ("" when ok)
    meaning: str = ""      # the error in words
    raw: bytes = b""


@dataclass
class Step:
    """One command of a download with the source lines it came from.

    kind: "clear" (empties memory before the download), "send" (configuration or stored
    program text), "save" (held back until verified; sent with --save), "run" (held back until
    verified; sent with --run), "verify" (a read-back).
    """

    command: str
    kind: str = "send"
    sources: tuple[Span, ...] = ()
    stored: bool = False   # the command is stored in program memory (not executed)
    line: int = 0          # 1-based line of the listing

    def to_json(self) -> dict:
        return {"command": self.command, "kind": self.kind, "listing_line": self.line,
                "sources": sorted({f"{s.file}:{s.line}" for s in self.sources})}


@dataclass
class Mismatch:
    """A difference between what was sent and what the device holds."""

    where: str
    expected: str
    found: str


class DeviceError(Exception):
    """The device refused a command (an error reply), with its decoded meaning."""

    def __init__(self, reply: Reply) -> None:
        super().__init__(f"{reply.command}: error {reply.error} {reply.meaning}".strip())
        self.reply = reply


class LostReply(Exception):
    """No complete reply arrived in time, or it did not match what was sent (garbled)."""

    def __init__(self, command: str, received: bytes, garbled: bool = False) -> None:
        kind = "garbled" if garbled else "lost"
        super().__init__(f"{command}: reply {kind} (received {received!r})")
        self.command = command
        self.received = received
        self.garbled = garbled


def normalize(text: str) -> str:
    """A stored line as devices list it back: case and runs of blanks do not matter."""
    return " ".join(text.upper().split())


def echo_at(raw: bytes, echo: bytes) -> int:
    """Where the echo of the command just sent starts in what the device sent back: 0, or after
    whole lines a running program printed before it (a drive transmits a program's output as it
    runs, lexium-mcode.txt L4895; an X150 sequence's messages, parker-x150.md L5593); -1 when the
    echo is not there (the line was garbled on the way)."""
    if raw.startswith(echo):
        return 0
    at = raw.find(echo)
    while at > 0:
        if raw[at - 1:at] in (b"\r", b"\n"):
            return at
        at = raw.find(echo, at + 1)
    return -1
