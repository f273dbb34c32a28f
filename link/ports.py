"""Opening a port (a pyserial URL) and reading replies against a deadline.

pyserial is imported here and only here, when a port is opened, so that mcc works without it and
says how to install it when a link command needs it.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field
from typing import Callable

from mcc.link.errors import LinkError
from mcc.link.settings import LinkSettings

INSTALL_HINT = ('the device link needs pyserial: install it with  pip install "mcc[link]"  '
                '(or  pip install pyserial)')


def serial_module():
    try:
        import serial  # noqa: PLC0415 - optional dependency, imported when needed
    except ImportError:
        raise LinkError(INSTALL_HINT) from None
    return serial


def open_port(url: str, settings: LinkSettings):
    """A pyserial port for `url` (/dev/ttyUSB0, COM3, socket://host:port, rfc2217://..., loop://)."""
    serial = serial_module()
    try:
        return serial.serial_for_url(url, baudrate=settings.baudrate, parity=settings.parity,
                                     bytesize=settings.bytesize, stopbits=settings.stopbits,
                                     timeout=min(settings.timeout, 0.05), write_timeout=settings.timeout)
    except (serial.SerialException, ValueError, OSError) as exc:
        raise LinkError(f"cannot open port {url}: {exc}",
                        "nothing was sent: the device is as it was") from None


@dataclass
class Exchange:
    """One direction of traffic, for the transcript (`--format json`, `mcc send -v`)."""

    direction: str  # "send" | "recv"
    data: bytes
    at: float


@dataclass
class Channel:
    """A port with a transcript and reads that end when a reply is complete or a deadline passes."""

    port: object
    settings: LinkSettings
    transcript: list[Exchange] = field(default_factory=list)
    pending: bytes = b""

    def send(self, data: bytes) -> None:
        serial = serial_module()
        self.transcript.append(Exchange("send", data, time.monotonic()))
        try:
            self.port.write(data)
            self.port.flush()
        except (serial.SerialException, OSError) as exc:
            raise LinkError(f"the port closed while sending: {exc}") from None

    def read_until(self, complete: Callable[[bytes], int], timeout: float | None = None) -> tuple[bytes, bool]:
        """Read until `complete(buffer)` returns the length of a complete reply (0: not yet).

        Returns (reply, True), keeping any bytes after the reply for the next read, or
        (everything received, False) when `timeout` seconds pass first.
        """
        serial = serial_module()
        deadline = time.monotonic() + (self.settings.timeout if timeout is None else timeout)
        buffer = self.pending
        self.pending = b""
        while True:
            end = complete(buffer)
            if end:
                self.pending = buffer[end:]
                reply = buffer[:end]
                self.transcript.append(Exchange("recv", reply, time.monotonic()))
                return reply, True
            if time.monotonic() >= deadline:
                if buffer:
                    self.transcript.append(Exchange("recv", buffer, time.monotonic()))
                return buffer, False
            try:
                chunk = self.port.read(max(1, getattr(self.port, "in_waiting", 0) or 1))
            except (serial.SerialException, OSError) as exc:
                if buffer:
                    self.transcript.append(Exchange("recv", buffer, time.monotonic()))
                raise LinkError(f"the port closed while waiting for a reply: {exc}") from None
            buffer += chunk

    def discard_input(self, quiet: float = 0.05) -> bytes:
        """Read and drop whatever arrives until the line is quiet for `quiet` seconds."""
        dropped, _ = self.read_until(lambda _buf: 0, quiet)
        return dropped

    def close(self) -> None:
        try:
            self.port.close()
        except Exception:  # noqa: BLE001 - closing a broken port must not hide the real error
            pass


def transcript_text(transcript: list[Exchange]) -> list[dict]:
    """The transcript as JSON-friendly rows (bytes shown with escapes)."""
    start = transcript[0].at if transcript else 0.0
    return [{"dir": e.direction, "data": e.data.decode("latin-1"), "t": round(e.at - start, 4)}
            for e in transcript]
