"""The envelope of each axis, read from `[tool.mcc.axes.<axis>]` (project configuration) and from a
profile's `[envelope.<axis>]` (a profile's `axes` key is already the list of its logical axes).

Everything is converted to the IR's units once, here: positions in steps, speeds in steps/s,
accelerations in steps/s². A table gives its lengths in `unit` = "steps" (the default), "mm" or
"deg"; "mm" needs `steps-per-mm`, or `steps-per-rev` and `lead` (mm per revolution); "deg" needs
`steps-per-rev` (360 degrees a revolution). docs/CONFIGURATION.md, "Envelope", has every key.
"""

from __future__ import annotations

from dataclasses import dataclass, fields, replace
from typing import Any

from mcc.compiler.suggest import close_matches

KEYS = ("unit", "min", "max", "home", "max-speed", "max-accel", "must-home", "steps-per-mm", "steps-per-rev",
        "lead")
UNITS = ("steps", "mm", "deg")
NUMBERS = ("min", "max", "home", "max-speed", "max-accel", "steps-per-mm", "steps-per-rev", "lead")


@dataclass(frozen=True)
class AxisEnvelope:
    """One axis's envelope in IR units; None where the configuration does not say."""

    axis: str
    min: float | None = None  # steps
    max: float | None = None  # steps
    home: float | None = None  # steps: the position homing leaves the axis at
    max_speed: float | None = None  # steps/s
    max_accel: float | None = None  # steps/s²
    must_home: bool = False  # a move before a homing of this axis is reported (G304)
    unit: str = "steps"  # how the user wrote it: messages print positions in this unit too
    scale: float = 1.0  # steps per `unit`

    def shown(self, steps: float) -> str:
        """A position in the user's unit, with the steps beside it when that is not steps."""
        if self.unit == "steps":
            return f"{steps:g}"
        return f"{steps / self.scale:g} {self.unit} ({steps:g} steps)"

    def merged(self, over: "AxisEnvelope") -> "AxisEnvelope":
        """This envelope with every key `over` gives replaced (the project's table over a profile's)."""
        changes = {f.name: getattr(over, f.name) for f in fields(over)
                   if f.name not in ("axis", "must_home") and getattr(over, f.name) is not None}
        changes["must_home"] = over.must_home or self.must_home
        return replace(self, **changes)


def parse(table: Any, where: str = "axes") -> tuple[dict[str, AxisEnvelope], list[tuple[tuple[str, ...], str, str]]]:
    """The envelopes of a `{axis: {key: value}}` table, and its problems as (keys, code, message):
    G102 for a key mcc does not know, G103 for a value it cannot use."""
    problems: list[tuple[tuple[str, ...], str, str]] = []
    out: dict[str, AxisEnvelope] = {}
    if not isinstance(table, dict):
        return out, [((where,), "G103", f"'{where}' must be a table of axes: [{where}.X] min = 0 ...")]
    for axis, raw in table.items():
        keys = (where, str(axis))
        if not isinstance(raw, dict):
            problems.append((keys, "G103", f"'{where}.{axis}' must be a table (min, max, max-speed, ...)"))
            continue
        envelope = parse_axis(str(axis), raw, keys, problems)
        if envelope is not None:
            out[str(axis)] = envelope
    return out, problems


def parse_axis(axis: str, raw: dict, keys: tuple[str, ...], problems: list) -> AxisEnvelope | None:
    bad = len(problems)
    for key in raw:
        if key not in KEYS:
            near = close_matches(key.replace("_", "-"), KEYS, n=1, cutoff=0.6)
            hint = f"; did you mean '{near[0]}'?" if near else f" (known keys: {', '.join(KEYS)})"
            problems.append(((*keys, key), "G102", f"unknown envelope key '{key}'{hint}"))
    values: dict[str, float] = {}
    for key in NUMBERS:
        value = raw.get(key)
        if value is None:
            continue
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            problems.append(((*keys, key), "G103", f"'{key}' must be a number, not {value!r}"))
        elif key in ("max-speed", "max-accel", "steps-per-mm", "steps-per-rev", "lead") and value <= 0:
            problems.append(((*keys, key), "G103", f"'{key}' must be greater than 0, not {value!r}"))
        else:
            values[key] = float(value)
    must_home = raw.get("must-home", False)
    if not isinstance(must_home, bool):
        problems.append(((*keys, "must-home"), "G103", f"'must-home' must be true or false, not {must_home!r}"))
        must_home = False
    unit = raw.get("unit", "steps")
    if unit not in UNITS:
        problems.append(((*keys, "unit"), "G103", f"'unit' must be one of {', '.join(UNITS)}, not {unit!r}"))
        return None
    scale = scale_of(unit, values, keys, problems)
    if "min" in values and "max" in values and values["min"] > values["max"]:
        problems.append(((*keys, "min"), "G103", f"'min' ({values['min']:g}) is above 'max' ({values['max']:g})"))
    if len(problems) > bad and any(p[1] == "G103" for p in problems[bad:]) or scale is None:
        return None

    def steps(key: str) -> float | None:
        return values[key] * scale if key in values else None

    return AxisEnvelope(axis, steps("min"), steps("max"), steps("home"), steps("max-speed"), steps("max-accel"),
                        must_home, unit, scale)


def scale_of(unit: str, values: dict[str, float], keys: tuple[str, ...], problems: list) -> float | None:
    """Steps per `unit`."""
    if unit == "steps":
        return 1.0
    if unit == "mm":
        if "steps-per-mm" in values:
            return values["steps-per-mm"]
        if "steps-per-rev" in values and "lead" in values:
            return values["steps-per-rev"] / values["lead"]
        problems.append(((*keys, "unit"), "G103", "unit = \"mm\" needs 'steps-per-mm', or 'steps-per-rev' and "
                                                  "'lead' (mm per revolution)"))
        return None
    if "steps-per-rev" in values:
        return values["steps-per-rev"] / 360.0
    problems.append(((*keys, "unit"), "G103", "unit = \"deg\" needs 'steps-per-rev'"))
    return None


def envelopes(profile: Any, configured: tuple[tuple[str, AxisEnvelope], ...] = ()) -> dict[str, AxisEnvelope]:
    """Each axis's envelope: the profile's `[envelope]` with the project's `[tool.mcc.axes]` over it."""
    out: dict[str, AxisEnvelope] = {}
    table = profile.get("envelope") if profile is not None else None
    if table:
        out, _ = parse(table, "envelope")  # a profile's problems are reported when it is loaded
    for axis, envelope in configured:
        out[axis] = out[axis].merged(envelope) if axis in out else envelope
    return out


def profile_problems(profile_data: dict) -> list[str]:
    """The messages of a profile's `[envelope]` problems (profiles.load raises on them)."""
    if "envelope" not in profile_data:
        return []
    _, problems = parse(profile_data["envelope"], "envelope")
    return [f"{'.'.join(keys)}: {message}" for keys, _, message in problems]
