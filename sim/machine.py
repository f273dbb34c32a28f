"""The machine a program drives: axes with their settings and motion, inputs and outputs.

Positions are the axis's commanded position in the IR's steps; `offset` turns them into machine
coordinates (where the scenario's home and limit switches are): machine = position + offset.
Homing and setting the position change the offset, never the machine coordinate.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from mcc.compiler.ir import MotionParam
from mcc.compiler.profiles import power_up
from mcc.sim.motion import Limits, Motion



def defaults(steps_per_rev: int, profile=None) -> dict[MotionParam, float]:
    """The settings an axis starts with when the program sets none: the product's power-up values
    (`[machine.defaults]` of its profile, else mcc's fallback; compiler/profiles.py `power_up`),
    in the IR's steps."""
    return {MotionParam(name): value for name, value in power_up(profile, steps_per_rev).items()}


@dataclass
class Axis:
    name: str
    position: float = 0.0  # when idle; while moving, `motion` says where the axis is
    offset: float = 0.0
    motion: Motion | None = None
    settings: dict[MotionParam, float] = field(default_factory=dict)
    # which of accel / accel_time (decel / decel_time) was set last: a ramp time is turned into an
    # acceleration with the speeds in force when the move starts
    ramp_by_time: dict[str, bool] = field(default_factory=dict)
    fault: int = 0
    stalled: int = 0  # 1 after the scenario stalled the axis
    enabled: int = 1
    on_end: str = ""  # "home": the position becomes 0 when the motion ends
    home_accel: float | None = None  # X150 GA: homing ramps at it rather than at the move acceleration
    home_final_speed: float | None = None  # the home_final_speed setting: the creep runs at it
    homing: object = None  # the homing in progress (interpreter.HomeRun), while on_end is "home"
    cached: Limits | None = None  # the limits in force, until a setting changes

    def at(self, t: float) -> float:
        if self.motion is None:
            return self.position
        return self.motion.positions(t)[self.name]

    def speed(self, t: float) -> float:
        if self.motion is None:
            return 0.0
        s = self.motion.distance(t)
        return self.motion.speed(t) * self.motion.path.axis_rate(self.name, s)

    def moving(self, t: float) -> bool:
        return self.motion is not None and t < self.motion.t_end

    def setting(self, param: MotionParam, fallback: dict[str, dict[MotionParam, float]]) -> float:
        if param in self.settings:
            return self.settings[param]
        shared = fallback.get("*", {})
        if param in shared:
            return shared[param]
        return fallback["defaults"].get(param, 0.0)

    def limits(self, fallback: dict[str, dict[MotionParam, float]]) -> Limits:
        if self.cached is None:
            self.cached = self._limits(fallback)
        return self.cached

    def _limits(self, fallback: dict[str, dict[MotionParam, float]]) -> Limits:
        get = lambda p: self.setting(p, fallback)  # noqa: E731
        initial, maximum = get(MotionParam.INITIAL_SPEED), get(MotionParam.MAX_SPEED)
        accel, decel = get(MotionParam.ACCEL), get(MotionParam.DECEL)
        shared = fallback.get("*ramp", {})
        if self.ramp_by_time.get("accel", shared.get("accel", False)):
            ramp = get(MotionParam.ACCEL_TIME)
            accel = abs(maximum - initial) / ramp if ramp > 0 else 0.0
        if self.ramp_by_time.get("decel", shared.get("decel", False)):
            ramp = get(MotionParam.DECEL_TIME)
            decel = abs(maximum - initial) / ramp if ramp > 0 else 0.0
        return Limits(initial, maximum, accel, decel, smooth=get(MotionParam.PROFILE) == 1)


@dataclass
class Machine:
    axes: dict[str, Axis] = field(default_factory=dict)
    inputs: dict[int, int] = field(default_factory=dict)
    analog: dict[int, float] = field(default_factory=dict)
    outputs: dict[int, int] = field(default_factory=dict)
    home_inputs: set[int] = field(default_factory=set)  # inputs set up as the home switch (input_function "home")
    # settings written for every axis ("*"), read by an axis without its own
    shared: dict[str, dict] = field(default_factory=lambda: {"*": {}, "*ramp": {}, "defaults": defaults(0)})

    def axis(self, name: str) -> Axis:
        found = self.axes.get(name)
        if found is None:
            found = self.axes[name] = Axis(name)
        return found

    def set_motion(self, param: MotionParam, axis: str, value: float) -> None:
        for each in self.axes.values():
            each.cached = None
        targets = [self.axis(axis)] if axis != "*" else list(self.axes.values())
        if axis == "*":
            self.shared["*"][param] = value
        for target in targets:
            target.settings[param] = value
        kind = {MotionParam.ACCEL: ("accel", False), MotionParam.ACCEL_TIME: ("accel", True),
                MotionParam.DECEL: ("decel", False), MotionParam.DECEL_TIME: ("decel", True)}.get(param)
        if kind is not None:
            if axis == "*":
                self.shared["*ramp"][kind[0]] = kind[1]
            for target in targets:
                target.ramp_by_time[kind[0]] = kind[1]

    def input_mask(self) -> int:
        return sum(1 << (n - 1) for n, v in self.inputs.items() if v and n >= 1)

    def output_mask(self) -> int:
        return sum(1 << (n - 1) for n, v in self.outputs.items() if v and n >= 1)
