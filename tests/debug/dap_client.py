"""A tiny Debug Adapter Protocol client for the tests: runs `mcc debug` over pipes (or connects
to its TCP port), sends requests and collects responses and events (a reader thread)."""

from __future__ import annotations

import json
import queue
import subprocess
import sys
import threading

TIMEOUT = 30.0


class Client:
    def __init__(self, reader, writer, process: subprocess.Popen | None = None):
        self.reader, self.writer, self.process = reader, writer, process
        self.seq = 0
        self.responses: dict[int, dict] = {}
        self.events: list[dict] = []
        self.stop_cursor = 0
        self.inbox: queue.Queue = queue.Queue()
        self.thread = threading.Thread(target=self._read, daemon=True)
        self.thread.start()

    @classmethod
    def stdio(cls) -> "Client":
        process = subprocess.Popen([sys.executable, "-m", "mcc", "debug"], stdin=subprocess.PIPE,
                                   stdout=subprocess.PIPE, stderr=subprocess.PIPE)
        return cls(process.stdout, process.stdin, process)

    def _read(self) -> None:
        while True:
            length = None
            while True:
                line = self.reader.readline()
                if not line:
                    self.inbox.put(None)
                    return
                line = line.strip()
                if not line:
                    break
                name, _, value = line.decode().partition(":")
                if name.lower() == "content-length":
                    length = int(value)
            self.inbox.put(json.loads(self.reader.read(length)))

    def send_raw(self, data: bytes) -> None:
        self.writer.write(data)
        self.writer.flush()

    def send(self, command: str, arguments: dict | None = None) -> int:
        self.seq += 1
        message = {"seq": self.seq, "type": "request", "command": command}
        if arguments is not None:
            message["arguments"] = arguments
        data = json.dumps(message).encode()
        self.send_raw(b"Content-Length: %d\r\n\r\n" % len(data) + data)
        return self.seq

    def _pump(self) -> dict:
        message = self.inbox.get(timeout=TIMEOUT)
        if message is None:
            raise EOFError("the adapter closed the connection")
        if message["type"] == "response":
            self.responses[message["request_seq"]] = message
        else:
            self.events.append(message)
        return message

    def request(self, command: str, arguments: dict | None = None) -> dict:
        seq = self.send(command, arguments)
        while seq not in self.responses:
            self._pump()
        return self.responses[seq]

    def ok(self, command: str, arguments: dict | None = None) -> dict:
        response = self.request(command, arguments)
        assert response["success"], response
        assert response["command"] == command
        return response.get("body") or {}

    def event(self, name: str, after: int = 0) -> dict:
        """The first event `name` at or after index `after` of `events` (waiting for it)."""
        while True:
            for event in self.events[after:]:
                if event["event"] == name:
                    return event
            self._pump()

    def next_stop(self) -> dict:
        """The next stopped (or terminated) event after the last one this returned (waiting for it)."""
        while True:
            for n in range(self.stop_cursor, len(self.events)):
                if self.events[n]["event"] in ("stopped", "terminated"):
                    self.stop_cursor = n + 1
                    return self.events[n]
            self._pump()

    def outputs(self, category: str | None = None) -> str:
        return "".join(e["body"]["output"] for e in self.events
                       if e["event"] == "output" and (category is None or e["body"]["category"] == category))

    def close(self) -> None:
        if self.process is not None:
            try:
                self.process.stdin.close()
            except OSError:
                pass
            try:
                self.process.wait(timeout=10)
            except subprocess.TimeoutExpired:
                self.process.kill()
                self.process.wait()
