"""What every virtual device shares: splitting the byte stream into commands, the time each command
takes on the line and in the device, and the faults."""

from __future__ import annotations

import threading

from mcc.link.device.faults import Faults


class ConnectionDropped(Exception):
    """An injected fault: the device drops the connection."""


class VirtualDevice:
    """Subclasses implement `command(raw: str) -> bytes` (the whole reply to one command), set
    `terminators`, the bytes that end a command, and keep their machine in `self.sim` (a
    link.device.machine.DeviceMachine; a bus of drives overrides `machines`).

    Virtual time (docs/LINK.md, "Virtual time"): a command's characters cross the line at the
    link's baud rate, the device takes its execution time, then answers, and the reply's
    characters cross the line; the runs on the machine go on meanwhile. What they print while the
    host is silent reaches the host before the next reply (`unsolicited`)."""

    terminators = b"\r"

    def __init__(self, faults: Faults | None = None) -> None:
        self.faults = faults or Faults()
        self.received = 0
        self.buffer = b""
        self.lock = threading.Lock()
        self.synced = 0   # the machine's `generation` the protocol state was last brought up to date with

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

    def machines(self) -> list:
        """The machines behind this port (one; a bus has one per drive): they share the time."""
        return [self.sim]

    def elapse(self, seconds: float) -> None:
        """The host waits `seconds` (a sleep, a reader's timeout): the devices run on meanwhile."""
        with self.lock:
            for machine in self.machines():
                machine.elapse(seconds)

    def synchronise(self) -> None:
        """Bring the state the protocol keeps up to date with what the running program changed
        (its variables): called before each command, after the time it took has passed."""

    def unsolicited(self, lines: list[str]) -> bytes:
        """What a program printed while the host was silent, as the device transmits it."""
        return "".join(line + "\r" for line in lines).encode("latin-1")

    def one(self, raw: bytes) -> bytes:
        machines = self.machines()
        for machine in machines:
            machine.transmit(len(raw))   # the command arrives
            machine.execute()            # the device's command execution time (L6821)
        early = self.unsolicited([line for m in machines for text in m.take_output() for line in text.splitlines()])
        self.synchronise()
        reply = self.answer(raw)
        late = self.unsolicited([line for m in machines for text in m.take_output() for line in text.splitlines()])
        out = early + reply + late
        for machine in machines:
            machine.transmit(len(out))   # the reply goes back
        return out

    def answer(self, raw: bytes) -> bytes:
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
