"""Scenarios: what the world does to the machine while a program runs (docs/SIMULATOR.md).

A scenario is a small TOML file:

```toml
until = 20.0                 # optional: the time limit (seconds), unless --until is given

[inputs]                     # input levels at t = 0 (an input not listed rests at its idle level: docs/SIMULATOR.md, "Inputs")
1 = 1

[analog]                     # analog input values (the device's counts)
1 = 512

[[events]]                   # at t = 0.5 s set input 2 to 1
at = 0.5
input = 2
value = 1

[[events]]                   # when axis X passes 4000 steps, set input 3 to 1
axis = "X"
passes = 4000
input = 3
value = 1

[axes.X]                     # switches on axis X, in steps
home = 1200                  # the home switch position (default 0)
limit_plus = 50000           # positive limit switch (default: none)
limit_minus = -50000

capture = 1                  # the capture input (default: the one the program sets up, else 1)

[[stall]]                    # axis X stalls at t = 2 s
at = 2.0
axis = "X"

[[fault]]                    # a drive fault at t = 3 s (on axis X; without `axis`, on every axis)
at = 3.0
axis = "X"

[[power]]                    # the main power is lost at t = 5 s
at = 5.0
```
"""

from __future__ import annotations

from dataclasses import dataclass, field

from mcc.compiler import toml


class ScenarioError(Exception):
    """A scenario file that cannot be read or does not have the documented shape."""


@dataclass(frozen=True)
class InputEvent:
    input: int
    value: int
    at: float | None = None  # a time, or
    axis: str = ""  # when `axis` passes `passes`
    passes: float = 0.0


@dataclass(frozen=True)
class AxisSwitches:
    home: float = 0.0
    limit_plus: float | None = None
    limit_minus: float | None = None


@dataclass(frozen=True)
class Incident:
    """Something that happens to the machine at a time: a stall, a drive fault, a power loss."""

    kind: str  # "stall" | "fault" | "power"
    at: float
    axis: str = ""  # "" : every axis (a fault) or none (a power loss)


INCIDENTS = ("stall", "fault", "power")


@dataclass
class Scenario:
    inputs: dict[int, int] = field(default_factory=dict)
    analog: dict[int, float] = field(default_factory=dict)
    events: list[InputEvent] = field(default_factory=list)
    axes: dict[str, AxisSwitches] = field(default_factory=dict)
    until: float | None = None
    name: str = "default"
    incidents: list[Incident] = field(default_factory=list)
    capture: int | None = None  # the capture input; None: the program's (input_function), else 1

    def switches(self, axis: str) -> AxisSwitches:
        return self.axes.get(axis, AxisSwitches())

    def inputs_driven(self) -> set[int]:
        return set(self.inputs) | {e.input for e in self.events}


def _number(value, where: str) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise ScenarioError(f"{where}: expected a number, got {value!r}")
    return value


def _index(key, where: str) -> int:
    try:
        index = int(key)
    except (TypeError, ValueError):
        raise ScenarioError(f"{where}: '{key}' is not an input number") from None
    if index < 1:
        raise ScenarioError(f"{where}: input numbers start at 1, got {index}")
    return index


def parse(text: str, name: str = "scenario") -> Scenario:
    try:
        data = toml.loads(text)
    except toml.TOMLDecodeError as exc:
        raise ScenarioError(f"{name}: invalid TOML: {exc}") from None
    known = {"until", "inputs", "analog", "events", "axes", "capture", *INCIDENTS}
    unknown = sorted(set(data) - known)
    if unknown:
        raise ScenarioError(f"{name}: unknown key '{unknown[0]}' (known: {', '.join(sorted(known))})")
    out = Scenario(name=name)
    if "until" in data:
        out.until = float(_number(data["until"], f"{name}: until"))
    for table, target in (("inputs", out.inputs), ("analog", out.analog)):
        raw = data.get(table, {})
        if not isinstance(raw, dict):
            raise ScenarioError(f"{name}: [{table}] must be a table of input number = value")
        for key, value in raw.items():
            target[_index(key, f"{name}: [{table}]")] = _number(value, f"{name}: [{table}] {key}")
    events = data.get("events", [])
    if not isinstance(events, list):
        raise ScenarioError(f"{name}: events must be an array of tables ([[events]])")
    for n, raw in enumerate(events, 1):
        where = f"{name}: event {n}"
        if not isinstance(raw, dict):
            raise ScenarioError(f"{where}: expected a table")
        if "input" not in raw or "value" not in raw:
            raise ScenarioError(f"{where}: needs 'input' and 'value'")
        index = _index(raw["input"], where)
        value = int(_number(raw["value"], f"{where}: value"))
        if "at" in raw:
            at = float(_number(raw["at"], f"{where}: at"))
            if at < 0:
                raise ScenarioError(f"{where}: 'at' must be >= 0")
            out.events.append(InputEvent(index, value, at=at))
        elif "axis" in raw and "passes" in raw:
            out.events.append(InputEvent(index, value, axis=str(raw["axis"]),
                                         passes=float(_number(raw["passes"], f"{where}: passes"))))
        else:
            raise ScenarioError(f"{where}: needs 'at' (seconds) or 'axis' and 'passes' (steps)")
    if "capture" in data:
        out.capture = _index(data["capture"], f"{name}: capture")
    for kind in INCIDENTS:
        raw_list = data.get(kind, [])
        if not isinstance(raw_list, list):
            raise ScenarioError(f"{name}: {kind} must be an array of tables ([[{kind}]])")
        for n, raw in enumerate(raw_list, 1):
            where = f"{name}: {kind} {n}"
            if not isinstance(raw, dict) or "at" not in raw:
                raise ScenarioError(f"{where}: needs 'at' (seconds)")
            extra = sorted(set(raw) - ({"at"} if kind == "power" else {"at", "axis"}))
            if extra:
                raise ScenarioError(f"{where}: unknown key '{extra[0]}'")
            if kind == "stall" and "axis" not in raw:
                raise ScenarioError(f"{where}: needs 'axis' (the axis that stalls)")
            at = float(_number(raw["at"], f"{where}: at"))
            if at < 0:
                raise ScenarioError(f"{where}: 'at' must be >= 0")
            out.incidents.append(Incident(kind, at, str(raw.get("axis", ""))))
    axes = data.get("axes", {})
    if not isinstance(axes, dict):
        raise ScenarioError(f"{name}: [axes.NAME] tables expected")
    for axis, raw in axes.items():
        if not isinstance(raw, dict):
            raise ScenarioError(f"{name}: [axes.{axis}] must be a table")
        extra = sorted(set(raw) - {"home", "limit_plus", "limit_minus"})
        if extra:
            raise ScenarioError(f"{name}: [axes.{axis}]: unknown key '{extra[0]}'")
        out.axes[str(axis)] = AxisSwitches(
            home=float(_number(raw.get("home", 0.0), f"{name}: axes.{axis}.home")),
            limit_plus=float(_number(raw["limit_plus"], "limit_plus")) if "limit_plus" in raw else None,
            limit_minus=float(_number(raw["limit_minus"], "limit_minus")) if "limit_minus" in raw else None)
    return out


def load(path: str) -> Scenario:
    try:
        with open(path, encoding="utf-8") as handle:
            text = handle.read()
    except (OSError, UnicodeDecodeError) as exc:
        raise ScenarioError(f"cannot read scenario {path}: {exc}") from None
    return parse(text, path)
