"""What a product's homing command does, read from its profile's `[homing]` table.

The three dialects home differently (docs/SIMULATOR.md, "Homing", has the manuals' lines): MCode
`HM` creeps back off the switch at VI and leaves the counter alone, Arcus `HOME` zeroes the
counter at the switch and ramps down past it, X150 `GH` reverses onto the switch edge at GHF and
zeroes there. The lowering writes the product's homing into each `ir.Home` (`home_op`), so the
simulator runs only what the IR says; a backend asks `refusal` whether its dialect's homing
command does what an `ir.Home` says, and refuses the conversion (G003) when it does not: a
conversion that moves the machine's zero or where the axis stops is a different program.

Profile keys (`[homing]`, and `[homing.methods.<method>]` for what one homing method, an
`ir.Home.method`, does otherwise):

- `creep`: "written" (the command's type says the creep direction: MCode HM 1-4), "reverse"
  (back onto the switch, against the seek: X150 GH), "none" (no creep: Arcus HOME);
- `creep_speed`: "initial" (the initial speed in force: MCode VI) or a speed in rev/s (X150's GHF
  default 0.1);
- `zero`: "switch" (the counter becomes 0 as the switch trips), "end" (where the homing stops),
  "none" (the counter keeps counting);
- `accel`: the seek's and the brake's ramp in rev/s² (X150's GA default 10), a program's own
  setting (GA) replacing it; absent: the move ramps in force;
- `input`: true when the command fails unless an input is set up as the home switch (MCode
  `IS=n,1,a`, Error 80 "HOME Sw. not defined").
"""

from __future__ import annotations

from dataclasses import dataclass

from mcc.compiler import ir
from mcc.compiler.profiles import Profile

CREEPS = ("written", "reverse", "none")


@dataclass(frozen=True)
class Model:
    creep: str = "reverse"
    creep_speed: float | None = None  # rev/s; None: the initial speed in force
    zero: str = "end"
    accel: float | None = None  # rev/s²; None: the move ramps in force
    input: bool = False  # the homing fails unless an input is set up as the home switch


def _positive(value) -> float | None:
    if isinstance(value, (int, float)) and not isinstance(value, bool) and value > 0:
        return float(value)
    return None


def model(profile: Profile, method: str = "switch") -> Model:
    """The profile's homing by `method` (its `[homing.methods.<method>]` keys over `[homing]`);
    a value the table does not allow falls back to the default."""
    base, own = profile.get("homing"), profile.get(f"homing.methods.{method}")
    table = {k: v for k, v in (base.items() if isinstance(base, dict) else ()) if k != "methods"}
    table.update(own if isinstance(own, dict) else {})
    creep = str(table.get("creep", "reverse"))
    zero = str(table.get("zero", "end"))
    return Model(creep if creep in CREEPS else "reverse", _positive(table.get("creep_speed", "initial")),
                 zero if zero in ir.HOME_ZEROS else "end", _positive(table.get("accel")), table.get("input") is True)


def home_op(profile: Profile, steps_per_rev: int, axis: str, method: str, direction: int, span=None,
            written_creep: int = 0, speed: ir.Expr | None = None) -> ir.Home:
    """The `ir.Home` of the product's homing command seeking in `direction`; `written_creep` is
    the creep direction the command's type gives (MCode HM n)."""
    found = model(profile, method)
    creep = {"written": written_creep, "reverse": -direction, "none": 0}[found.creep]
    creep_speed = None
    if creep and found.creep_speed is not None:
        creep_speed = ir.Const(found.creep_speed * (steps_per_rev or 1), ir.Unit.STEPS_PER_S, span)
    accel = None
    if found.accel is not None:
        accel = ir.Const(found.accel * (steps_per_rev or 1), ir.Unit.STEPS_PER_S2, span)
    return ir.Home(axis, method, direction, span=span, creep=creep, speed=speed, creep_speed=creep_speed,
                   zero=found.zero, accel=accel, needs_input=found.input)


def refusal(op: ir.Home, profile: Profile, source_steps_per_rev: int) -> str:
    """Why the target's homing command would not do what `op` says ("" when it does): a different
    zero, a creep off the switch or none, another creep direction or speed."""
    target = model(profile, op.method)
    name = profile.dialect
    if op.zero != target.zero:
        return (f"the source's homing {_ZERO[op.zero]}, {name}'s {_ZERO[target.zero]}: the machine's zero would "
                "move; home in the target's own way, or compile to the source's dialect")
    creep = {"written": op.creep, "reverse": -op.direction, "none": 0}[target.creep]
    if target.creep == "written" and op.creep == 0:
        creep = None
    if creep != op.creep:
        return (f"the source's homing {_creep(op.creep)}, {name}'s {_creep(creep)}: the axis would stop "
                "elsewhere; compile to the source's dialect")
    if op.creep and not _same_speed(op.creep_speed, target.creep_speed, source_steps_per_rev):
        return (f"the source's homing creeps off the switch at {_speed(op.creep_speed, source_steps_per_rev)}, "
                f"{name}'s at {_speed_rev(target.creep_speed)}: the homing would take another time")
    if not _same_speed(op.accel, target.accel, source_steps_per_rev):
        return (f"the source's homing ramps at {_accel(op.accel, source_steps_per_rev)}, {name}'s at "
                f"{_accel_rev(target.accel)}: the axis would stop elsewhere past the switch")
    return ""


def _accel(accel: ir.Expr | None, steps_per_rev: int) -> str:
    if accel is None:
        return "the move ramps"
    if isinstance(accel, ir.Const):
        return _accel_rev(float(accel.value) / (steps_per_rev or 1))
    return "a computed acceleration"


def _accel_rev(rev_s2: float | None) -> str:
    return "the move ramps" if rev_s2 is None else f"{rev_s2:g} rev/s²"


_ZERO = {"switch": "zeroes the counter as the switch trips", "end": "zeroes the counter where it stops",
         "none": "leaves the counter alone"}


def _creep(direction: int | None) -> str:
    if direction is None:
        return "always creeps off the switch"
    if not direction:
        return "does not creep off the switch"
    return "creeps off the switch in " + ("+" if direction > 0 else "-")


def _same_speed(speed: ir.Expr | None, rev_s: float | None, steps_per_rev: int) -> bool:
    if speed is None or rev_s is None:
        return speed is None and rev_s is None
    if not isinstance(speed, ir.Const):
        return False
    return abs(float(speed.value) / (steps_per_rev or 1) - rev_s) <= 1e-6 * max(1.0, rev_s)


def _speed(speed: ir.Expr | None, steps_per_rev: int) -> str:
    if speed is None:
        return "the initial speed"
    if isinstance(speed, ir.Const):
        return _speed_rev(float(speed.value) / (steps_per_rev or 1))
    return "a computed speed"


def _speed_rev(rev_s: float | None) -> str:
    return "the initial speed" if rev_s is None else f"{rev_s:g} rev/s"
