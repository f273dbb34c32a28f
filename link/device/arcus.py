"""A virtual Arcus PMX-4EX-SA behind its ASCII protocol on RS-485 (`@00CMD` CR, reply CR).

State (manual L1492-L1715): the standalone program's compiled lines SA0-SA3229 (written to flash
as they arrive, L844), its status SASTAT and program counter SPC, SR run/stop/pause/continue,
the variables V0-V63, SLOAD and the parameters STORE keeps, and the motion settings the host can
read back. The real compiled-line format is the vendor compiler's and undocumented; the virtual
device holds mcc's compiled statements in their place (one per line), which only it interprets,
so that running a program (SR=1) can go through the execution seam (device/execute.py).
"""

from __future__ import annotations

import re

from mcc.link.device import execute
from mcc.link.device.base import VirtualDevice
from mcc.link.device.faults import Faults
from mcc.link.device.programs import module_of

PROGRAM_LINES = 3230
INVALID = "?Invalid Command"   # the manual: "?(Error Message)" (L1494), the text is undocumented
SETTINGS = {"ACC": "300", "HS": "1000", "LS": "100", "DO": "0", "DI": "0", "EO": "0", "SLOAD": "0",
            "DB": "1", "DN": "4EX00", "TR": "0"}
ACTIONS = ("ABORT", "ABS", "INC", "STOP", "BO", "BF", "STORE")


class ArcusDevice(VirtualDevice):
    terminators = b"\r"

    def __init__(self, faults: Faults | None = None, address: str = "00", version: str = "V135") -> None:
        super().__init__(faults)
        self.address = address
        self.version = version
        self.lines: dict[int, str] = {}
        self.variables = [0] * 64
        self.settings = dict(SETTINGS)
        self.stored_settings = dict(SETTINGS)
        self.state = "0"   # SASTAT: 0 stopped, 1 running, 2 paused, 4 in error
        self.pc = 0

    def load_program(self, text: str, name: str = "<device>") -> None:
        """Put a .prg on the device as the vendor's software would (mcc's statements stand in
        for the undocumented compiled lines)."""
        from mcc.compiler import driver

        result = driver.compile_file(name, "arcus", text=text)
        if result.listing is None or result.has_errors:
            raise ValueError(f"{name} does not compile: " + "; ".join(d.message for d in result.diagnostics[:3]))
        self.lines = {i: line.text for i, line in enumerate(result.listing.lines)}

    def command(self, raw: bytes) -> bytes:
        text = raw.rstrip(b"\r").decode("latin-1")
        if not text.startswith("@" + self.address):
            return b""   # another device on the RS-485 line
        return (self.execute(text[1 + len(self.address):].strip()) + "\r").encode("latin-1")

    def execute(self, cmd: str) -> str:
        upper = cmd.upper()
        if upper == "VER":
            return self.version
        if upper == "SASTAT":
            return self.state
        if upper == "SPC":
            return str(self.pc)
        match = re.fullmatch(r"SA(\d+)(?:=(.*))?", cmd, re.S)
        if match:
            index = int(match.group(1))
            if index >= PROGRAM_LINES:
                return INVALID
            if match.group(2) is None:
                return self.lines.get(index, "")
            if self.state in ("1", "2"):
                return INVALID   # the program is running: its flash is not written
            self.lines[index] = match.group(2)
            return "OK"
        match = re.fullmatch(r"V(\d+)(?:=(-?\d+))?", upper)
        if match:
            n = int(match.group(1))
            if n > 63:
                return INVALID
            if match.group(2) is None:
                return str(self.variables[n])
            self.variables[n] = int(match.group(2))
            return "OK"
        match = re.fullmatch(r"SR=([0-3])", upper)
        if match:
            return self.control(match.group(1))
        if upper == "STORE":
            self.stored_settings = dict(self.settings)
            return "OK"
        match = re.fullmatch(r"([A-Z]+)(?:=(\S+))?", upper)
        if match and match.group(1) in self.settings:
            if match.group(2) is None:
                return self.settings[match.group(1)]
            self.settings[match.group(1)] = match.group(2)
            return "OK"
        if upper in ACTIONS or re.fullmatch(r"([XYZU]-?\d+\s*)+", upper) or re.fullmatch(r"J[XYZU][+-]", upper):
            return "OK"
        return INVALID

    def control(self, code: str) -> str:
        if code == "0":
            self.state = "0"
        elif code == "1":
            self.run()
        elif code == "2" and self.state == "1":
            self.state = "2"
        elif code == "3" and self.state == "2":
            self.state = "1"
        return "OK"

    # -- the execution seam ------------------------------------------------------------------
    def run(self) -> None:
        text = "\n".join(self.lines[i] for i in sorted(self.lines))
        module = module_of("arcus", text + "\n") if text else None
        if module is None:
            self.state = "4"
            return
        values = {f"V{i}": v for i, v in enumerate(self.variables)}
        outcome = execute.run_program(module, values)
        for name, value in outcome.variables.items():
            if re.fullmatch(r"V\d+", name) and int(name[1:]) < 64:
                self.variables[int(name[1:])] = int(value)
        self.state = "1" if outcome.status == "running" else "0"
