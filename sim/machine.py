"""The machine a program drives: axes with their settings and motion, inputs and outputs.

Positions are the axis's commanded position in the IR's steps; `offset` turns them into machine
coordinates (where the scenario's home and limit switches are): machine = position + offset.
Homing and setting the position change the offset, never the machine coordinate.
"""

from __future__ import annotations

import math
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
    # (position, offset, motions begun) when its last homing ended: a homing that finds the axis
    # still there, nothing having moved since, does nothing (interpreter._home)
    homed: tuple | None = None
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

    def own(self, param: MotionParam, fallback: dict) -> bool:
        """Whether the axis runs with its own value of `param`: one it set, and for a parameter of
        the module's axis sets (`Module.axis_sets`, Arcus L447-L457) only once it set all of them."""
        sets = fallback.get("sets", ())
        if param in sets:
            return all(p in self.settings for p in sets)
        return param in self.settings

    def setting(self, param: MotionParam, fallback: dict[str, dict[MotionParam, float]]) -> float:
        if self.own(param, fallback):
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
        sets = fallback.get("sets", ())
        complete = not sets or all(p in self.settings for p in sets)
        by_time = self.ramp_by_time if complete else {}  # an incomplete set ramps as the global ACC says
        if by_time.get("accel", shared.get("accel", False)):
            ramp = get(MotionParam.ACCEL_TIME)
            accel = abs(maximum - initial) / ramp if ramp > 0 else 0.0
        if by_time.get("decel", shared.get("decel", False)):
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
    # settings written for every axis ("*"), read by an axis without its own; "sets": the module's
    # axis sets (the parameters an axis uses its own values of only once it set them all)
    shared: dict = field(default_factory=lambda: {"*": {}, "*ramp": {}, "defaults": defaults(0), "sets": ()})
    # the countdown timer (Arcus TR, L789-L793): (when it was loaded, the seconds loaded), in the
    # run's time; it counts down in ticks of `countdown_tick` seconds (TR counts milliseconds)
    countdown: tuple[float, float] = (0.0, 0.0)
    countdown_tick: float = 0.001

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
            if param in self.shared.get("sets", ()):
                targets = []  # a separate register: the axes keep their own values
        for target in targets:
            target.settings[param] = value
        kind = {MotionParam.ACCEL: ("accel", False), MotionParam.ACCEL_TIME: ("accel", True),
                MotionParam.DECEL: ("decel", False), MotionParam.DECEL_TIME: ("decel", True)}.get(param)
        if kind is not None:
            if axis == "*":
                self.shared["*ramp"][kind[0]] = kind[1]
            for target in targets:
                target.ramp_by_time[kind[0]] = kind[1]

    def load_countdown(self, now: float, seconds: float) -> None:
        """Load the countdown timer (Arcus TR=n, L789-L793): from `now` it counts down to 0."""
        self.countdown = (now, max(0.0, seconds))

    def countdown_left(self, now: float) -> float:
        """What the countdown timer reads at `now`: the time loaded less the whole ticks elapsed
        (it counts in milliseconds, L791), never below 0."""
        start, loaded = self.countdown
        tick = self.countdown_tick
        ticks = math.floor((now - start) / tick + 1e-9)
        return max(0.0, round(loaded - ticks * tick, 9))

    def countdown_end(self) -> float:
        """When the countdown timer reaches 0 (after the tick that takes it there)."""
        start, loaded = self.countdown
        return start + math.ceil(loaded / self.countdown_tick - 1e-9) * self.countdown_tick

    def register(self, param: MotionParam, axis: str) -> float:
        """The value written for `axis` (or for every axis, "*") as the program reads it back: the
        register itself where the axes' own settings form a set (Arcus HSPDX reads HSPDX, HSPD the
        global HSPD, L1552-L1560); otherwise, and before any write, the value in force."""
        if param in self.shared.get("sets", ()):
            if axis == "*":
                return self.shared["*"].get(param, self.shared["defaults"].get(param, 0.0))
            own = self.axis(axis).settings.get(param)
            if own is not None:
                return own
        return self.axis(axis).setting(param, self.shared)

    def input_mask(self) -> int:
        return sum(1 << (n - 1) for n, v in self.inputs.items() if v and n >= 1)

    def output_mask(self) -> int:
        return sum(1 << (n - 1) for n, v in self.outputs.items() if v and n >= 1)
