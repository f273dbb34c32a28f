"""Target profiles: what a program is compiled and checked for.

A profile is a small TOML file: dialect, product, firmware, logical axes, steps per revolution,
limits (line length, memory budgets) and dialect-specific settings such as the Arcus cost model.
Built-in profiles live in `compiler/profiles/`; a user may pass a path to their own file, which
may `extends = "<built-in name>"` and override any key.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import lru_cache
from pathlib import Path
from typing import Any

from mcc.compiler import toml

PROFILE_DIR = Path(__file__).parent / "profiles"


class ProfileError(Exception):
    """A profile that does not exist or cannot be read; the CLI reports it as a usage error."""


@dataclass(frozen=True)
class Profile:
    name: str
    dialect: str
    product: str
    title: str = ""
    firmware: str = ""
    axes: tuple[str, ...] = ()
    steps_per_rev: int = 0
    data: dict = field(default_factory=dict, compare=False, hash=False)

    def get(self, dotted: str, default: Any = None) -> Any:
        """Look up a key such as "limits.line_length" in the profile's data."""
        node: Any = self.data
        for part in dotted.split("."):
            if not isinstance(node, dict) or part not in node:
                return default
            node = node[part]
        return node


# The motion settings an axis has at power-up when the profile's `[machine.defaults]` does not
# give them: mcc's fallback, per motor revolution (docs/SIMULATOR.md, "Defaults").
FALLBACK_POWER_UP_PER_REV = {"initial_speed": 0.0, "max_speed": 1.0, "accel": 10.0, "decel": 10.0}
STEPS_PER_REV_UNKNOWN = 1000  # the step size assumed when a module does not know its own
SCALED_SETTINGS = ("initial_speed", "max_speed", "accel", "decel")  # steps/s or steps/s² (or revs)
PLAIN_SETTINGS = ("profile",)  # plain numbers (0 trapezoidal, 1 S-curve)


def power_up(profile: "Profile | None", steps_per_rev: int) -> dict[str, float]:
    """The motion settings in force at power-up, in steps of `steps_per_rev` per revolution, keyed
    by `ir.MotionParam` value: the profile's `[machine.defaults]` (in its `unit`, "steps" or
    "revs") where it gives them, else FALLBACK_POWER_UP_PER_REV. One table, read by the simulator,
    the virtual device and cross-dialect compilation (which writes the source's settings where the
    target powers up with others)."""
    scale = steps_per_rev if steps_per_rev > 0 else STEPS_PER_REV_UNKNOWN
    out = {name: value * scale for name, value in FALLBACK_POWER_UP_PER_REV.items()}
    out["profile"] = 0
    table = profile.get("machine.defaults", {}) if profile is not None else {}
    if not isinstance(table, dict) or table.get("unit", "steps") not in ("steps", "revs"):
        return out  # a table in no known unit is not guessed at
    per = 1 if table.get("unit", "steps") == "steps" else scale
    for name in SCALED_SETTINGS:
        value = table.get(name)
        if isinstance(value, (int, float)) and not isinstance(value, bool):
            out[name] = float(value) * per
    for name in PLAIN_SETTINGS:
        value = table.get(name)
        if isinstance(value, (int, float)) and not isinstance(value, bool):
            out[name] = value
    return out


def _merge(base: dict, over: dict) -> dict:
    out = dict(base)
    for key, value in over.items():
        if isinstance(value, dict) and isinstance(out.get(key), dict):
            out[key] = _merge(out[key], value)
        else:
            out[key] = value
    return out


def _read(path: Path) -> dict:
    from mcc.compiler.files import read_bytes  # only regular files: a FIFO named as a profile never blocks

    try:
        if path.parent == PROFILE_DIR:  # a built-in profile: parsed once, then read from the cache
            data = toml.load_data_file(path)
        else:
            data = toml.loads(read_bytes(str(path)).decode("utf-8"))
    except (OSError, UnicodeDecodeError) as exc:
        raise ProfileError(f"cannot read profile {path}: {exc}") from None
    except toml.TOMLDecodeError as exc:
        raise ProfileError(f"{path}: invalid TOML: {exc}") from None
    parent = data.pop("extends", None)
    if parent:
        data = _merge(_read(_builtin_path(parent)), data)
    return data


def _builtin_path(name: str) -> Path:
    path = PROFILE_DIR / f"{name}.toml"
    if not path.exists():
        raise ProfileError(f"unknown profile '{name}' (built-in profiles: {', '.join(builtin_names())})")
    return path


def builtin_names() -> list[str]:
    return sorted(p.stem for p in PROFILE_DIR.glob("*.toml"))


def load(name_or_path: str) -> Profile:
    """A built-in profile by name (read once per process) or a user profile by path."""
    path = Path(name_or_path)
    if path.suffix != ".toml" and not path.exists():
        return _load_builtin(name_or_path)
    return _load(name_or_path)


@lru_cache(maxsize=None)
def _load_builtin(name: str) -> Profile:
    return _load(name)


def _load(name_or_path: str) -> Profile:
    path = Path(name_or_path)
    if path.suffix == ".toml" or path.exists():
        if not path.exists():
            raise ProfileError(f"profile file not found: {name_or_path}")
        data = _read(path)
        default_name = path.stem
    else:
        data = _read(_builtin_path(name_or_path))
        default_name = name_or_path
    for key in ("dialect", "product"):
        if key not in data:
            raise ProfileError(f"profile {name_or_path}: missing key '{key}'")
    from mcc.compiler.envelope.axes import profile_problems

    problems = profile_problems(data)
    if problems:
        raise ProfileError(f"profile {name_or_path}: {problems[0]}")
    return Profile(
        name=data.get("name", default_name),
        dialect=data["dialect"],
        product=data["product"],
        title=data.get("title", ""),
        firmware=str(data.get("firmware", "")),
        axes=tuple(str(a) for a in data.get("axes", ())),
        steps_per_rev=int(data.get("steps_per_rev", 0)),
        data=data,
    )
