"""A virtual X150/X150E chain: the devices at the given addresses behind one RS-232C port.

State per device (manual L4860-L5447, L3064, L1433): the sequences 1-64 and the 8,000 bytes they
share (XBS), the definition in progress (XD ... XT) and the last download status (XSD), what SV
saved, the upload password (PASS), the communication style EX (terminal/computer), echo (SSA),
the variables VAR1-VAR50, the last run status (XSR) and the status bits R reports. Commands are
echoed (SSA0) and, in terminal mode, answered with the prompt `>`. Running a sequence goes through
the execution seam (device/execute.py).
"""

from __future__ import annotations

import copy
import re
from dataclasses import dataclass, field
from functools import lru_cache

from mcc.compiler import catalog
from mcc.link.device import execute
from mcc.link.device.base import VirtualDevice
from mcc.link.device.faults import Faults
from mcc.link.device.programs import module_of

SEQUENCE_BYTES = 8000   # L4871


@lru_cache(maxsize=None)
def mnemonics() -> tuple[str, ...]:
    words = {e.name for e in catalog.load("x150").entries if re.fullmatch(r"[A-Z]+", e.name)}
    return tuple(sorted(words, key=len, reverse=True))


def parse(command: str) -> tuple[str, str, str]:
    """(address, mnemonic, argument): the longest catalog mnemonic at the start wins."""
    match = re.match(r"^(\d*)(.*)$", command, re.S)
    address, rest = match.group(1), match.group(2)
    if rest[:1] in ('"', "#", ";"):
        return address, rest[:1], rest[1:]
    for word in mnemonics():
        if rest.startswith(word):
            return address, word, rest[len(word):]
    return address, "", rest


@dataclass
class Unit:
    """One X150 on the chain."""

    address: str
    sequences: dict[int, list[str]] = field(default_factory=dict)
    password: str = "0000"
    locked: bool = False
    terminal: bool = True
    echo: bool = True
    variables: dict[int, float] = field(default_factory=dict)
    xsd: str = "0"
    xsr: str = "0"
    defining: int | None = None
    buffer: list[str] = field(default_factory=list)
    refused: str = ""        # why the definition in progress will not be stored
    saved: dict = field(default_factory=dict)
    running: bool = False

    def used(self) -> int:
        return sum(len(c) + 1 for body in self.sequences.values() for c in body)


class X150Device(VirtualDevice):
    terminators = b"\r"

    def __init__(self, faults: Faults | None = None, addresses: tuple[str, ...] = ("1", "2", "3", "4"),
                 capacity: int = SEQUENCE_BYTES) -> None:
        super().__init__(faults)
        self.units = {a: Unit(a) for a in addresses}
        self.capacity = capacity
        for unit in self.units.values():
            unit.saved = self.snapshot(unit)

    @staticmethod
    def snapshot(unit: Unit) -> dict:
        return copy.deepcopy({"sequences": unit.sequences, "password": unit.password, "variables": unit.variables})

    def command(self, raw: bytes) -> bytes:
        text = raw.rstrip(b"\r\n").decode("latin-1").strip()
        address, word, arg = parse(text)
        targets = [self.units[address]] if address in self.units else ([] if address else list(self.units.values()))
        if not targets:
            return raw if self.echo_on() else b""   # for a device not on this chain: passed along
        out: list[str] = []
        for unit in targets:
            out += self.execute(unit, text, word, arg.strip())
        first = targets[0]
        reply = (raw if first.echo else b"") + "".join(line + "\r" for line in out).encode("latin-1")
        return reply + (b">" if first.terminal else b"")

    def echo_on(self) -> bool:
        return any(u.echo for u in self.units.values())

    def execute(self, unit: Unit, text: str, word: str, arg: str) -> list[str]:
        if unit.defining is not None and word not in ("XT", "S", "STOP"):
            body = re.sub(r"\s+;.*$", "", text)
            if word == ";" or not body:
                return []   # comments are not stored (L5534)
            if not word:
                unit.refused = unit.refused or "unknown command"
            unit.buffer.append(body)
            return []
        handler = getattr(self, f"do_{word}", None)
        if handler is not None:
            return handler(unit, arg)
        if word == "VAR":
            return self.var(unit, arg)
        return []   # other commands: accepted (motion and I/O are the simulator's work)

    # -- sequences ---------------------------------------------------------------------------
    def do_XD(self, unit: Unit, arg: str) -> list[str]:
        unit.defining = int(arg) if arg.isdigit() else 0
        unit.buffer, unit.refused = [], ""
        if unit.defining in unit.sequences:
            unit.refused = "1"
        return []

    def do_XT(self, unit: Unit, arg: str) -> list[str]:
        if unit.defining is None:
            return []
        number, body = unit.defining, unit.buffer
        unit.defining, unit.buffer = None, []
        size = sum(len(c) + 1 for c in body)
        if unit.refused == "1":
            unit.xsd = "1"
        elif unit.used() + size > self.capacity:
            unit.xsd = "2"
        elif unit.refused or not 1 <= number <= 64:
            unit.xsd = "0"  # not stored; the manual gives XSD no code for it: XSS reports it
        else:
            unit.sequences[number] = body
            unit.xsd = "0"
        return []

    def do_S(self, unit: Unit, arg: str) -> list[str]:
        unit.defining, unit.buffer = None, []   # S aborts a download in progress (L3661)
        unit.running = False
        return []

    do_STOP = do_S

    def do_XE(self, unit: Unit, arg: str) -> list[str]:
        if arg.isdigit():
            unit.sequences.pop(int(arg), None)
        return []

    def do_XEALL(self, unit: Unit, arg: str) -> list[str]:
        unit.sequences.clear()
        return []

    def do_XSD(self, unit: Unit, arg: str) -> list[str]:
        return [unit.xsd] + ([";download OK"] if unit.xsd == "0" and unit.terminal else [])

    def do_XSS(self, unit: Unit, arg: str) -> list[str]:
        return ["2" if arg.isdigit() and int(arg) in unit.sequences else "0"]

    def do_XSR(self, unit: Unit, arg: str) -> list[str]:
        return [unit.xsr]

    def do_XBS(self, unit: Unit, arg: str) -> list[str]:
        return [f"*{self.capacity - unit.used()} bytes free"]

    def do_XU(self, unit: Unit, arg: str) -> list[str]:
        if unit.locked:
            return []
        numbers = [int(arg)] if arg.isdigit() else sorted(unit.sequences)
        out = []
        for n in numbers:
            if n in unit.sequences:
                out += [f"XD{n}", *unit.sequences[n], "XT"]
        return out

    def do_PASS(self, unit: Unit, arg: str) -> list[str]:
        if not re.fullmatch(r"\d{4}", arg):
            return []
        if unit.password == "0000":
            unit.password, unit.locked = arg, arg != "0000"
        elif arg == unit.password:
            unit.locked = not unit.locked
        elif arg == "0000" and not unit.locked:
            unit.password = "0000"
        return []

    def do_SV(self, unit: Unit, arg: str) -> list[str]:
        unit.saved = self.snapshot(unit)
        return []

    def do_EX(self, unit: Unit, arg: str) -> list[str]:
        unit.terminal = arg != "0"
        return []

    def do_SSA(self, unit: Unit, arg: str) -> list[str]:
        unit.echo = arg != "1"
        return []

    def do_R(self, unit: Unit, arg: str) -> list[str]:
        function_error = unit.xsr == "2"
        return [("*B" if unit.running else "*R") if not function_error else ("*C" if unit.running else "*S")]

    def var(self, unit: Unit, arg: str) -> list[str]:
        match = re.fullmatch(r"(\d+)(?:=(-?\d+(?:\.\d+)?))?", arg.replace(" ", ""))
        if not match or not 1 <= int(match.group(1)) <= 50:
            return []
        n = int(match.group(1))
        if match.group(2) is None:
            return [f"* {unit.variables.get(n, 0.0):.4f}"]
        unit.variables[n] = float(match.group(2))
        return []

    # -- the execution seam ------------------------------------------------------------------
    def do_XR(self, unit: Unit, arg: str) -> list[str]:
        if not arg.isdigit() or int(arg) not in unit.sequences:
            unit.xsr = "2"
            return []
        unit.xsr = "0"
        text = "\n".join(f"{unit.address}XD{n}\n" + "\n".join(body) + f"\n{unit.address}XT"
                         for n, body in sorted(unit.sequences.items()))
        module = module_of("x150", text + "\n")
        if module is None:
            return []
        values = {f"VAR{k}": v for k, v in unit.variables.items()}
        outcome = execute.run_program(module, values, int(arg))
        for name, value in outcome.variables.items():
            if name.startswith("VAR") and name[3:].isdigit():
                unit.variables[int(name[3:])] = value
        unit.running = outcome.status == "running"
        return []

    do_XG = do_GOSUB = do_GOTO = do_XR
