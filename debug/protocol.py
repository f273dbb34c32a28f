"""The Debug Adapter Protocol's base protocol: messages framed by a `Content-Length` header.

No maintained Python library implements the adapter side of DAP for a custom debugger (debugpy
is Python's own debugger, not a framework), so the framing lives here, in one small module, as
pygls keeps it for the language server: a header block (`Content-Length: N`, CRLF line endings,
a blank line) and N bytes of UTF-8 JSON. Every message the adapter sends gets the next `seq`;
`send` may be called from the simulator's thread while the reader thread waits for requests.
"""

from __future__ import annotations

import json
import threading
from typing import Any, BinaryIO


MAX_MESSAGE = 64 * 1024 * 1024  # bytes: far above any request, a guard against a garbled header


class ProtocolError(Exception):
    """A message that does not follow the base protocol (a missing header, bad JSON)."""


class Connection:
    def __init__(self, reader: BinaryIO, writer: BinaryIO):
        self.reader = reader
        self.writer = writer
        self.seq = 0
        self.lock = threading.Lock()

    def read(self) -> dict[str, Any] | None:
        """The next message, or None at the end of the input."""
        length = None
        while True:
            line = self.reader.readline()
            if not line:
                return None
            line = line.strip()
            if not line:
                if length is None:
                    continue  # blank lines before a header: tolerated
                break
            name, _, value = line.decode("ascii", "replace").partition(":")
            if name.strip().lower() == "content-length":
                try:
                    length = int(value.strip())
                except ValueError:
                    raise ProtocolError(f"Content-Length is not a number: {value.strip()!r}") from None
        if length < 0 or length > MAX_MESSAGE:
            raise ProtocolError(f"Content-Length {length} is out of range")
        body = self.reader.read(length)
        if len(body) < length:
            return None
        try:
            message = json.loads(body.decode("utf-8"))
        except (UnicodeDecodeError, json.JSONDecodeError) as exc:
            raise ProtocolError(f"the message is not JSON: {exc}") from None
        if not isinstance(message, dict):
            raise ProtocolError("the message is not a JSON object")
        return message

    def send(self, message: dict[str, Any]) -> None:
        with self.lock:
            self.seq += 1
            message = {"seq": self.seq, **message}
            data = json.dumps(message, separators=(",", ":")).encode("utf-8")
            try:
                self.writer.write(b"Content-Length: %d\r\n\r\n" % len(data) + data)
                self.writer.flush()
            except (BrokenPipeError, OSError, ValueError):
                pass  # the client went away; the reader sees the end of input

    def respond(self, request: dict[str, Any], body: dict[str, Any] | None = None, *, success: bool = True,
                message: str | None = None) -> None:
        reply: dict[str, Any] = {"type": "response", "request_seq": request.get("seq", 0), "success": success,
                                 "command": request.get("command", "")}
        if message is not None:
            reply["message"] = message
        if body is not None:
            reply["body"] = body
        self.send(reply)

    def event(self, name: str, body: dict[str, Any] | None = None) -> None:
        message: dict[str, Any] = {"type": "event", "event": name}
        if body is not None:
            message["body"] = body
        self.send(message)
