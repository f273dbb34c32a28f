"""Motion profiles, computed analytically.

A `Motion` moves a point along a path (a line through one or more axes, or a circular arc) with a
speed profile made of `Segment`s: a ramp from one speed to another, or a cruise at constant speed.
The position at any time, and the time at which the path passes a given distance, are computed in
closed form (or by bisection on a monotonic function), so the simulator never steps through time.

Profiles (docs/SIMULATOR.md, "Motion"):

- **trapezoidal**: the move starts at the initial speed, accelerates at `accel` to the maximum
  speed, cruises, and decelerates at `decel` back to the initial speed, where it stops. A move too
  short to reach the maximum speed has a triangular profile with the highest peak that fits.
- **S-curve**: the same phases, durations and distances, with the speed following a smoothstep
  (3u² − 2u³) instead of a straight line during each ramp: the jerk is finite and the move takes
  exactly as long as the trapezoidal one (mcc's decision; the dialects do not document their
  S-curve shapes).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

INF = math.inf


@dataclass(slots=True)
class Segment:
    """One phase of a profile: speed goes from v0 to v1 over `duration` (v0 == v1: cruise)."""

    t0: float  # start time (virtual seconds)
    duration: float  # may be INF for an endless cruise (slew)
    s0: float  # distance along the path at t0
    v0: float
    v1: float
    smooth: bool = False

    @property
    def t1(self) -> float:
        return self.t0 + self.duration

    @property
    def length(self) -> float:
        if self.duration == INF:
            return INF
        return (self.v0 + self.v1) / 2 * self.duration

    def distance(self, t: float) -> float:
        """Distance along the path at time t (t0 <= t <= t1)."""
        tau = t - self.t0
        if tau <= 0:
            return self.s0
        if self.v0 == self.v1 or self.duration == INF:
            return self.s0 + self.v0 * tau
        if tau >= self.duration:
            return self.s0 + self.length
        dv = self.v1 - self.v0
        if self.smooth:
            u = tau / self.duration
            return self.s0 + self.v0 * tau + dv * self.duration * (u ** 3 - u ** 4 / 2)
        return self.s0 + self.v0 * tau + dv * tau * tau / (2 * self.duration)

    def speed(self, t: float) -> float:
        tau = t - self.t0
        if self.v0 == self.v1 or self.duration == INF or self.duration <= 0:
            return self.v0
        u = min(max(tau / self.duration, 0.0), 1.0)
        if self.smooth:
            u = 3 * u * u - 2 * u ** 3
        return self.v0 + (self.v1 - self.v0) * u

    def time_at(self, s: float) -> float:
        """The time the path reaches distance s (s0 <= s <= s0 + length): distance is monotonic."""
        if s <= self.s0:
            return self.t0
        if self.v0 == self.v1 or self.duration == INF:
            return self.t0 + (s - self.s0) / self.v0 if self.v0 > 0 else INF
        lo, hi = self.t0, self.t1
        for _ in range(64):
            mid = (lo + hi) / 2
            if self.distance(mid) < s:
                lo = mid
            else:
                hi = mid
        return hi


@dataclass(slots=True)
class Path:
    """Where distance s along the path puts each axis."""

    start: dict[str, float]
    length: float  # INF for a slew
    # a line: unit direction per axis; an arc: centre, radius, start angle, signed sweep (radians)
    direction: dict[str, float] = field(default_factory=dict)
    arc: tuple[str, str, float, float, float, float, float] | None = None

    def at(self, s: float) -> dict[str, float]:
        if self.arc is None:
            return {axis: self.start[axis] + d * s for axis, d in self.direction.items()}
        ax, ay, cx, cy, radius, angle0, sweep = self.arc
        angle = angle0 + math.copysign(s / radius, sweep) if radius > 0 else angle0
        return {ax: cx + radius * math.cos(angle), ay: cy + radius * math.sin(angle)}

    def axis_rate(self, axis: str, s: float) -> float:
        """d(axis position)/d(distance) at s: the share of the path speed this axis moves at."""
        if self.arc is None:
            return self.direction.get(axis, 0.0)
        ax, ay, cx, cy, radius, angle0, sweep = self.arc
        angle = angle0 + math.copysign(s / radius, sweep) if radius > 0 else angle0
        sign = 1.0 if sweep >= 0 else -1.0
        return -sign * math.sin(angle) if axis == ax else sign * math.cos(angle)


@dataclass(slots=True)
class Motion:
    """A path traversed with a speed profile; `ident` tells stale scheduled events apart."""

    ident: int
    path: Path
    segments: list[Segment]
    target: dict[str, float] | None = None  # exact end positions (no rounding drift)
    t0: float = field(init=False, default=0.0)
    t_end: float = field(init=False, default=0.0)  # asked often (is the axis moving?): computed once

    def __post_init__(self) -> None:
        if self.segments:
            self.t0, self.t_end = self.segments[0].t0, self.segments[-1].t1

    def segment_at(self, t: float) -> Segment:
        for seg in self.segments:
            if t < seg.t1:
                return seg
        return self.segments[-1]

    def distance(self, t: float) -> float:
        if not self.segments:
            return 0.0
        if t >= self.t_end:
            return self.path.length
        return self.segment_at(t).distance(t)

    def speed(self, t: float) -> float:
        if not self.segments or t >= self.t_end or t < self.t0:
            return 0.0
        return self.segment_at(t).speed(t)

    def positions(self, t: float) -> dict[str, float]:
        if self.target is not None and t >= self.t_end:
            return dict(self.target)
        return self.path.at(self.distance(t))

    def time_at(self, s: float) -> float:
        """When the path first reaches distance s (INF when it never does)."""
        for seg in self.segments:
            if seg.s0 + seg.length >= s:
                return seg.time_at(s)
        return INF


@dataclass(frozen=True, slots=True)
class Limits:
    """The settings a move runs with (steps/s, steps/s²; accel 0 or less: instant)."""

    initial: float
    maximum: float
    accel: float
    decel: float
    smooth: bool = False


def plan(t0: float, length: float, lim: Limits) -> list[Segment]:
    """The segments of a move of `length` (>= 0) steps along a path starting at time t0."""
    if length <= 0:
        return []
    vi = max(lim.initial, 0.0)
    vmax = max(lim.maximum, vi)
    if vmax <= 0:
        raise ValueError("the maximum speed is 0: the move would never end")
    if vmax == vi:
        return [Segment(t0, length / vi, 0.0, vi, vi)]
    a = lim.accel if lim.accel > 0 else INF
    d = lim.decel if lim.decel > 0 else INF
    up = (vmax * vmax - vi * vi) / (2 * a)
    down = (vmax * vmax - vi * vi) / (2 * d)
    if up + down > length:
        # a triangle: the highest peak that fits, (vp² − vi²)(1/2a + 1/2d) = length
        inv = (0.5 / a if a != INF else 0.0) + (0.5 / d if d != INF else 0.0)
        vmax = math.sqrt(vi * vi + length / inv)
        up = (vmax * vmax - vi * vi) / (2 * a)
        down = length - up
    segments: list[Segment] = []
    t, s = t0, 0.0
    if up > 0 and a != INF:
        dur = (vmax - vi) / a
        segments.append(Segment(t, dur, s, vi, vmax, lim.smooth))
        t, s = t + dur, s + up
    cruise = length - up - down
    if cruise > 1e-12:
        dur = cruise / vmax
        segments.append(Segment(t, dur, s, vmax, vmax))
        t, s = t + dur, s + cruise
    if down > 0 and d != INF:
        dur = (vmax - vi) / d
        segments.append(Segment(t, dur, s, vmax, vi, lim.smooth))
    return segments


def plan_slew(t0: float, v_from: float, speed: float, accel: float, smooth: bool) -> list[Segment]:
    """Ramp from `v_from` to `speed` (both >= 0) and cruise forever."""
    segments: list[Segment] = []
    t, s = t0, 0.0
    if speed != v_from and accel > 0:
        dur = abs(speed - v_from) / accel
        segments.append(Segment(t, dur, 0.0, v_from, speed, smooth))
        t, s = t + dur, (v_from + speed) / 2 * dur
    segments.append(Segment(t, INF, s, speed, speed))
    return segments


def plan_stop(t0: float, v_from: float, decel: float, smooth: bool) -> list[Segment]:
    """Ramp from `v_from` down to standstill at `decel` (decel 0 or less: at once)."""
    if v_from <= 0 or decel <= 0:
        return []
    return [Segment(t0, v_from / decel, 0.0, v_from, 0.0, smooth)]


def plan_seek(t0: float, length: float, lim: Limits) -> tuple[list[Segment], float]:
    """A homing seek: ramp from the initial speed toward the maximum and keep going until the
    switch, `length` (> 0) steps away; the axis passes the switch still moving. Returns the
    segments and the speed at the switch (the seek does not know where the switch is, so it never
    slows down for it)."""
    vi = max(lim.initial, 0.0)
    vmax = max(lim.maximum, vi)
    if vmax <= 0:
        raise ValueError("the homing speed is 0: the seek would never reach the switch")
    segments: list[Segment] = []
    t, s, v = t0, 0.0, vi
    if vmax > vi and lim.accel > 0:
        up = (vmax * vmax - vi * vi) / (2 * lim.accel)
        if up >= length:  # the switch comes before the top speed
            v = math.sqrt(vi * vi + 2 * lim.accel * length)
            segments.append(Segment(t, (v - vi) / lim.accel, 0.0, vi, v, lim.smooth))
            return segments, v
        dur = (vmax - vi) / lim.accel
        segments.append(Segment(t, dur, 0.0, vi, vmax, lim.smooth))
        t, s = t + dur, up
    v = vmax
    segments.append(Segment(t, (length - s) / v, s, v, v))
    return segments, v


def plan_brake(t0: float, v_from: float, v_to: float, decel: float, smooth: bool) -> list[Segment]:
    """Ramp from `v_from` down to `v_to` at `decel` and stop there (decel 0 or less: at once):
    a homing seek slowing down past the switch to its initial speed."""
    if v_from <= v_to or decel <= 0:
        return []
    return [Segment(t0, (v_from - v_to) / decel, 0.0, v_from, v_to, smooth)]


def plan_creep(t0: float, length: float, speed: float) -> list[Segment]:
    """A creep at constant `speed` (> 0) for `length` steps, starting and stopping at once (a
    speed the motor starts and stops at without a ramp)."""
    if length <= 0:
        return []
    return [Segment(t0, length / speed, 0.0, speed, speed)]
