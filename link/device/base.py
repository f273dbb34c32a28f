"""What every virtual device shares: splitting the byte stream into commands and the faults."""

from __future__ import annotations

import threading

from mcc.link.device.faults import Faults


class ConnectionDropped(Exception):
    """An injected fault: the device drops the connection."""


class VirtualDevice:
    """Subclasses implement `command(raw: str) -> bytes` (the whole reply to one command) and set
    `terminators`, the bytes that end a command."""

    terminators = b"\r"

    def __init__(self, faults: Faults | None = None) -> None:
        self.faults = faults or Faults()
        self.received = 0
        self.buffer = b""
        self.lock = threading.Lock()

    def feed(self, data: bytes) -> bytes:
        """Bytes from the host in, bytes to the host out."""
        out = b""
        with self.lock:
            self.buffer += data
            while True:
                ends = [i for i in (self.buffer.find(bytes([t])) for t in self.terminators) if i >= 0]
                if not ends:
                    break
                end = min(ends)
                raw, self.buffer = self.buffer[:end + 1], self.buffer[end + 1:]
                out += self.one(raw)
        return out

    def one(self, raw: bytes) -> bytes:
        self.received += 1
        n = self.received
        if self.faults.close == n:
            raise ConnectionDropped()
        if self.faults.garble == n and len(raw) > 2:
            middle = len(raw) // 2
            noisy = raw[middle] ^ 0x04
            if noisy < 0x20 or noisy > 0x7E:
                noisy = 0x23   # never a terminator or a control character: the line length stays the same
            raw = raw[:middle] + bytes([noisy]) + raw[middle + 1:]
        reply = self.command(raw)
        if self.faults.drop_reply == n:
            return b""
        return reply

    def command(self, raw: bytes) -> bytes:  # pragma: no cover - abstract
        raise NotImplementedError
