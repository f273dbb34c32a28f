"""A virtual Arcus PMX-4EX-SA behind its ASCII protocol on RS-485 (`@00CMD` CR, reply CR).

State (manual L1492-L1715): the standalone program's compiled lines SA0-SA3229 (written to flash
as they arrive, L844), its status SASTAT and program counter SPC, SR run/stop/pause/continue,
the variables V0-V63, SLOAD and the parameters STORE keeps, and the motion settings the host can
read back. The real compiled-line format is the vendor compiler's and undocumented; the virtual
device holds mcc's compiled statements in their place (one per line), which only it interprets:
running the program (SR=1, GSn for a subroutine) compiles them back into the IR and runs them on
the simulator's machine (device/machine.py), as do the host's motion, position and output
commands (spelled as standalone statements, HOST_COMMANDS); PX, PP, PS, DO and DI read it.
"""

from __future__ import annotations

import copy
import re
from typing import TYPE_CHECKING

from mcc.compiler import ir
from mcc.link.device.base import VirtualDevice
from mcc.link.device.faults import Faults
from mcc.link.device.machine import RUN_LIMIT, DeviceMachine
from mcc.link.device.programs import module_of

if TYPE_CHECKING:
    from mcc.link.device.virtual import DeviceOptions

PROGRAM_LINES = 3230
INVALID = "?Invalid Command"   # the manual: "?(Error Message)" (L1494), the text is undocumented
SETTINGS = {"ACC": "300", "HS": "1000", "LS": "100", "DO": "0", "DI": "0", "EO": "0", "SLOAD": "0",
            "DB": "1", "DN": "4EX00",
            # per-axis speeds HS[axis], LS[axis], ACC[axis] (L449-L458): they read back what was
            # set, starting at the global defaults (the manual gives no default of their own)
            **{f"{name}{axis}": value for name, value in (("HS", "1000"), ("LS", "100"), ("ACC", "300"))
               for axis in "XYZU"},
            # signal polarity PO[axis], bits home/alarm/limit (L702-L704); the manual gives no
            # default: 0
            **{f"PO{axis}": "0" for axis in "XYZU"}}
BUFFER_POINTS = 36   # "Linear Interpolations is buffer move size is 36 points" (L628)
TIMER_MAX = 1_000_000  # TR reads 0..1,000,000 ms (L1701)
ACTIONS = ("ABORT", "ABS", "INC", "STOP", "BO", "BF", "STORE")
AXES = "XYZU"
# The settings a program can change, read back from the machine: name -> (motion setting, scale
# to the host's unit: ACC in ms, L441; HS, LS in pulses/s, L445).
READ_BACK = {"ACC": (ir.MotionParam.ACCEL_TIME, 1000), "HS": (ir.MotionParam.MAX_SPEED, 1),
             "LS": (ir.MotionParam.INITIAL_SPEED, 1)}
# Host commands that act on the machine, as the standalone statement mcc's frontend compiles
# (the catalog's `ascii` spellings, compiler/catalogs/arcus.toml): (pattern, statement template).
HOST_COMMANDS = [
    (r"J([XYZU])([+-])", r"JOG\1\2"),
    (r"H([XYZU])([+-])0?", r"HOME\1\2"),
    (r"H([XYZU])([+-])2", r"ZHOME\1\2"),
    (r"H([XYZU])([+-])3", r"ZOME\1\2"),
    (r"(STOP|ABORT)([XYZU]?)", r"\1\2"),
    (r"((?:[XYZU]-?\d+\s*)+)", r"\1"),
    (r"P([XYZU])=(-?\d+)", r"P\1=\2"),
    (r"HS=(\d+)", r"HSPD=\1"),
    (r"LS=(\d+)", r"LSPD=\1"),
    (r"((?:ARC[PN]-?\d+:-?\d+:-?\d+)|(?:CIR[PN]-?\d+:-?\d+))", r"\1"),   # arcs and circles (L586-L600)
    (r"HS([XYZU])=(\d+)", r"HSPD\1=\2"),
    (r"LS([XYZU])=(\d+)", r"LSPD\1=\2"),
    (r"ACC([XYZU])=(\d+)", r"ACC\1=\2"),
    (r"ACC=(\d+)", r"ACC=\1"),
    (r"DO=(\d+)", r"DO=\1"),
    (r"DO([1-8])=([01])", r"DO\1=\2"),
]


class ArcusDevice(VirtualDevice):
    terminators = b"\r"

    def __init__(self, faults: Faults | None = None, address: str = "00", version: str = "V135",
                 run_limit: float = RUN_LIMIT) -> None:
        super().__init__(faults)
        self.sim = DeviceMachine("arcus", run_limit)
        self.mode = "ABS"   # ABS / INC: the move mode of the host's X/Y/Z/U commands (L1512, L1547)
        self.address = address
        self.version = version
        self.lines: dict[int, str] = {}
        self.variables = [0] * 64
        self.settings = dict(SETTINGS)
        self.stored_settings = dict(SETTINGS)
        self.paused = False
        self.pc = 0
        self.buffered = False                       # BO / BF (L628)
        self.points: list[tuple[int, int, int, int]] = []   # I moves waiting for BO

    @property
    def state(self) -> str:
        """SASTAT: 0 stopped, 1 running, 2 paused, 4 in error (from the machine's program)."""
        status = self.sim.status
        if status == "running":
            return "2" if self.paused else "1"
        return "4" if status == "error" else "0"

    def load_program(self, text: str, name: str = "<device>") -> None:
        """Put a .prg on the device as the vendor's software would (mcc's statements stand in
        for the undocumented compiled lines)."""
        from mcc.compiler import driver

        result = driver.compile_file(name, "arcus", text=text, verify=False)
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
        match = re.fullmatch(r"GS(\d+)", upper)
        if match:   # call a subroutine of the standalone program; an undefined one is an error (L823, L1551)
            return "OK" if self.run(int(match.group(1))) else INVALID
        match = re.fullmatch(r"TR(?:=(\d+))?", upper)
        if match:   # the timer register counts down to 0 in ms from the value written (L789-L793, L1701-L1702)
            machine = self.sim.machine
            if match.group(1) is None:
                return str(int(round(machine.countdown_left(self.sim.clock) * 1000)))
            if int(match.group(1)) > TIMER_MAX:
                return INVALID
            machine.load_countdown(self.sim.clock, int(match.group(1)) / 1000)
            return "OK"
        reading = self.reading(upper)
        if reading is not None:
            return reading
        match = re.fullmatch(r"V(\d+)(?:=(-?\d+))?", upper)
        if match:
            n = int(match.group(1))
            if n > 63:
                return INVALID
            if match.group(2) is None:
                return str(self.variables[n])
            self.variables[n] = int(match.group(2))
            self.sim.write(f"V{n}", self.variables[n])   # what the running program and the next run read
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
            self.on_machine(upper)
            return "OK"
        if upper in ("ABS", "INC"):
            self.mode = upper
            return "OK"
        match = re.fullmatch(r"I(-?\d+):(-?\d+):(-?\d+):(\d+)", upper)
        if match:   # buffered linear interpolation of X, Y, Z at a constant speed (L622-L630)
            return self.interpolation(tuple(int(g) for g in match.groups()))
        if upper in ("BO", "BF"):
            self.buffered = upper == "BO"
            while self.buffered and self.points:
                self.interpolate(self.points.pop(0))
            return "OK"
        if self.on_machine(upper) or upper in ACTIONS:
            return "OK"
        return INVALID

    def reading(self, cmd: str) -> str | None:
        """Positions, speeds and I/O read from the machine (L1581-L1614), or None."""
        sim = self.sim
        if re.fullmatch(r"P[XYZU]", cmd) or re.fullmatch(r"E[XYZU]", cmd):
            return str(int(round(sim.position(cmd[1]))))
        if cmd in ("PP", "PE"):
            return ":".join(str(int(round(sim.position(a)))) for a in AXES)
        if cmd == "PS":
            return ":".join(str(int(round(abs(sim.speed(a))))) for a in AXES)
        if cmd == "MST":
            return self.motor_status()
        if cmd == "DO":
            return str(sim.machine.output_mask())
        if cmd == "DI":   # the levels: 255 with nothing connected, an input sunk to ground reads 0 (L797, L1905)
            return str(sum(sim.input_level(n) << (n - 1) for n in range(1, 9)))
        match = re.fullmatch(r"D([OI])([1-8])", cmd)
        if match:   # DI1-DI8: 1 when the input is triggered, as a program reads it (L1929)
            if match.group(1) == "I":
                return str(sim.input_logic(int(match.group(2))))
            return str(sim.machine.outputs.get(int(match.group(2)), 0))
        return None

    def motor_status(self) -> str:
        """MST (L720-L731, L1581): per axis bit 0 accelerating, bit 1 decelerating, bit 2 constant
        speed, at the clock (the limit and alarm bits: no switch on a virtual device), then the
        buffered move's state: enabled (BO), start and end (0: the manual does not say what they
        hold), the points still free of the 36 (L628), and the move mode (0 ABS, 1 INC: a decision,
        the manual gives no values)."""
        sim, now = self.sim, self.sim.clock
        fields = []
        for name in AXES:
            bits = 0
            if sim.is_moving(name):
                here, later = abs(sim.speed(name)), abs(self.speed_at(name, now + 1e-4))
                bits = 1 if later > here + 1e-6 else 2 if later < here - 1e-6 else 4
            fields.append(bits)
        fields += [int(self.buffered), 0, 0, BUFFER_POINTS - len(self.points), int(self.mode == "INC")]
        return ":".join(str(f) for f in fields)

    def speed_at(self, name: str, t: float) -> float:
        axis = self.sim.machine.axes.get(name)
        if axis is None or axis.motion is None:
            return self.sim.moving.get(name, 0.0)   # a held program's frozen axis keeps its speed
        return axis.speed(t)

    def synchronise(self) -> None:
        """What the running program changed (its variables, the settings it set) is what the host reads."""
        if self.sim.generation != self.synced:
            self.synced = self.sim.generation
            self.take_variables()
            self.take_settings()

    def on_machine(self, cmd: str) -> bool:
        """Run a host command that acts on the machine; False when it is not one."""
        for pattern, template in HOST_COMMANDS:
            match = re.fullmatch(pattern, cmd)
            if match:
                statement = match.expand(template)
                module = module_of("arcus", f"{self.mode}\n{statement}\nEND\n")
                if module is None:
                    return False
                self.sim.variables.update({f"V{i}": v for i, v in enumerate(self.variables)})
                self.sim.run(module, None, program=False)
                self.take_variables()
                return True
        return False

    def interpolation(self, point: tuple[int, int, int, int]) -> str:
        """`I x:y:z:speed`: with the buffered mode on the move starts at once, else it waits in
        the 36-point buffer for BO (L628)."""
        if point[3] <= 0:
            return INVALID
        if self.buffered:
            self.interpolate(point)
            return "OK"
        if len(self.points) >= BUFFER_POINTS:
            return INVALID
        self.points.append(point)
        return "OK"

    def interpolate(self, point: tuple[int, int, int, int]) -> None:
        """One buffered move to the X, Y, Z position at its own constant speed: "There is no
        acceleration or deceleration in the speed" (L624), so it starts and ends at that speed
        (LSPD = HSPD). The move's speed is its own: the speeds in force are kept."""
        x, y, z, speed = point
        kept = copy.deepcopy((self.sim.machine.shared, {a: ax.settings for a, ax in self.sim.machine.axes.items()}))
        module = module_of("arcus", f"HSPD={speed}\nLSPD={speed}\nABS\nX{x} Y{y} Z{z}\nEND\n")
        if module is not None:
            self.sim.run(module, None, program=False)
        shared, settings = kept
        self.sim.machine.shared.clear()
        self.sim.machine.shared.update(shared)
        for name, axis in self.sim.machine.axes.items():
            if name in settings:
                axis.settings = settings[name]
            axis.cached = None

    def control(self, code: str) -> str:
        if code == "0":
            self.sim.stop()
            self.paused = False
        elif code == "1":
            self.run()
        elif code == "2" and self.state == "1":
            self.paused = True
            self.sim.pause()    # the program stops where it is until SR=3 (L1626-L1632)
        elif code == "3" and self.state == "2":
            self.paused = False
            self.sim.resume()
        return "OK"

    # -- the standalone program on the simulator's machine ------------------------------------
    def run(self, subroutine: int | None = None) -> bool:
        """SR=1: run the standalone program from its start (or GSn: subroutine n)."""
        text = "\n".join(self.lines[i] for i in sorted(self.lines))
        module = module_of("arcus", text + "\n") if text else None
        kind = ir.RoutineKind.MAIN if subroutine is None else ir.RoutineKind.SUBROUTINE
        routine = None if module is None else next(
            (r for r in module.routines if r.kind is kind and (subroutine is None or r.number == subroutine)), None)
        self.paused = False
        if routine is None:
            if subroutine is None:
                self.sim.status, self.sim.reason = "error", "no program to run"
            return False
        self.sim.variables.update({f"V{i}": v for i, v in enumerate(self.variables)})
        self.sim.run(module, (routine.name, None))
        self.take_variables()
        self.take_settings()
        return True

    def take_settings(self) -> None:
        """What the program set (ACC=V3, HSPD=2500, HSPDX=...) is what the host reads back."""
        enable = self.sim.settings.get(("enable_outputs", ir.ALL_AXES, None))   # EO=3 in the program (L2142)
        if enable is not None:
            self.settings["EO"] = str(int(enable))
        shared = self.sim.machine.shared.get("*", {})
        for name, (param, scale) in READ_BACK.items():
            if param in shared:
                self.settings[name] = str(int(round(shared[param] * scale)))
            for axis in AXES:
                found = self.sim.machine.axes.get(axis)
                if found is not None and param in found.settings:
                    self.settings[f"{name}{axis}"] = str(int(round(found.settings[param] * scale)))

    def take_variables(self) -> None:
        for name, value in self.sim.variables.items():
            if re.fullmatch(r"V\d+", name) and int(name[1:]) < 64:
                self.variables[int(name[1:])] = int(value)


def make(faults: Faults | None, options: DeviceOptions) -> VirtualDevice:
    """The virtual device `mcc device` runs (link/device/virtual.py): a controller at the options'
    address, with the options' program image loaded."""
    device = ArcusDevice(faults, address=options.address, run_limit=options.run_limit)
    if options.program:
        with open(options.program, encoding="utf-8", errors="replace") as handle:
            device.load_program(handle.read(), options.program)
    return device
