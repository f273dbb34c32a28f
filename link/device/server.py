"""Serve a virtual device on a TCP port, one host connection at a time, the state kept between
connections as a real controller keeps it while the cable is unplugged.

Time runs on while the host is silent (docs/LINK.md, "Virtual time"): before the device reads
what arrived, it lets the wall time since it last heard from or answered the host pass, times
`time_scale` (1: real time; 0: only the commands' own time passes, for reproducible runs; more than
1: a test that waits a short while sees a long program end)."""

from __future__ import annotations

import socket
import sys
import threading
import time
import traceback

from mcc.link.device.base import ConnectionDropped, VirtualDevice


class DeviceServer:
    def __init__(self, device: VirtualDevice, host: str = "127.0.0.1", port: int = 0,
                 time_scale: float = 1.0) -> None:
        self.device = device
        self.time_scale = time_scale
        self.heard = time.monotonic()   # when the host last sent something or was last answered
        self.sock = socket.create_server((host, port))
        self.sock.settimeout(0.2)
        self.host, self.port = self.sock.getsockname()[:2]
        self.stopping = threading.Event()
        self.thread: threading.Thread | None = None

    @property
    def url(self) -> str:
        return f"socket://{self.host}:{self.port}"

    def serve_forever(self) -> None:
        while not self.stopping.is_set():
            try:
                conn, _addr = self.sock.accept()
            except (socket.timeout, OSError):
                continue
            with conn:
                self.handle(conn)

    def handle(self, conn: socket.socket) -> None:
        conn.settimeout(0.2)
        while not self.stopping.is_set():
            try:
                data = conn.recv(4096)
            except socket.timeout:
                continue
            except OSError:
                return
            if not data:
                return
            now = time.monotonic()
            if self.time_scale > 0:
                self.device.elapse((now - self.heard) * self.time_scale)   # the host was silent that long
            try:
                reply = self.device.feed(data)
            except ConnectionDropped:
                self.device.buffer = b""
                return
            except Exception as exc:  # noqa: BLE001 - a bug in a virtual device must not kill the server
                frames = traceback.extract_tb(exc.__traceback__)
                where = f" at {frames[-1].filename.rsplit('/', 1)[-1]}:{frames[-1].lineno}" if frames else ""
                print(f"virtual device: internal error {type(exc).__name__}: {exc}{where}; the connection was "
                      "closed. This is a bug in mcc; please report it with the commands sent.", file=sys.stderr)
                self.device.buffer = b""
                return
            if reply:
                try:
                    conn.sendall(reply)
                except OSError:
                    return
            self.heard = time.monotonic()

    def start(self) -> "DeviceServer":
        self.thread = threading.Thread(target=self.serve_forever, daemon=True)
        self.thread.start()
        return self

    def stop(self) -> None:
        self.stopping.set()
        if self.thread is not None:
            self.thread.join(2)
        self.sock.close()

    def __enter__(self) -> "DeviceServer":
        return self.start()

    def __exit__(self, *exc) -> None:
        self.stop()
