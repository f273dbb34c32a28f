"""What the passes share about the target: fixed facts of the PMX-4EX-SA and the profile's settings.

Kept apart so that the legaliser (which decides what can be written) and the writer (which writes
it) read the same tables, and the profile is read in one place.
"""

from __future__ import annotations

from dataclasses import dataclass

from mcc.compiler import ir
from mcc.compiler.profiles import Profile

DIALECT = "arcus"
# +limit, -limit, home and alarm inputs for each axis (arcus-pmx-4ex-sa.txt L333); DI1-DI8 are general
# inputs with no function to choose: none of these needs a set-up in the program (backends/input_setup.py)
DEDICATED_INPUTS = frozenset({"home", "limit_plus", "limit_minus", "general"})
AXES = ("X", "Y", "Z", "U")
# IR method -> ASCII homing mode (catalog home_mode); "limit" is LHOME, on the products that have it
HOME_KEYWORDS = {"switch": 0, "limit": 1, "switch+index": 2, "index": 3}
MOTION_IR = {ir.MotionParam.MAX_SPEED: "max_speed", ir.MotionParam.INITIAL_SPEED: "initial_speed",
             ir.MotionParam.ACCEL: "accel"}


@dataclass
class Config:
    """The `[arcus]` settings of a profile, with the defaults of the PMX-4EX-SA."""

    budget: int
    model: str
    calibrated: bool
    warn_fraction: float
    gui_limit: int  # the Windows software's limit on compiled lines (L1079); 0: not checked
    costs: dict[str, int]
    default_cost: int
    temporaries: list[int]
    sub_range: tuple[int, int]
    allocate_from: int
    axes: tuple[str, ...]
    max_copied: int
    variables: tuple[int, int] = (0, 63)  # the product's V numbers (`[arcus] variables`)

    @classmethod
    def from_profile(cls, profile: Profile) -> "Config":
        cost = profile.get("arcus.cost", {}) or {}
        temps = [int(v) for v in (profile.get("arcus.temporaries") or [60, 61, 62, 63])]
        rng = profile.get("arcus.subroutines") or [0, 31]
        axes = tuple(a for a in profile.axes if a in AXES) or AXES
        return cls(budget=int(cost.get("budget", 3230)), model=str(cost.get("model", "h-estimate")),
                   calibrated=bool(cost.get("calibrated", False)),
                   warn_fraction=float(cost.get("warn_fraction", 0.9)),
                   gui_limit=int(cost.get("gui_limit", 1785)),
                   costs={str(k).upper(): int(v) for k, v in (cost.get("statements") or {}).items()},
                   default_cost=int(cost.get("default", 1)), temporaries=temps,
                   sub_range=(int(rng[0]), int(rng[1])),
                   allocate_from=int(profile.get("arcus.allocate_subroutines_from", 1)), axes=axes,
                   max_copied=int(profile.get("arcus.loop_test_copy_max", 4)),
                   variables=tuple(int(v) for v in (profile.get("arcus.variables") or [0, 63]))[:2])

    def cost(self, key: str) -> int:
        return max(1, self.costs.get(key, self.default_cost))
