"""A virtual Lexium MCode device: the host protocol of manual §7.1 and the state it exposes.

State: echo mode EM, checksum mode CK, party mode PY and name DN, the error register ER/EF,
program memory (lines stored between `PG n` and `PG`, with their labels), user variables (VA,
global or local), the factory variables of the catalog with their defaults, ranges and access,
the lock LK, and what `S` saved. Commands are recognised with mcc's MCode catalog; errors are the
manual's codes (20 unknown variable, 21 bad value, 25 read only, 28 redefined, 29 name of a
command, 30 unknown label, 42 bad address, 44 locked, 45 program space full, 46 not in program
mode, 60 unknown command). Programs and immediate commands run on the simulator's machine
(device/machine.py), and P, V, MV, BY, the outputs, the inputs and the motion settings are read
from it.
"""

from __future__ import annotations

import copy
import re
from dataclasses import dataclass, field
from functools import lru_cache
from typing import TYPE_CHECKING

from mcc.compiler import catalog, ir, ir_names
from mcc.compiler.mcode.tables import STAND_IN_VERSION, TABLES
from mcc.compiler.profiles import load as load_profile
from mcc.link.device.base import VirtualDevice
from mcc.link.device.faults import Faults
from mcc.link.device.machine import RUN_LIMIT, DeviceMachine
from mcc.link.device.programs import module_of
from mcc.sim import values

if TYPE_CHECKING:
    from mcc.link.device.virtual import DeviceOptions

ACK, NAK = b"\x06", b"\x15"
USER_NAME_TABLE = 192   # labels and user variables share one table (L537)
AXIS = "1"              # the IR's name for the drive's own axis
MOVES = ("MA", "MR", "SL")   # the motion instructions MD remembers (L4150)
# factory variables that are motion settings of the simulator's machine
SETTINGS = {"VM": ir.MotionParam.MAX_SPEED, "VI": ir.MotionParam.INITIAL_SPEED, "A": ir.MotionParam.ACCEL,
            "D": ir.MotionParam.DECEL}


class MCodeError(Exception):
    def __init__(self, code: int) -> None:
        super().__init__(code)
        self.code = code


@dataclass(frozen=True)
class Name:
    kind: str       # instruction | variable | flag | keyword | reserved | ...
    access: str
    default: object
    range: tuple | None
    setting: str = ""   # the neutral setting the register holds (the catalog's `setting` key)


@lru_cache(maxsize=None)
def names() -> dict[str, Name]:
    """Every factory name of the catalog (indexed families expanded: I1-I4, R1-R4, ...)."""
    table: dict[str, Name] = {}
    for entry in catalog.load("mcode").entries:
        if entry.kind in ("operator", "function"):
            continue
        info = Name(entry.kind, entry.get("access", "") or "", entry.default, entry.range, entry.get("setting", ""))
        index = entry.get("index")
        spellings = [f"{entry.name}{i}" for i in range(index[0], index[1] + 1)] if index else [entry.name]
        for spelling in spellings:
            table.setdefault(spelling.upper(), info)
    return table


def split_items(text: str) -> list[str]:
    """PR items / parameters split on commas outside double quotes."""
    items, current, quoted = [], "", False
    for ch in text:
        if ch == '"':
            quoted = not quoted
        if ch == "," and not quoted:
            items.append(current.strip())
            current = ""
        else:
            current += ch
    if current.strip():
        items.append(current.strip())
    return items


# The setups kept per line (IS, OS, LS) and how PR writes them: compiler/mcode/tables.py, which
# the lowering reads too.
CLOCK_TYPES = (13, 14, 15)   # IS types of the input 3/4 pair: setting one sets the other (L3522)
INDEX_INPUT = 6              # IS=6,<active>: its only parameter is the active state (L3595-L3605)


def factory_tables() -> dict[str, dict[int, list[int]]]:
    return {name: {n: list(rest) for n, rest in lines.items()} for name, (lines, _form) in TABLES.items()}


@dataclass
class Memory:
    """What S saves and a power cycle restores."""

    program: list[str] = field(default_factory=list)
    origins: dict[int, int] = field(default_factory=dict)      # PG address -> first line index
    labels: dict[str, int] = field(default_factory=dict)       # label -> line index
    user: dict[str, list] = field(default_factory=dict)        # name -> [scope G|L, value]
    variables: dict[str, object] = field(default_factory=dict)
    tables: dict[str, dict[int, list[int]]] = field(default_factory=factory_tables)
    lock: int = 0


class MCodeDevice(VirtualDevice):
    terminators = b"\r\n"

    def __init__(self, faults: Faults | None = None, program_lines: int = 1500, version: str | None = None,
                 run_limit: float = RUN_LIMIT, profile=None) -> None:
        super().__init__(faults)
        self.program_lines = program_lines
        self.run_limit = run_limit
        self.profile = profile if profile is None or not isinstance(profile, str) else load_profile(profile)
        self.sim = DeviceMachine("mcode", run_limit, self.profile)
        # The drive's identity, as PR VR and PR PN report it (L6185-L6192, L4868-L4875): the
        # product profile's [device] version and part_number; mcc's own stand-in without them.
        identity = self.sim.profile
        self.version = version or (identity.get("device.version") if identity is not None else None) or STAND_IN_VERSION
        self.part_number = (identity.get("device.part_number") if identity is not None else None) or ""
        self.memory = Memory(variables={n: i.default for n, i in names().items()
                                        if i.kind in ("variable", "flag") and i.default is not None})
        self.saved = copy.deepcopy(self.memory)
        self.error = 0
        self.program_mode = False

    # -- framing ---------------------------------------------------------------------------
    def var(self, name: str, default=0):
        return self.memory.variables.get(name, default)

    def command(self, raw: bytes) -> bytes:
        body = raw.rstrip(b"\r\n")
        party = int(self.var("PY", 0) or 0)
        checksum = int(self.var("CK", 0) or 0)
        echo_mode = int(self.var("EM", 0) or 0)
        reply_wanted = True
        if party:
            name = str(self.var("DN", "!")).strip('"')
            prefix = body[:1].decode("latin-1")
            if prefix == "*":
                reply_wanted = False
            elif prefix != name:
                return b""  # addressed to another device on the line
            body = body[1:]
        echo = raw.rstrip(b"\r\n") if echo_mode in (0, 3) else b""
        if checksum:
            if not body or sum((raw.rstrip(b"\r\n"))) & 0x7F:
                return (echo + NAK + b">") if reply_wanted else b""
            body = body[:-1]
        text = body.decode("latin-1")
        output, ok = self.execute(text)
        if not reply_wanted:
            return b""
        lines = b""
        for line in output:
            data = line.encode("latin-1")
            if checksum:
                data += bytes([((-sum(data)) & 0x7F) | 0x80])
            lines += data + b"\r\n"
        end = ACK if checksum else b"\r\n"
        prompt = b">" if ok else b"?"
        if echo_mode == 0:
            return echo + end + lines + prompt
        if echo_mode == 1:
            return lines + end
        if echo_mode == 2:
            return lines
        return echo + lines + end

    # -- commands --------------------------------------------------------------------------
    def execute(self, text: str) -> tuple[list[str], bool]:
        try:
            return self.dispatch(text.strip()), True
        except MCodeError as exc:
            self.error = exc.code
            self.memory.variables["EF"] = 1
            return [], False

    def dispatch(self, text: str) -> list[str]:
        if not text or text.startswith(("'", "`")):
            return []
        text = re.split(r"\s['`]", text, maxsplit=1)[0].strip()
        word_match = re.match(r"([A-Za-z][A-Za-z0-9_]*)", text)
        if not word_match:
            raise MCodeError(60)
        word = word_match.group(1).upper()
        rest = text[word_match.end():]
        if word == "PG":
            return self.pg(rest.strip())
        if self.program_mode:
            return self.store(text, word, rest)
        handler = getattr(self, f"cmd_{word}", None)
        if handler is not None:
            return handler(rest.strip())
        before = self.numbers()   # an assignment's expression reads the values before it
        self.assign_or_instruction(word, rest)
        self.on_machine(text, before)
        if word in MOVES:
            self.memory.variables["MD"] = word   # the last motion instruction (MD, L4145-L4153)
        return []

    def pg(self, arg: str) -> list[str]:
        if not arg:
            if not self.program_mode:
                raise MCodeError(46)
            self.program_mode = False
            return []
        if self.program_mode:
            raise MCodeError(42)
        if not arg.isdigit() or int(arg) < 1:
            raise MCodeError(42)
        if self.memory.lock:
            raise MCodeError(44)
        self.memory.origins.setdefault(int(arg), len(self.memory.program))
        self.program_mode = True
        return []

    def store(self, text: str, word: str, rest: str) -> list[str]:
        info = names().get(word)
        if word not in self.memory.user and word not in self.memory.labels and info is None:
            raise MCodeError(60 if not rest.lstrip().startswith("=") else 20)
        if info is not None and info.kind == "reserved":
            raise MCodeError(24)
        if word == "LB":
            label = rest.strip().upper()
            if label in self.memory.labels or label in self.memory.user:
                raise MCodeError(28)
            if len(self.memory.labels) + len(self.memory.user) >= USER_NAME_TABLE:
                raise MCodeError(31)
        if word == "VA":
            self.declare(rest.strip(), "L")
        if len(self.memory.program) >= self.program_lines:
            raise MCodeError(45)
        if word == "LB":
            self.memory.labels[rest.strip().upper()] = len(self.memory.program)
        self.memory.program.append(" ".join(text.split()))
        return []

    def declare(self, spec: str, scope: str) -> None:
        name, _, initial = spec.partition("=")
        name = name.strip().upper()
        if not re.fullmatch(r"[A-Z][A-Z0-9_]*", name):
            raise MCodeError(24)
        if name in names():
            raise MCodeError(29)
        if name in self.memory.user or name in self.memory.labels:
            raise MCodeError(28)
        if len(self.memory.labels) + len(self.memory.user) >= USER_NAME_TABLE:
            raise MCodeError(31)
        self.memory.user[name] = [scope, self.evaluate(initial) if initial.strip() else 0]

    def evaluate(self, text: str):
        text = text.strip()
        try:
            return int(text)
        except ValueError:
            pass
        try:
            return float(text)
        except ValueError:
            pass
        upper = text.upper()
        if upper in self.memory.user:
            return self.memory.user[upper][1]
        if upper in self.memory.variables:
            return self.memory.variables[upper]
        return text  # an expression or a multi-part setting kept as written

    def read(self, name: str):
        upper = name.upper()
        if upper in self.memory.user:
            return self.memory.user[upper][1]
        info = names().get(upper)
        if info is None or info.kind in ("instruction", "reserved"):
            raise MCodeError(35)
        live = self.live(upper)
        return live if live is not None else self.memory.variables.get(upper, 0)

    def live(self, name: str):
        """What the simulator's machine says for a factory variable, or None."""
        sim = self.sim
        if name in ("P", "C1", "C2"):   # counters: whole steps
            return int(round(sim.position(AXIS)))
        if name == "MV":   # the axis is moving now (L4424)
            return 1 if sim.is_moving(AXIS) else 0
        if name == "MP":   # a positional move (MA, MR) in progress (L4211-L4220); a slew is not one
            return 1 if sim.is_moving(AXIS) and not sim.is_slewing(AXIS) else 0
        if name == "V":
            return int(round(sim.speed(AXIS)))
        if name == "BY":
            return 1 if sim.status == "running" else 0
        if name in SETTINGS and SETTINGS[name] in sim.machine.axis(AXIS).settings:
            return plain(sim.setting(AXIS, SETTINGS[name]))
        match = re.fullmatch(r"([OI])(\d)", name)
        if match:
            table = sim.machine.outputs if match.group(1) == "O" else sim.machine.inputs
            return table.get(int(match.group(2)), 0)
        if name == "OT":
            return sim.machine.output_mask()
        if name == "IN":
            return sim.machine.input_mask()
        return None

    def assign_or_instruction(self, word: str, rest: str) -> list[str]:
        info = names().get(word)
        user = word in self.memory.user
        assigning = rest.lstrip().startswith("=") or (info is not None and info.kind in ("variable", "flag")
                                                      and rest.strip() != "")
        if not user and info is None:
            if word in self.memory.labels:
                raise MCodeError(32 if assigning else 60)
            raise MCodeError(20 if rest.lstrip().startswith("=") else 60)
        if info is not None and info.kind == "reserved":
            raise MCodeError(24)
        if not assigning:
            if info is not None and info.kind in ("variable", "flag", "keyword") and not user:
                raise MCodeError(60)
            return []  # an instruction: accepted, then run on the machine (dispatch)
        value_text = rest.strip().lstrip("=").strip()
        if user:
            self.memory.user[word][1] = self.evaluate(value_text)
            return []
        if info.kind == "instruction":
            raise MCodeError(33)
        if info.access in ("ro",):
            raise MCodeError(25)
        value = self.evaluate(value_text)
        if info.access == "rc" and value != 0:
            raise MCodeError(21)
        if isinstance(value, (int, float)) and info.range and not (info.range[0] <= value <= info.range[1]):
            raise MCodeError(21)
        if word == "ER":
            self.error = 0
            self.memory.variables["EF"] = 0
        if word in TABLES:
            self.set_line(word, value_text)
        self.memory.variables[word] = value
        return []

    def set_line(self, name: str, text: str) -> None:
        """IS/OS/LS=<line>,<p2>[,<p3>]: one line of a setup table; an omitted parameter keeps
        the line's value. A line the product does not have is error 21 (illegal data)."""
        try:
            numbers = [int(part) for part in text.split(",")]
        except ValueError:
            raise MCodeError(21) from None
        table = self.memory.tables[name]
        if not 2 <= len(numbers) <= 3 or numbers[0] not in table:
            raise MCodeError(21)
        line, params = numbers[0], numbers[1:]
        if name == "IS" and line == INDEX_INPUT and len(params) == 1:
            table[line][1] = params[0]
        else:
            table[line][:len(params)] = params
        if name == "IS" and line in (3, 4) and table[line][0] in CLOCK_TYPES:
            table[7 - line] = list(table[line])   # the other input of the clock pair (L3520)

    # -- instructions with effects on the protocol state -----------------------------------
    def cmd_PR(self, rest: str) -> list[str]:
        out = ""
        for item in split_items(rest.rstrip(";")):
            if item.startswith('"'):
                out += item.strip('"')
            elif item.upper() == "ER":
                out += str(self.error)
                self.error = 0
                self.memory.variables["EF"] = 0
            elif item.upper() == "UV":
                return [f"{n} = {scope} {v}" for n, (scope, v) in self.memory.user.items()]
            elif item.upper() in TABLES:   # every line's setup (PR IS L3533, PR OS L4647, PR LS L4044)
                form = TABLES[item.upper()][1]
                return [form.format(*params, n=n) for n, params in self.memory.tables[item.upper()].items()]
            elif item.upper() == "VR":
                out += self.version
            elif item.upper() == "PN" and self.part_number:
                out += self.part_number
            elif item.upper() == "EF":
                out += str(self.memory.variables.get("EF", 0))
            else:
                out += self.text_of(item, self.read(item))
        return [out]

    def text_of(self, name: str, value) -> str:
        """A value as PR prints it: a floating-point register (F1-F8, SA: the catalog's default is
        a float) in the print format PF in force (default 10,6,0,0, L4744-L4777), as `mcc sim`
        prints it (sim/values.float_text); any other value as it is."""
        info = names().get(name.upper())
        if info is not None and isinstance(info.default, float) and isinstance(value, (int, float)):
            fmt = values.float_format(self.var("PF", info.default)) or values.float_format(names()["PF"].default)
            profile = self.sim.profile
            pad = bool(profile.get("machine.arithmetic.float_print_pad", False)) if profile is not None else False
            return values.float_text(float(value), fmt, pad)
        return str(value)

    def cmd_VA(self, rest: str) -> list[str]:
        self.declare(rest, "G")
        return []

    def cmd_L(self, rest: str) -> list[str]:
        if self.memory.lock:
            raise MCodeError(44)
        start = 0
        if rest:
            key = rest.strip().upper()
            if key.isdigit():
                start = self.memory.origins.get(int(key), -1)
            else:
                start = self.memory.labels.get(key, -1)
            if start < 0:
                raise MCodeError(30 if not key.isdigit() else 42)
        return self.memory.program[start:]

    def cmd_CP(self, rest: str) -> list[str]:
        params = [p.strip() for p in rest.split(",") if p.strip()]
        self.memory.program, self.memory.origins, self.memory.labels = [], {}, {}
        self.memory.lock = 0
        if params[:1] == ["1"] or not params:
            self.memory.user = {}
        else:
            self.memory.user = {n: v for n, v in self.memory.user.items() if v[0] == "G"}
        return []

    def cmd_S(self, rest: str) -> list[str]:
        if rest:
            raise MCodeError(60)
        self.saved = copy.deepcopy(self.memory)
        return []

    def cmd_LK(self, rest: str) -> list[str]:
        value = rest.strip().lstrip("=").strip()
        if value not in ("0", "1"):
            raise MCodeError(21)
        self.memory.lock = int(value)
        self.memory.variables["LK"] = int(value)
        return []

    def cmd_EX(self, rest: str) -> list[str]:
        target = rest.strip().upper()
        if target.isdigit():
            if int(target) not in self.memory.origins:
                raise MCodeError(42)
            entry: str | int = int(target)
        else:
            if target not in self.memory.labels:
                raise MCodeError(30)
            entry = target
        self.run(entry)
        # what the program prints goes to the host as it runs (PR "outputs ... to the communications host", L4895)
        outcome = self.sim.outcome
        return [line for text in (outcome.prints if outcome is not None else []) for line in text.splitlines()]

    def power_cycle(self) -> None:
        """What a power cycle does: the saved state comes back (L862), SU runs."""
        self.memory = copy.deepcopy(self.saved)
        self.program_mode = False
        self.error = 0
        self.sim = DeviceMachine("mcode", self.run_limit, self.profile)
        if "SU" in self.memory.labels:
            self.run("SU")

    # -- the simulator's machine ----------------------------------------------------------
    def synchronise(self) -> None:
        """What the running program changed (its variables, the registers it set) is what the host
        reads: the same as after a command's run."""
        if self.sim.generation != self.synced:
            self.synced = self.sim.generation
            self.after_run()

    def unsolicited(self, lines: list[str]) -> bytes:
        """A program's PR output as the drive sends it while it runs (L4895): each line ends in CR LF."""
        return "".join(line + "\r\n" for line in lines).encode("latin-1")

    def declarations(self) -> list[str]:
        return [f"VA {n}" for n in self.memory.user]

    def program_text(self) -> str:
        declared = [f"VA {n}={v[1] if isinstance(v[1], (int, float)) else 0}"
                    for n, v in self.memory.user.items() if v[0] == "G"]
        regions, lines = [], self.memory.program
        starts = sorted(self.memory.origins.items(), key=lambda kv: kv[1])
        for i, (address, first) in enumerate(starts):
            last = starts[i + 1][1] if i + 1 < len(starts) else len(lines)
            regions += [f"PG {address}", *lines[first:last], "PG"]
        return "\n".join(declared + regions) + "\n"

    def numbers(self) -> dict[str, int | float]:
        """The user variables and registers the device holds, as the simulator reads them."""
        values = {n: v[1] for n, v in self.memory.user.items() if isinstance(v[1], (int, float))}
        values.update({n: v for n, v in self.memory.variables.items()
                       if isinstance(v, (int, float)) and re.fullmatch(r"[RF]\d+", n)})
        return values

    def before_run(self, values: dict | None = None) -> None:
        self.sim.variables.update(self.numbers() if values is None else values)
        for name, info in names().items():  # the drive registers as the device holds them (after a power cycle too)
            value = self.memory.variables.get(name)
            if info.setting and value is not None:
                unit = ir_names.SETTINGS[info.setting].unit
                self.sim.settings[(info.setting, AXIS, None)] = value / 1000 if unit is ir.Unit.S and \
                    isinstance(value, (int, float)) else value

    def after_run(self) -> None:
        """What the run changed, back into the variables the host reads."""
        for name, value in self.sim.variables.items():
            if name in self.memory.user:
                self.memory.user[name][1] = plain(value)
            elif re.fullmatch(r"[RF]\d+", name) and name in names():
                self.memory.variables[name] = plain(value)
        for name, info in names().items():  # drive registers a program set (CW=100 in a program EX ran)
            value = self.sim.settings.get((info.setting, AXIS, None)) if info.setting else None
            if value is not None:
                unit = ir_names.SETTINGS[info.setting].unit
                self.memory.variables[name] = plain(round(value * 1000, 6) if unit is ir.Unit.S else value)
        settings = self.sim.machine.axis(AXIS).settings
        for name, param in SETTINGS.items():
            if param in settings:
                self.memory.variables[name] = plain(settings[param])

    def on_machine(self, text: str, before: dict) -> None:
        """Run an immediate command on the machine (a move, a setting, an output, an assignment).
        A command mcc's frontend does not compile changes only what the protocol state above holds."""
        module = module_of("mcode", "\n".join([*self.declarations(), text]) + "\n")
        if module is None:
            return
        self.before_run(before)
        self.sim.run(module, None, program=False)
        self.after_run()

    def run(self, entry) -> None:
        """Run the stored program from a label or a PG address (EX, the power-up label SU)."""
        module = module_of("mcode", self.program_text())
        start = None if module is None else self.entry(module, entry)
        if start is None:
            self.sim.status, self.sim.reason = "error", "the stored program does not compile"
            return
        self.before_run()
        self.sim.run(module, start)
        self.after_run()

    @staticmethod
    def entry(module: ir.Module, entry) -> tuple[str, str | None] | None:
        for routine in module.routines:
            if isinstance(entry, int) and routine.origin == entry:
                return routine.name, None
            for block in routine.blocks:
                if not isinstance(entry, int) and block.named and block.label.upper() == str(entry).upper():
                    return routine.name, block.label
        return None


def plain(value):
    """A number as the drive prints it: integers without a decimal point."""
    if isinstance(value, float) and value.is_integer():
        return int(value)
    return value


class MCodeBus(VirtualDevice):
    """Several MCode drives in party mode on one RS-422/485 line (L5000-L5053): every drive sees
    every command, each answers only to its own name, none to the global `*`."""

    terminators = b"\r\n"

    def __init__(self, names_on_bus: tuple[str, ...], faults: Faults | None = None, **options) -> None:
        super().__init__(faults)
        self.drives: dict[str, MCodeDevice] = {}
        for name in names_on_bus:
            drive = MCodeDevice(**options)
            drive.memory.variables["PY"] = 1
            drive.memory.variables["DN"] = name
            drive.saved = copy.deepcopy(drive.memory)
            self.drives[name] = drive

    def machines(self) -> list:
        return [drive.sim for drive in self.drives.values()]   # one line, one time for every drive

    def synchronise(self) -> None:
        for drive in self.drives.values():
            drive.synchronise()

    def unsolicited(self, lines: list[str]) -> bytes:
        return "".join(line + "\r\n" for line in lines).encode("latin-1")

    def command(self, raw: bytes) -> bytes:
        return b"".join(drive.command(raw) for drive in self.drives.values())


def make(faults: Faults | None, options: DeviceOptions) -> VirtualDevice:
    """The virtual device `mcc device` runs (link/device/virtual.py): a party of named devices when
    the options name one, else one device; both report the options' product profile."""
    if options.party:
        return MCodeBus(options.party, faults, program_lines=options.program_lines, run_limit=options.run_limit,
                        profile=options.profile)
    return MCodeDevice(faults, program_lines=options.program_lines, run_limit=options.run_limit,
                       profile=options.profile)
