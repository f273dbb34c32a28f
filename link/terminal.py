"""`mcc terminal`: a line terminal that knows the dialect (history, replies in words)."""

from __future__ import annotations

import os
import re
import sys

from mcc.link.protocol import LostReply

HISTORY = os.path.join(os.path.expanduser("~"), ".mcc_terminal_history")


def explain(dialect: str, code: str) -> str:
    """A device error number in words, or an mcc diagnostic code's page (`mcc explain`)."""
    if re.fullmatch(r"[A-Za-z]\d{3}", code):
        from mcc.compiler.codes import registry

        info = registry().get(code.upper())
        return info.page() if info is not None else f"unknown code {code} (see mcc explain --list)"
    from mcc.link import protocols

    return protocols.module(dialect).explain_code(code)


class Terminal:
    def __init__(self, proto, dialect: str, read=input, write=print) -> None:
        self.proto = proto
        self.dialect = dialect
        self.read = read
        self.write = write

    def loop(self) -> None:
        readline = None
        if self.read is input and sys.stdin.isatty():
            try:
                import readline  # noqa: PLC0415 - history when the platform has it
                readline.read_history_file(HISTORY)
            except (ImportError, OSError):
                pass
        self.write(f"mcc terminal ({self.dialect}); :explain CODE, :status, :quit")
        try:
            while True:
                try:
                    line = self.read(f"{self.dialect}> ")
                except EOFError:
                    break
                if not self.handle(line.strip()):
                    break
        finally:
            if readline is not None:
                try:
                    readline.write_history_file(HISTORY)
                except OSError:
                    pass

    def handle(self, line: str) -> bool:
        from mcc.link.protocols import describe

        if not line:
            return True
        if line in (":quit", ":q", ":exit"):
            return False
        if line.startswith(":explain"):
            self.write(explain(self.dialect, line.split(maxsplit=1)[1].strip() if " " in line else ""))
            return True
        if line == ":status":
            self.write(", ".join(f"{k} {v}" for k, v in self.proto.status().items()))
            return True
        try:
            reply = self.proto.transact(line)
        except LostReply as exc:
            self.write(f"no reply: {exc}")
            return True
        self.write(describe(self.dialect, reply))
        return True
