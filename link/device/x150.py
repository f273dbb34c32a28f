"""A virtual X150/X150E chain: the devices at the given addresses behind one RS-232C port.

State per device (manual L4860-L5447, L3064, L1433): the sequences 1-64 and the 8,000 bytes they
share (XBS), the definition in progress (XD ... XT) and the last download status (XSD), what SV
saved, the upload password (PASS), the communication style EX (terminal/computer), echo (SSA),
the variables VAR1-VAR50, the last run status (XSR) and the status bits R reports. Commands are
echoed (SSA0) and, in terminal mode, answered with the prompt `>`. Every other command (a move,
a setting, an output) and every sequence run (XR, XG, GOSUB, GOTO) runs on the simulator's
machine (device/machine.py), shared by the devices of the chain (one axis per address); R and
PR read it.
"""

from __future__ import annotations

import copy
import re
from dataclasses import dataclass, field
from functools import lru_cache
from typing import TYPE_CHECKING

from mcc.compiler import catalog
from mcc.link.device.base import VirtualDevice
from mcc.link.device.faults import Faults
from mcc.link.device.machine import RUN_LIMIT, DeviceMachine
from mcc.link.device.programs import module_of

if TYPE_CHECKING:
    from mcc.link.device.virtual import DeviceOptions

SEQUENCE_BYTES = 8000   # L4871
# Commands whose effect mcc's frontend resolves where the program is compiled (the distance D and
# the move modes that G uses, L1433): a device remembers the last of each group per address and
# compiles each later command after them, so `1D4000` then `1G` moves 4000 steps.
CONTEXT = {"D": "D", "MPA": "MP", "MPI": "MP", "MN": "MODE", "MC": "MODE", "MQ": "MODE", "V": "V", "A": "A",
           "AA": "AA", "AD": "AD"}
RUNS = ("XR", "XG", "GOSUB", "GOTO", "XRP")


@lru_cache(maxsize=None)
def mnemonics() -> tuple[str, ...]:
    words = {e.name for e in catalog.load("x150").entries if re.fullmatch(r"[A-Z]+", e.name)}
    return tuple(sorted(words, key=len, reverse=True))


@lru_cache(maxsize=None)
def buffered(word: str) -> bool:
    """A buffered command (the catalog's `exec = "B"`): it waits for the sequence running to end
    ("stored in the command buffer and executed in sequential order", L177); an immediate one runs
    at once."""
    return any(e.name == word and e.get("exec") == "B" for e in catalog.load("x150").entries)


@lru_cache(maxsize=None)
def device_specific() -> frozenset[str]:
    """Commands that "require a device address for execution" (L181: every report among them)."""
    return frozenset(e.name for e in catalog.load("x150").entries if e.get("address") == "D")


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
    context: dict[str, str] = field(default_factory=dict)   # CONTEXT group -> the command last sent

    def used(self) -> int:
        return sum(len(c) + 1 for body in self.sequences.values() for c in body)


class X150Device(VirtualDevice):
    terminators = b"\r"

    def __init__(self, faults: Faults | None = None, addresses: tuple[str, ...] = ("1", "2", "3", "4"),
                 capacity: int = SEQUENCE_BYTES, run_limit: float = RUN_LIMIT) -> None:
        super().__init__(faults)
        self.units = {a: Unit(a) for a in addresses}
        self.capacity = capacity
        self.sim = DeviceMachine("x150", run_limit)
        self.stepping: dict[str, Stepping] = {}   # address -> its sequence in single-step mode
        self.running = ""                          # the address whose sequence is the device's program
        for unit in self.units.values():
            unit.saved = self.snapshot(unit)

    @staticmethod
    def snapshot(unit: Unit) -> dict:
        return copy.deepcopy({"sequences": unit.sequences, "password": unit.password, "variables": unit.variables})

    def command(self, raw: bytes) -> bytes:
        text = raw.rstrip(b"\r\n").decode("latin-1").strip()
        address, word, arg = parse(text)
        targets = [self.units[address]] if address in self.units else ([] if address else list(self.units.values()))
        if not address and word in device_specific() and not any(u.defining is not None for u in targets):
            # L181: a device specific command (XU, XSD, R, PR, SV ...) needs an address; without
            # one no device executes it (so several devices never answer at once): echo, prompt
            first = targets[0]
            return (raw if first.echo else b"") + (b">" if first.terminal else b"")
        if not targets:
            return raw if self.echo_on() else b""   # for a device not on this chain: passed along
        out: list[str] = []
        for unit in targets:
            out += self.execute(unit, text, word, arg.strip())
        first = targets[0]
        if first.defining is None and word not in PROTOCOL and word != ";" and text:
            out += self.on_machine(first, text, word)   # what the command or the sequence transmits
        relayed = self.relayed(first, word, arg)
        if relayed is not None and first.defining is None:
            self.command((relayed + "\r").encode("latin-1"))   # device b's echo goes on to the host
        reply = (raw if first.echo else b"") + "".join(line + "\r" for line in out).encode("latin-1")
        return reply + (b">" if first.terminal else b"")

    def relayed(self, sender: Unit, word: str, arg: str) -> str | None:
        """The command string a quote sends to another device of the chain (`1"2XR3"`: device 2
        runs sequence 3; L5593 "to command other devices to move", example L5614), else None."""
        if word != '"':
            return None
        inner = arg.strip().removesuffix('"')
        match = re.fullmatch(r"(\d+)[A-Za-z].*", inner)
        if match is None or match.group(1) == sender.address or match.group(1) not in self.units:
            return None
        return inner

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
        if word == "#":
            return self.step(unit, arg)
        handler = getattr(self, f"do_{word}", None)
        if handler is not None:
            return handler(unit, arg)
        if word == "VAR":
            return self.var(unit, arg)
        return []   # other commands: accepted, then run on the machine (command)

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
        self.sim.stop()
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
        running = self.sim.status == "running" or self.sim.is_moving(unit.address)   # now, on the clock
        return [("*B" if running else "*R") if not function_error else ("*C" if running else "*S")]

    def do_PR(self, unit: Unit, arg: str) -> list[str]:
        """The absolute position counter (L3141-L3144: `*-25600`, `*+4000`), as the simulator prints
        `aPR` on the machine: the format is the one the lowering gives it (compiler/x150/neutral.py)."""
        module = module_of("x150", f"{unit.address}PR\n")
        outcome = self.sim.run(module, None, program=False, buffered=True) if module is not None else None
        # the counter counts whole steps: read during a sequence's move it is a whole number too
        return [re.sub(r"([+-]?\d+\.\d+)", lambda m: str(round(float(m.group(1)))), text.rstrip("\n"))
                for text in outcome.prints] if outcome is not None else []

    def do_IS(self, unit: Unit, arg: str) -> list[str]:
        """Input status (L2173-L2178): the 7 dedicated inputs (none active on a virtual device),
        then the 10 user inputs from the machine."""
        user = "".join(str(self.sim.machine.inputs.get(n, 0)) for n in range(1, 11))
        return [f"*0000000_{user}"]

    def var(self, unit: Unit, arg: str) -> list[str]:
        match = re.fullmatch(r"(\d+)(?:=(-?\d+(?:\.\d+)?))?", arg.replace(" ", ""))
        if not match or not 1 <= int(match.group(1)) <= 50:
            return []
        n = int(match.group(1))
        if match.group(2) is None:
            return [f"* {unit.variables.get(n, 0.0):.4f}"]
        unit.variables[n] = float(match.group(2))
        self.sim.write(f"VAR{n}", unit.variables[n])   # the running sequence reads it too
        return []

    # -- single step --------------------------------------------------------------------------
    def setting_on(self, name: str, unit: Unit) -> bool:
        """Whether the device setting `name` (the simulator's, kept between commands) is on for `unit`."""
        return any(value for (setting, axis, _), value in self.sim.settings.items()
                   if setting == name and axis in (unit.address, "*"))

    def step(self, unit: Unit, arg: str) -> list[str]:
        """`#n`: the sequence running in single-step mode runs n more commands (L5330-L5345; `#`
        alone one, L5557). The device replays it from where it started up to that many commands
        (the simulator runs a program from its start), so the machine is where those commands left
        it; the reply is what they transmitted (their trace lines when the trace is on, L5345)."""
        state = self.stepping.get(unit.address)
        if state is None:
            return []
        state.done += int(arg) if arg.isdigit() else 1
        self.sim.restore(state.start)
        outcome = self.sim.run(state.module, None, program=True, commands=state.done)
        lines = [line for text in outcome.prints for line in text.splitlines()]
        new, state.sent = lines[state.sent:], len(lines)
        if outcome.status != "running" or outcome.reason and not outcome.reason.startswith("single step"):
            del self.stepping[unit.address]   # the sequence ended (or stopped otherwise)
        for name, value in self.sim.variables.items():
            if name.startswith("VAR") and name[3:].isdigit() and 1 <= int(name[3:]) <= 50:
                unit.variables[int(name[3:])] = float(value)
        return new

    # -- the simulator's machine ----------------------------------------------------------
    def synchronise(self) -> None:
        """The variables the running sequence changed are what `VARn` reads (on the unit that ran it)."""
        unit = self.units.get(self.running)
        if unit is not None and self.sim.generation != self.synced:
            self.synced = self.sim.generation
            self.take_variables(unit)

    def take_variables(self, unit: Unit) -> None:
        for name, value in self.sim.variables.items():
            if name.startswith("VAR") and name[3:].isdigit() and 1 <= int(name[3:]) <= 50:
                unit.variables[int(name[3:])] = float(value)

    def on_machine(self, unit: Unit, text: str, word: str) -> list[str]:
        """Run a command on the machine, after the unit's context; a sequence run (XR, XG, GOSUB,
        GOTO) also compiles the unit's sequences and is the device's program. Returns the lines
        the run transmitted (quoted messages, TX, reports), which the host receives."""
        arg = parse(text)[2].strip()
        variable = re.fullmatch(r"\(VAR(\d+)\)", arg.replace(" ", "")) if word == "D" else None
        if word in CONTEXT and (variable or re.fullmatch(r"-?\d+(\.\d+)?" if CONTEXT[word] not in ("MP", "MODE") else "",
                                                          arg)):
            unit.context[CONTEXT[word]] = text
            if word == "D":   # D(VAR5): the distance is the variable's value (L832-L837)
                value = unit.variables.get(int(variable.group(1)), 0.0) if variable else float(arg)
                self.sim.variables[f"%D{unit.address}"] = int(value) if float(value).is_integer() else value
        lines = [line for key, line in unit.context.items() if line != text]
        program = word in RUNS
        if program:
            if not arg.isdigit() or int(arg) not in unit.sequences:
                unit.xsr = "2"
                return []
            unit.xsr = "0"
            for n, body in sorted(unit.sequences.items()):
                lines += [f"{unit.address}XD{n}", *body, f"{unit.address}XT"]
            if not parse(text)[0]:
                text = unit.address + text   # an unaddressed XR1 runs the unit's sequence 1, stored as 1XD1
            if self.setting_on("trace", unit):
                lines.append(f"{unit.address}XTR1")   # trace on (XTR1 earlier): the run reports its commands
            if self.setting_on("single_step", unit):
                lines.append(f"{unit.address}XST1")   # single step (XST1 earlier): the host's # runs each command

            if any('"' in line for body in unit.sequences.values() for line in body):
                # a quote may start another device's sequence (`1"2XR3"`): theirs are in the program too
                for other in self.units.values():
                    if other is not unit:
                        for n, body in sorted(other.sequences.items()):
                            lines += [f"{other.address}XD{n}", *body, f"{other.address}XT"]
        module = module_of("x150", "\n".join([*lines, text]) + "\n")
        if module is None:
            return []
        self.sim.variables.update({f"VAR{k}": v for k, v in unit.variables.items()})
        if program and self.setting_on("single_step", unit):
            # single step (L5330-L5345): the sequence waits for the host's #n; it starts from here
            self.stepping[unit.address] = Stepping(module, self.sim.snapshot())
            self.sim.run(module, None, program=True, commands=0)
            return []
        outcome = self.sim.run(module, None, program=program, buffered=buffered(word))
        if program:
            self.running = unit.address
        self.take_variables(unit)
        if program and outcome.status == "error":
            unit.xsr = "2"
        return [line for text in outcome.prints for line in text.splitlines()]


@dataclass
class Stepping:
    """A sequence run in single-step mode: its program, the device's state where it started, the
    commands the host has let run and the lines already sent."""

    module: object
    start: dict
    done: int = 0
    sent: int = 0


PROTOCOL = {"XD", "XT", "S", "STOP", "XE", "XEALL", "XSD", "XSS", "XSR", "XBS", "XU", "PASS", "SV", "EX", "SSA",
            "R", "PR", "IS", '"', "#"}


def make(faults: Faults | None, options: DeviceOptions) -> VirtualDevice:
    """The virtual device `mcc device` runs (link/device/virtual.py): the devices at the options'
    addresses, each with a sequence store of the options' size."""
    return X150Device(faults, addresses=options.addresses, capacity=options.sequence_bytes,
                      run_limit=options.run_limit)
