"""The machine behind a virtual device: mcc.sim's machine, kept between commands, and its clock.

A virtual device stores programs as text (what its host protocol documents) and runs them, and the
immediate commands it receives, through the simulator (`mcc.sim`): it compiles the text with
mcc's own frontend into the IR and hands the module to `sim.interpreter.Simulator`, on one
`sim.machine.Machine` that lives as long as the device (positions, settings, outputs, inputs) and
one table of variables. The device's replies to status, position and variable queries read that
state, so there is a single interpreter for programs in mcc.

Virtual time (docs/LINK.md, "Virtual time"; docs/decisions/0017-device-time.md): the device has a
clock that runs as a controller's does. Each command the host sends costs the transmission time of
its characters at the link's baud rate, then the product's command execution time (the profile's
`[device] command_time`; MCode 1-5 ms, L6821), then the transmission time of the reply; a host
that waits (`elapse`, the server's measure of the host's silence) lets that much time pass. A move
or a program goes on across commands: the run that started it stays live (`Simulator.advance`)
and is advanced to the clock before each command, so a query reads the state at that moment (MCode
`PR MP` reads 1 while the move of `MA 5120000` runs, L4220). The device is a function of what the
host sends and when, not of how fast mcc computes.

One run is live at a time: the device's program (MCode EX, X150 XR/XG/GOSUB/GOTO, Arcus SR=1/GSn)
or, with no program running, the last immediate command, which owns the moves it left going.
A program that has not ended `run_limit` virtual seconds after it started, that waits for something
nothing on a virtual device can cause (an input no one sets), or that ran MAX_STEPS operations
without waiting is held: reported running (MCode BY=1, X150 busy, Arcus SASTAT 1) with the machine
frozen where it was, as `mcc sim` leaves it at its time limit; a stop command ends it.
"""

from __future__ import annotations

import copy
import dataclasses
import weakref
from dataclasses import dataclass, field

from mcc.compiler import ir
from mcc.sim import values
from mcc.sim.interpreter import ContractError, Options, Simulator
from mcc.sim.machine import Machine, defaults
from mcc.sim.scenario import Scenario
from mcc.sim.trace import Trace

RUN_LIMIT = 60.0         # virtual seconds a run may take (the default of `mcc sim`)
# operations a run may execute: a fifth of `mcc sim`'s default, so that a loop that never waits
# ends in well under a second and the device answers within the host's timeout (2 s by default)
MAX_STEPS = 200_000


@dataclass
class Outcome:
    """How a run on the device ended."""

    status: str                 # "idle" (ended) | "running" (still running on a real device) | "error"
    reason: str = ""
    trace: Trace | None = None
    prints: list[str] = field(default_factory=list)


def _walk(value, out: set[str]) -> None:
    """Every variable name read or written anywhere inside an IR node."""
    if isinstance(value, ir.Var):
        out.add(value.name)
    elif isinstance(value, (list, tuple)):
        for item in value:
            _walk(item, out)
    elif dataclasses.is_dataclass(value) and not isinstance(value, type):
        for f in dataclasses.fields(value):
            if f.name != "span":
                _walk(getattr(value, f.name), out)


def variables_used(module: ir.Module) -> set[str]:
    names: set[str] = set(module.variables)
    for _routine, block in module.blocks():
        _walk(block.ops, names)
        _walk(block.terminator, names)
    return names


def starting_at(module: ir.Module, entry: tuple[str, str | None] | None) -> ir.Module:
    """The module arranged so that the simulator starts where the device was told to.

    `entry` is (routine name, block label or None), or None for "the commands sent outside any
    program" (the module's immediate routines: an immediate command, an X150 `XR`). The chosen
    routine becomes the main program with the block first; other main and power-up routines
    become subroutines (they run only when called); immediate routines are dropped when a stored
    program is started (what was sent outside it has already run, as it arrived)."""
    routines = []
    for routine in module.routines:
        kind = routine.kind
        if entry is not None and kind is ir.RoutineKind.IMMEDIATE:
            continue
        if kind in (ir.RoutineKind.MAIN, ir.RoutineKind.POWERUP):
            kind = ir.RoutineKind.SUBROUTINE
        if entry is not None and routine.name == entry[0]:
            blocks = list(routine.blocks)
            first = next((b for b in blocks if b.label == entry[1]), None) if entry[1] else None
            if first is not None:
                blocks = [first] + [b for b in blocks if b is not first]
            routines.append(dataclasses.replace(routine, kind=ir.RoutineKind.MAIN, blocks=blocks))
        else:
            routines.append(dataclasses.replace(routine, kind=kind))
    return dataclasses.replace(module, routines=routines, variables=dict(module.variables))


def default_profile(dialect: str):
    """The dialect's default profile, as `mcc sim` uses it (its axes, its call depth)."""
    from mcc.compiler import dialects, driver

    try:
        return driver.profile_for(dialects.get(dialect), None)
    except Exception:  # noqa: BLE001 - a profile is a refinement; the simulator runs without one
        return None


INF = float("inf")
BITS_PER_CHARACTER = 10   # a start bit, 8 data bits, a stop bit (the profiles' 8N1); +1 with a parity bit
DEFAULT_BAUD = 9600       # every product's factory rate (lexium-mcode.txt L1586, arcus L401; X150 profile)


def timing(profile) -> tuple[float, float]:
    """(command execution time, one character's transmission time) in seconds, from the product
    profile: `[device] command_time` and `[link] baudrate` / `parity`."""
    get = profile.get if profile is not None else (lambda _key, default=None: default)
    command = get("device.command_time", 0.0)
    command = float(command) if isinstance(command, (int, float)) and not isinstance(command, bool) \
        and command >= 0 else 0.0
    baud = get("link.baudrate", DEFAULT_BAUD)
    baud = baud if isinstance(baud, (int, float)) and not isinstance(baud, bool) and baud > 0 else DEFAULT_BAUD
    bits = BITS_PER_CHARACTER + (0 if str(get("link.parity", "N")).upper() == "N" else 1)
    return command, bits / baud


class DeviceMachine:
    """The simulator's machine and variables of one virtual device, its clock and the run that goes
    on across commands (the device's program, or the moves an immediate command left going)."""

    def __init__(self, dialect: str, run_limit: float = RUN_LIMIT, profile=None) -> None:
        self.dialect = dialect
        self.run_limit = run_limit
        self.profile = profile if profile is not None else default_profile(dialect)
        self.command_time, self.char_time = timing(self.profile)
        self.machine = Machine()
        for axis in (self.profile.axes if self.profile is not None else ()):
            self.machine.axis(axis)   # the product's axes exist from power-up, as in `mcc sim`
        self.variables: dict[str, int | float] = {}
        # the device settings the runs set (the simulator's `settings`: (name, axis, index) -> value)
        # and the input polarities: a device keeps them from one command or program to the next,
        # so the host reads back what a stored program set and a report reads what earlier
        # commands set
        self.settings: dict = {}
        self.active_high: dict[int, bool] = {}
        self.clock = 0.0                      # virtual seconds since power-up
        self.status = "idle"                  # of the program: idle | running | error
        self.reason = ""
        self.live: Simulator | None = None    # the run that goes on across commands
        self.live_program = False             # `live` is the device's program
        self.started_at = 0.0                 # when the live program started (its run limit counts from there)
        self.paused_at: float | None = None   # when the live program was paused
        self.motion_ids = 0                   # one numbering of moves for every run on the machine
        # a held program's machine is frozen: the axes that were moving, with their speed, and the
        # slews among them (reported moving until a stop)
        self.moving: dict[str, float] = {}
        self.slewing: dict[str, float] = {}   # axis -> velocity of every slew, live or frozen
        self.generation = 0                   # bumped each time a run went on: the devices' state to update
        self.outbox: list[str] = []           # what runs printed since the device last answered
        self.begun: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()  # run -> the clock it started at
        self.sent: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()  # run -> its prints in the outbox
        self.busy_until = 0.0                 # when the last run's program, moves and delays ended
        self.first_start: float | None = None  # when the first run started
        self.first_program: float | None = None  # when the first program started (a case's duration)
        self.last: Trace | None = None       # the trace of the last run started
        self.traces: list[Trace] = []         # the trace of every run started (their output events)
        self.outcome: Outcome | None = None   # how the last run (a program or a command) ended

    # -- the clock -------------------------------------------------------------------------------
    def elapse(self, seconds: float) -> None:
        """Let `seconds` of virtual time pass: the live run goes on to the new time."""
        if seconds > 0:
            self.advance(self.clock + seconds)

    def advance(self, t: float) -> None:
        """The clock moves on to `t`; the live program runs on (its moves end, its delays pass)."""
        if t <= self.clock:
            return
        if self.paused_at is not None and self.live_program:
            self.clock = t   # a paused program does not go on (its moves do, on their own)
            return
        if self.live is not None:
            self._drive(self.live, t)
        self.clock = max(self.clock, t)

    def pause(self) -> None:
        """The program stops executing where it is (Arcus SR=2); the moves under way go on."""
        if self.live_program and self.paused_at is None:
            self.paused_at = self.clock

    def resume(self) -> None:
        """The paused program goes on (Arcus SR=3): what was due while it was paused happens now,
        and its run limit counts only the time it ran."""
        if self.paused_at is not None:
            self.started_at += self.clock - self.paused_at
            self.paused_at = None

    def transmit(self, characters: int) -> None:
        """`characters` cross the serial line (a command in, a reply out) at the link's baud rate."""
        self.elapse(characters * self.char_time)

    def execute(self) -> None:
        """A command's execution time passes (the profile's `[device] command_time`, L6821)."""
        self.elapse(self.command_time)

    def write(self, name: str, value) -> None:
        """The host sets a variable: the device's table, and the running program's, hold it."""
        self.variables[name] = values.plain(value) if not isinstance(value, str) else value
        live = self.live
        if live is not None and self.live_program and name in live.vars and live.vars[name] != value:
            live.set_variable(name, value)

    def take_output(self) -> list[str]:
        """What the runs printed that the host has not received yet (sent with the next reply)."""
        out, self.outbox = self.outbox, []
        return out

    # -- the state the host protocol reads, at the clock -----------------------------------------
    def position(self, axis: str) -> float:
        found = self.machine.axes.get(axis)
        return found.at(self.clock) if found is not None else 0.0

    def positions(self) -> dict[str, float]:
        return {name: axis.at(self.clock) for name, axis in self.machine.axes.items()}

    def is_moving(self, axis: str) -> bool:
        found = self.machine.axes.get(axis)
        return (found is not None and found.moving(self.clock)) or axis in self.moving

    def is_slewing(self, axis: str) -> bool:
        found = self.machine.axes.get(axis)
        if found is not None and found.motion is not None and found.moving(self.clock):
            return found.motion.t_end == INF
        return axis in self.moving and axis in self.slewing

    def speed(self, axis: str) -> float:
        """The axis's signed speed now (steps/s): of its move, else the speed it was held at."""
        found = self.machine.axes.get(axis)
        if found is not None and found.moving(self.clock):
            return found.speed(self.clock)
        return self.moving.get(axis, 0.0)

    def any_moving(self) -> bool:
        return any(self.is_moving(name) for name in self.machine.axes) or bool(self.moving)

    def setting(self, axis: str, param: ir.MotionParam) -> float:
        return self.machine.axis(axis).setting(param, self.machine.shared)

    def input_level(self, index: int) -> int:
        """Input `index`'s electrical level: what the host set, else the inactive level of the
        polarity in force (the product's `[machine.inputs] active_high`): an input nothing
        drives is not active."""
        level = self.machine.inputs.get(index)
        if level is not None:
            return 1 if level else 0
        table = self.profile.get("machine.inputs", {}) if self.profile is not None else {}
        idle = table.get("idle_level") if isinstance(table, dict) else None
        if idle in (0, 1) and not isinstance(idle, bool):
            return idle
        return 0 if self.active_high.get(index, self._active_high_default()) else 1

    def input_logic(self, index: int) -> int:
        """Input `index`'s logic state (1 active) through the polarity in force."""
        level = self.input_level(index)
        return level if self.active_high.get(index, self._active_high_default()) else 1 - level

    def _active_high_default(self) -> bool:
        table = self.profile.get("machine.inputs", {}) if self.profile is not None else {}
        return bool(table.get("active_high", True)) if isinstance(table, dict) else True

    def stop(self) -> None:
        """The program is stopped (a stop command): it no longer runs and the axes stop where they
        are now."""
        self.status, self.reason, self.paused_at = "idle", "stopped", None
        self.live, self.live_program = None, False
        self._freeze(keep=False)
        self.moving.clear()
        self.slewing.clear()

    # -- running ---------------------------------------------------------------------------------
    def snapshot(self) -> dict:
        """The device's state, to run a program again from it (single step: each step request
        replays the program from where it started, up to one more command)."""
        self._freeze(keep=True)   # a live run's moves would not survive the copy
        self.live, self.live_program = None, False
        return copy.deepcopy({"machine": self.machine, "variables": self.variables, "settings": self.settings,
                              "active_high": self.active_high, "clock": self.clock})

    def restore(self, state: dict) -> None:
        state = copy.deepcopy(state)
        self.machine, self.variables, self.settings = state["machine"], state["variables"], state["settings"]
        self.active_high, self.clock = state["active_high"], state["clock"]
        self.live, self.live_program = None, False

    def run(self, module: ir.Module, entry: tuple[str, str | None] | None = None, program: bool = True,
            commands: int | None = None, buffered: bool = False) -> Outcome:
        """Start `module` from `entry` (see `starting_at`) at the clock, on the device's machine and
        variables. `program`: this run is the device's program: it replaces the one running and
        goes on across commands (its end sets the program's status). Otherwise it is an immediate
        command: it runs at the clock and is answered at once; the moves it started go on, and if
        it has to wait (a move on a busy axis, decision 0010; an X150 G waiting for its move) it
        goes on too, the next command that runs on the machine waiting for it (L177 for the X150).
        While a program runs, an immediate command that would have to wait is not made. `commands`: single step,
        the program runs that many of its commands and is held (X150 XST1). `buffered`: the
        command waits in the device's buffer until the program running has ended (X150 buffered
        commands "executed in sequential order", parker-x150.md L177; the catalog's `exec`)."""
        module = starting_at(module, entry)
        for name in variables_used(module):
            if name not in self.variables:
                continue
            declared = module.variables.get(name)
            vtype = module.type_of(name) or module.default_type or ir.VarType.FLOAT64  # registers: the lowering's
            scope = declared.scope if declared is not None else "global"
            module.variables[name] = ir.Variable(name, vtype, ir.Const(self.variables[name]), scope)
        options = Options(until=self.clock, max_steps=MAX_STEPS, samples=False, commands=commands)
        try:
            simulator = Simulator(module, Scenario(inputs=dict(self.machine.inputs)), options, self.profile)
        except ContractError as exc:
            return self._ended(Outcome("error", f"cannot run: {exc}"), program)
        self.machine.shared["defaults"] = defaults(module.steps_per_rev, simulator.product)
        self.machine.shared["sets"] = tuple(module.axis_sets)
        simulator.machine = self.machine      # the device's machine: what earlier commands left
        simulator.settings = self.settings
        simulator.active_high = self.active_high
        simulator.now = self.clock
        simulator.slewing.update({a: v for a, v in self.slewing.items() if self.is_slewing(a)})
        self.last = simulator.trace
        self.traces.append(simulator.trace)
        self.begun[simulator] = self.clock
        if self.first_start is None:
            self.first_start = self.clock
        if buffered and self.live_program and self.live is not None:
            self._wait_for_program()
        if commands is None and self.live is not None and not self.live_program and not self.live.ended:
            self._wait_for(self.live)   # the command before it still runs: this one waits its turn
        if program:
            if self.first_program is None:
                self.first_program = self.clock
            self.moving.clear()   # a held program's frozen axes: the new program starts from rest
            self.status, self.reason, self.paused_at = "running", "", None
            self.live, self.live_program, self.started_at = simulator, True, self.clock
            # single step: the commands let run go to their end at once (the host waits for them)
            stopped = self._drive(simulator, self.clock + (self.run_limit if commands is not None else 0.0))
        elif self.live_program and self.live is not None:
            stopped = self._step(simulator, self.clock)   # no time passes for it: it does not wait
            if stopped == "end":
                self.live.adopt()   # the program's run lets the moves this command started end
            for name, value in simulator.vars.items():   # what it assigned, the program reads too
                self.write(name, value)
        else:
            stopped = self._step(simulator, self.clock)
            if stopped in (None, "end"):
                # it owns the moves it left going; one that waits (a move on a busy axis, an X150
                # G that waits for its move) goes on across the next commands, answered at once
                self.live, self.live_program = simulator, False
            elif stopped != "waiting":   # a loop that never waits: held where it is
                self._freeze(keep=True)
        status = {None: "running", "end": "idle", "error": "error"}.get(stopped, "running")
        prints = self.take_output()
        return self._ended(Outcome(status, simulator.trace.reason if stopped else "", simulator.trace, prints),
                           program, status_set=program)

    # -- the live run ------------------------------------------------------------------------------
    def _step(self, simulator: Simulator, until: float) -> str | None:
        """Advance `simulator` to `until` (it adopts the moves other runs left going first) and take
        what it changed: the variables, the settings, what it printed."""
        simulator.adopt()
        simulator.motion_ids = max(simulator.motion_ids, self.motion_ids)
        try:
            stopped = simulator.advance(until)
        except Exception as exc:  # noqa: BLE001 - a device keeps answering; the run is reported failed
            simulator.trace.stopped = "error"
            simulator.trace.reason = (f"internal error in the simulator ({type(exc).__name__}: {exc}); "
                                      "this is a bug in mcc, please report it")
            stopped = "error"
        self.motion_ids = max(self.motion_ids, simulator.motion_ids)
        self.generation += 1
        self.settings, self.active_high = simulator.settings, simulator.active_high
        merged = {**self.slewing, **simulator.slewing}
        self.slewing = {axis: v for axis, v in merged.items() if self._slews(axis)}
        self.variables.update({name: values.plain(v) for name, v in simulator.vars.items()})
        printed = simulator.trace.prints
        sent = self.sent.get(simulator, 0)
        self.outbox += [text for _t, text in printed[sent:]]
        self.sent[simulator] = len(printed)
        # busy: until the moves end, and while a run goes on past the time it began (a zero-time
        # command, a query, is not busy)
        ends = [a.motion.t_end for a in self.machine.axes.values() if a.motion is not None and a.motion.t_end < INF]
        last = simulator.end_time if simulator.ended else simulator.now
        self.busy_until = max(self.busy_until, last if last > self.begun.get(simulator, last) else 0.0, *ends)
        return stopped

    def _slews(self, axis: str) -> bool:
        found = self.machine.axes.get(axis)
        if found is not None and found.motion is not None:
            return found.motion.t_end == INF
        return axis in self.moving

    def _wait_for(self, simulator: Simulator) -> None:
        """The device runs the command in progress to its end before it starts the next one (the
        X150 runs buffered commands "in sequential order", L177): the clock moves on meanwhile."""
        stopped = self._step(simulator, self.clock + self.run_limit)
        self.clock = max(self.clock, simulator.now)
        if stopped != "end":   # it never ends (a slew it waits for, a delay past the run limit):
            self.live = None   # given up; the moves under way go on (the next run adopts them)

    def _wait_for_program(self) -> None:
        """The clock moves on until the running program ends (or is held at its run limit)."""
        live = self.live
        stopped = self._drive(live, self.started_at + self.run_limit)
        self.clock = max(self.clock, live.end_time if stopped == "end" else live.now)

    def _drive(self, simulator: Simulator, t: float) -> str | None:
        """The live run goes on to `t`; a program is held at its run limit, or when it waits for
        what cannot happen, or fails (the machine then stops where it is)."""
        limit = self.started_at + self.run_limit if self.live_program else INF
        stopped = self._step(simulator, min(t, limit))
        if stopped is None and t >= limit and self.live_program:
            stopped = "time-limit"
        if stopped is None or stopped == "end":
            if stopped == "end" and self.live_program:
                self.status, self.reason = "idle", simulator.trace.reason
                self.live_program = False    # the program ended; the run still owns the moves it left
            return stopped
        # held (or failed): the machine stops where it is; the program is reported running
        if self.live_program:
            self.status = "error" if stopped == "error" else "running"
            self.reason = simulator.trace.reason or f"the time limit of {self.run_limit:g} s was reached"
        self.live, self.live_program = None, False
        self.clock = max(self.clock, simulator.now)
        self._freeze(keep=True)
        return stopped

    def _freeze(self, keep: bool) -> None:
        """Stop every axis where it is at the clock. `keep`: the axes that were moving are reported
        moving at the speed they had (a held program); else they are stopped."""
        for name, axis in self.machine.axes.items():
            if axis.motion is None:
                continue
            if keep and axis.moving(self.clock):
                self.moving[name] = axis.speed(self.clock)
                if axis.motion.t_end == INF:
                    self.moving[name] = axis.speed(self.clock + 3600.0)   # a slew: the speed it runs at
            axis.position = round(axis.at(self.clock), 6)
            axis.motion, axis.on_end, axis.homing = None, "", None
        if not keep:
            self.moving.clear()

    def _ended(self, outcome: Outcome, program: bool, status_set: bool = False) -> Outcome:
        self.outcome = outcome
        if program and not status_set:
            self.status, self.reason = outcome.status, outcome.reason
        return outcome
