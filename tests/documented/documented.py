"""The manuals' own results, run on the simulator and on the virtual device.

Each dialect has one data file here (mcode.toml, x150.toml, arcus.toml): a case is a result the
vendor's manual prints (a reply, a position, an output), with the manual lines, the smallest
program that puts the device in the documented state, and the answer. `exceptions.toml` lists the
cases mcc does not reproduce yet or that the manual does not let anyone reproduce, each with its
reason. tests/documented/test_documented.py and bench/conformance_report.py both run the cases
through this module, so the test and the report count the same thing.

A case (keys of one `[[case]]` table):
    id        stable name, `<dialect>-L<line>-<what>`
    manual    the manual file and lines ("lexium-mcode.txt L6160-L6164")
    program   the program text: run as a file by the simulator and sent line by line to the device
    prints    the lines the program prints (simulator) and the device replies (device), in order
    positions axis -> position in steps after the program (optional)
    outputs   output number -> level after the program (optional)
    variables variable -> value after the program (optional; the device reads it with its own
              query, Arcus `Vn`)
    inputs    input number -> level held during the run (optional; the simulator's scenario)
    device    [[command, reply], ...] for the device when its exchange differs from the program's
              lines (a reply "" = the command answers nothing but its acknowledgement); with
              `stored`, the commands sent after the program's run
    stored    the device stores the program and runs it (Arcus standalone: load, then SR=1)
    profile   the product profile the example is about (default: the dialect's default profile)
    targets   which of "sim" and "device" the case applies to (default both)
    at_once   the device gets the commands one right after the other (default: before each command
              the host waits, up to TYPING seconds, for the device to be idle, as a person typing
              the manual's session waits for the motor to stop: the manual's replies are read then)
    note      how the set-up was derived from the manual, and any decision taken where the
              manual contradicts itself

Hand-worked programs (handworked_<dialect>.toml, issue 22): small realistic programs whose
results were worked out by hand from the manual's rules before running mcc, the arithmetic in a
comment above each case. They use the keys above and three more:
    output_order  [[output, level], ...]: every change of an output level, in the order they happen
    duration      seconds from the start of the run to the end of its last move or delay
    tolerance     the allowed difference on `duration`, in seconds, stated per case (1 ms, or the
                  time of one step at the speed the last move ends at); required with `duration`
On the virtual device, whose clock runs between commands (docs/LINK.md, "Virtual time"), the runner
waits as a host does until the program has ended and no axis moves (polling the status); the
duration is from the start of the first program (else of the first command run on the machine) to
the end of the last run, move or delay, and the output changes are those of every run the
commands started, in time order.
"""

from __future__ import annotations

import tempfile
from dataclasses import dataclass, field
from pathlib import Path

from mcc.compiler import toml

HERE = Path(__file__).resolve().parent
DIALECTS = ("mcode", "x150", "arcus")
EXTENSIONS = {"mcode": ".mxt", "x150": ".x150", "arcus": ".prg"}
TARGETS = ("sim", "device")


@dataclass
class Case:
    dialect: str
    id: str
    manual: str
    program: str
    prints: list[str] | None = None
    positions: dict[str, int] = field(default_factory=dict)
    outputs: dict[int, int] = field(default_factory=dict)
    variables: dict[str, float] = field(default_factory=dict)
    inputs: dict[int, int] = field(default_factory=dict)
    device: list[tuple[str, str]] | None = None
    targets: tuple[str, ...] = TARGETS
    stored: bool = False
    profile: str | None = None
    note: str = ""
    at_once: bool = False
    output_order: list[tuple[int, int]] | None = None
    duration: float | None = None
    tolerance: float | None = None
    handworked: bool = False


@dataclass
class Outcome:
    """What one target did with one case: `ok` when it gave the manual's answer."""

    ok: bool
    got: str


KEYS = {"id", "manual", "program", "prints", "positions", "outputs", "variables", "inputs", "device", "targets", "stored", "profile", "note",
        "at_once"}
HANDWORKED_KEYS = KEYS | {"output_order", "duration", "tolerance"}


def load(dialect: str) -> list[Case]:
    """The manual's printed results for `dialect` (<dialect>.toml)."""
    return _load(dialect, f"{dialect}.toml", KEYS)


def load_handworked(dialect: str) -> list[Case]:
    """The hand-worked programs for `dialect` (handworked_<dialect>.toml)."""
    return _load(dialect, f"handworked_{dialect}.toml", HANDWORKED_KEYS)


def _load(dialect: str, name: str, keys: set[str]) -> list[Case]:
    path = HERE / name
    if not path.exists():
        return []
    data = toml.loads(path.read_text())
    cases = []
    for raw in data.get("case", []):
        unknown = set(raw) - keys
        if unknown:
            raise ValueError(f"{name} {raw.get('id')}: unknown keys {sorted(unknown)}")
        if ("duration" in raw) != ("tolerance" in raw):
            raise ValueError(f"{name} {raw.get('id')}: a duration needs its explicit tolerance (and back)")
        cases.append(Case(
            dialect=dialect, id=raw["id"], manual=raw["manual"], program=raw.get("program", ""),
            prints=raw.get("prints"),
            positions={str(k): int(v) for k, v in raw.get("positions", {}).items()},
            outputs={int(k): int(v) for k, v in raw.get("outputs", {}).items()},
            variables={str(k): v for k, v in raw.get("variables", {}).items()},
            inputs={int(k): int(v) for k, v in raw.get("inputs", {}).items()},
            device=[(c, r) for c, r in raw["device"]] if "device" in raw else None,
            targets=tuple(raw.get("targets", TARGETS)), stored=bool(raw.get("stored", False)),
            profile=raw.get("profile"),
            note=raw.get("note", ""), at_once=bool(raw.get("at_once", False)),
            output_order=[(int(n), int(v)) for n, v in raw["output_order"]] if "output_order" in raw else None,
            duration=float(raw["duration"]) if "duration" in raw else None,
            tolerance=float(raw["tolerance"]) if "tolerance" in raw else None,
            handworked=name.startswith("handworked_")))
    return cases


def exceptions() -> dict[tuple[str, str], str]:
    """(case id, target) -> reason, from exceptions.toml."""
    data = toml.loads((HERE / "exceptions.toml").read_text())
    out = {}
    for raw in data.get("exception", []):
        for target in raw.get("targets", TARGETS):
            out[(raw["id"], target)] = raw["reason"]
    return out


def lines(program: str) -> list[str]:
    return [line.strip() for line in program.strip().splitlines() if line.strip()]


# -- the simulator -----------------------------------------------------------------------------
def run_sim(case: Case) -> Outcome:
    from mcc.sim.files import simulate_file
    from mcc.sim.scenario import Scenario

    scenario = Scenario(inputs={k: float(v) for k, v in case.inputs.items()}) if case.inputs else None
    with tempfile.TemporaryDirectory() as folder:
        path = str(Path(folder) / f"case{EXTENSIONS[case.dialect]}")
        Path(path).write_text(case.program.strip() + "\n")
        profile = None
        if case.profile:
            from mcc.compiler.profiles import load as load_profile

            profile = load_profile(case.profile)
        simulated = simulate_file(path, case.dialect, profile=profile, scenario=scenario)
    trace = simulated.trace
    if trace is None:
        errors = "; ".join(f"{d.code} {d.message}" for d in simulated.result.diagnostics
                           if d.severity.value == "error")
        return Outcome(False, f"not simulated: {errors or 'see mcc sim'}")
    got_prints = [line.rstrip("\r") for _t, text in trace.prints for line in text.splitlines()]
    got = _observed(got_prints if case.prints is not None else None,
                    {a: round(p) for a, p in trace.axes.items()},
                    {int(k): int(v) for k, v in trace.outputs.items()},
                    {n: trace.variables.get(n) for n in case.variables},
                    [(int(e.data["output"]), int(e.data["value"])) for e in trace.events if e.kind == "output"],
                    trace.time)
    return Outcome(_matches(case, got), _show(got, trace.stopped if trace.stopped != "end" else ""))


# -- the virtual device ------------------------------------------------------------------------
def _device(case: Case):
    from mcc.link.device.virtual import make_device

    return make_device(case.dialect, profile=case.profile)


def replies(dialect: str, device, command: str, sent: list[str] | None = None) -> list[str]:
    """The lines a device answers to one command, without its echo and prompt (MCode, X150) or
    framing (Arcus: the command goes out as `@00<command>`); a refusal is kept, as `?...`. What a
    running program printed before the answer (the device sends it as it happens, before the
    echo) goes to `sent`."""
    if dialect == "arcus":
        raw = device.feed(f"@00{command}\r".encode()).decode(errors="replace")
        return [line for line in raw.split("\r") if line]
    raw = device.feed(f"{command}\r".encode()).decode(errors="replace")
    parts = raw.replace("\r\n", "\r").split("\r")
    echo = next((i for i, part in enumerate(parts) if part.strip() == command.strip()), None)
    if echo is not None:
        if sent is not None:
            sent += [part for part in parts[:echo] if part]
        parts = parts[echo + 1:]   # the echo
    # the prompt `>` (or MCode's `?` after a refused command, kept so the case shows the refusal)
    return [part for part in parts if part not in (">", "")]


# How a host knows the device is done: the program no longer runs and no axis moves (MCode BY and
# MV, lexium-mcode.txt L1828, L4424; X150 R, parker-x150.md L3224-L3240; Arcus SASTAT and PS,
# arcus-pmx-4ex-sa.txt L1626, L716).
def _idle(dialect: str, device, sent: list[str]) -> bool:
    if getattr(device, "program_mode", False) or any(u.defining is not None for u in getattr(device, "units", {}).values()):
        return True   # the host is storing a program (PG, XD): it sends the next line, it does not poll
    if dialect == "mcode":
        return all(replies(dialect, device, f"PR {flag}", sent) == ["0"] for flag in ("BY", "MV"))
    if dialect == "x150":
        return all(replies(dialect, device, f"{a}R", sent) in (["*R"], ["*S"]) for a in device.units)
    return replies(dialect, device, "SASTAT") != ["1"] and set(replies(dialect, device, "PS")[0].split(":")) == {"0"}


TYPING = 5.0   # seconds a person typing a manual's session waits for the motor before the next line


def wait_until_idle(dialect: str, device, sent: list[str], step: float = 0.01, limit: float | None = None) -> None:
    """Wait as a host does: ask whether the device is done, and while it is not, wait `step`
    seconds (the host's sleep, `device.elapse`) and ask again, up to `limit` seconds, by default
    the device's run limit (a program still running then is held, as `mcc sim` stops at its time
    limit)."""
    from mcc.link.device.machine import RUN_LIMIT

    for _poll in range(int(((RUN_LIMIT + 1) if limit is None else limit) / step)):
        if _idle(dialect, device, sent):
            return
        device.elapse(step)


def run_device(case: Case) -> Outcome:
    device = _device(case)
    if case.inputs:
        device.sim.machine.inputs.update({k: float(v) for k, v in case.inputs.items()})
    got_prints: list[str] = []
    changes: list[tuple[int, int]] = []
    def record() -> None:
        """The output changes of every run the commands started, in the order they happened."""
        events = sorted((e.t, n, i, e.data) for n, trace in enumerate(device.sim.traces)
                        for i, e in enumerate(trace.events) if e.kind == "output")
        changes.extend((int(data["output"]), int(data["value"])) for _t, _n, _i, data in events)

    if case.stored:
        device.load_program(case.program.strip() + "\n", "case")
        started = replies(case.dialect, device, "SR=1")
        if started != _ack(case.dialect):
            return Outcome(False, f"SR=1 -> {started!r}")
        exchange = list(case.device or [])
    else:
        exchange = case.device if case.device is not None else [(c, None) for c in lines(case.program)]
    for command, reply in exchange:
        if not case.at_once:
            wait_until_idle(case.dialect, device, got_prints, limit=TYPING)
        answer = replies(case.dialect, device, command, got_prints)
        if reply is None:
            got_prints += answer
        elif answer != ([reply] if reply else _ack(case.dialect)):
            return Outcome(False, f"{command!r} -> {answer!r}, the manual: {reply!r}")
    # the host waits for the programs and moves it started to end before it reads the results
    wait_until_idle(case.dialect, device, got_prints)
    record()
    positions = {}
    for axis in case.positions:
        answer = replies(case.dialect, device, _position_command(case.dialect, axis))
        text = answer[-1] if answer else ""
        try:
            positions[axis] = int(text.replace("*", "").replace(" ", ""))
        except ValueError:
            positions[axis] = text
    outputs = {n: int(device.sim.machine.outputs.get(n, 0)) for n in case.outputs}
    variables = {}
    for name in case.variables:
        answer = replies(case.dialect, device, _variable_query(case.dialect, name))
        variables[name] = _number(answer[-1] if answer else "")
    # With an explicit exchange, its replies were the check of what the device answers.
    checked = case.prints is not None and case.device is None
    start = device.sim.first_program if device.sim.first_program is not None else device.sim.first_start
    duration = max(device.sim.busy_until, start) - start if start is not None else 0.0
    got = _observed(got_prints if checked else None, positions, outputs, variables, changes, duration)
    return Outcome(_matches(case, got, prints=checked), _show(got))


def _ack(dialect: str) -> list[str]:
    return ["OK"] if dialect == "arcus" else []


def _position_command(dialect: str, axis: str) -> str:
    return {"mcode": "PR P", "x150": f"{axis}PR", "arcus": f"P{axis}"}[dialect]


# -- comparing ---------------------------------------------------------------------------------
def _variable_query(dialect: str, name: str) -> str:
    return {"mcode": f"PR {name}", "x150": f"1{name}", "arcus": name}[dialect]


def _number(text: str):
    try:
        return float(text.replace("*", "").strip())
    except ValueError:
        return text


def _observed(prints, positions, outputs, variables=None, changes=None, duration=None) -> dict:
    return {"prints": prints, "positions": positions, "outputs": outputs, "variables": variables or {},
            "output_order": changes or [], "duration": duration}


def _matches(case: Case, got: dict, prints: bool = True) -> bool:
    if prints and case.prints is not None and got["prints"] != case.prints:
        return False
    if any(got["positions"].get(a, 0) != p for a, p in case.positions.items()):
        return False
    if any(got["variables"].get(n) != v for n, v in case.variables.items()):
        return False
    if case.output_order is not None and got["output_order"] != case.output_order:
        return False
    if case.duration is not None and (got["duration"] is None
                                      or abs(got["duration"] - case.duration) > case.tolerance + 1e-9):
        return False
    return all(got["outputs"].get(n, 0) == v for n, v in case.outputs.items())


def _show(got: dict, stopped: str = "") -> str:
    parts = []
    if got["prints"] is not None:
        parts.append("prints " + repr(got["prints"]))
    if got["positions"]:
        parts.append("positions " + repr(got["positions"]))
    if got["outputs"]:
        parts.append("outputs " + repr(got["outputs"]))
    if got["variables"]:
        parts.append("variables " + repr(got["variables"]))
    if got.get("output_order"):
        parts.append("output changes " + repr(got["output_order"]))
    if got.get("duration") is not None:
        parts.append(f"duration {got['duration']:.6f} s")
    if stopped:
        parts.append(f"stopped: {stopped}")
    return ", ".join(parts)


def run(case: Case, target: str) -> Outcome:
    if target not in case.targets:
        raise ValueError(f"{case.id} does not apply to {target}")
    return run_sim(case) if target == "sim" else run_device(case)


def all_cases() -> list[Case]:
    """Every case: the manuals' printed results, then the hand-worked programs."""
    return [case for dialect in DIALECTS for case in load(dialect) + load_handworked(dialect)]
