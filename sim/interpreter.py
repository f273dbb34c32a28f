"""The interpreter: runs an IR module against the machine model in virtual time.

It interprets the IR *contract* (docs/IR.md): a module the verifier rejects is refused with the
first violation, never guessed at. Time is event-driven: the program runs (operations take no
virtual time) until it waits (a delay, motion, an input, a move on a busy axis); then time jumps
to the next scheduled event (a move ends, an axis passes a watched position, the scenario changes
an input, a delay or a timer expires). Nothing ticks through idle time.

A program that spins without changing anything (a loop polling an input or a position) is
recognised after `Options.spin` steps with no change: time then advances to the next event, or by
`Options.poll` seconds while an axis moves, as a real controller's scan would.

Semantics the dialects leave open are decided in docs/SIMULATOR.md and noted where they are coded.
"""

from __future__ import annotations

import dataclasses
import heapq
import math
from dataclasses import dataclass
from decimal import Decimal

from mcc.compiler import cancel, ir, ir_names, ir_print, ir_verify
from mcc.compiler.diagnostics import Diagnostics
from mcc.compiler.span import Span
from mcc.sim import values
from mcc.sim.machine import Axis, Machine, defaults
from mcc.sim.motion import (INF, Limits, Motion, Path, plan, plan_brake, plan_creep, plan_seek, plan_slew,
                             plan_stop)
from mcc.sim.repeats import AFTER as REPEATS_AFTER
from mcc.sim.repeats import Repeats
from mcc.sim.scenario import Scenario
from mcc.sim.trace import Event, Trace

# The type of a variable the module does not declare (registers used without a declaration).
DEFAULT_NESTING = 16  # calls deep, when the profile does not say (limits.nesting)
# The bit of the `handler_enable` setting (MCode TE) that lets a gated handler of each event fire.
ENABLE_BITS = {event: bit for bit, event in ir_names.HANDLER_ENABLE_BITS.items()}
# Events whose handlers fire once in every dialect: a time elapses once, a position is passed once.
ONCE_EVENTS = frozenset({"time", "position"})
# Which handlers a runtime fault may run, the first installed one wins (docs/SIMULATOR.md).
HANDLER_CHAIN = {"error": ("error",), "fault": ("fault", "error"), "stall": ("stall", "fault", "error"),
                 "power": ("power_loss",)}
DEFAULT_CAPTURE_INPUT = 1  # MCode: the capture input is input 1 (L781, L5607)
CONTINUOUS = frozenset({"position", "encoder", "velocity", "measured_velocity", "moving", "moving_to_position"})  # readings that change between events
QUIET_KINDS = frozenset({"call", "return", "goto", "native"})
CANCEL_EVERY = 4096  # steps between two cancellation checkpoints (compiler/cancel.py)
POLL_RECHECK = 50  # steps without a change that show a loop is still polling after a poll
ROUND_STATES = 256  # states a loop may cycle through and still count as changing nothing


# Settings whose non-zero value changes how the machine runs in a way the simulator does not model.
UNMODELLED = {"following_mode": "the axis follows an external input instead of running its own moves",
              "single_step": "a stored program runs one command per step request from the host"}


# The functions whose angles follow the setting `trig_radians` (degrees when it is 0).
TRIG = frozenset({"sin", "cos", "tan", "asin", "acos", "atan"})
# Readings of what the machine model has no cause for (no slip, no over-current): the product's
# value the module declares (`device_values`), else 0.
UNCAUSED = frozenset({"position_error", "output_fault", "part_number", "firmware_version"})

# Readings that report a setting: the setting they read and its value before the program sets it.
SETTING_READINGS = {"following_ratio": ("following_ratio", 100), "input_levels": ("input_active_high", 0),
                    "output_levels": ("output_active_high", 0), "switch_levels": ("switch_active_high", 0)}


@dataclass
class HomeRun:
    """A homing in progress: its operation, the switch (machine coordinate), the limits it runs
    at, its creep speed, the phase it is in and its direction of travel."""

    op: ir.Home
    switch: float
    limits: Limits
    creep: float
    stage: str = "seek"  # seek | brake | creep
    direction: float = 1.0
    speed: float = 0.0  # at the switch, when the seek trips it


class ContractError(Exception):
    """The module does not keep the IR contract: the simulator will not guess what it means."""

    def __init__(self, violation: ir_verify.Violation):
        super().__init__(f"the IR does not keep the contract ({violation.group}) at {violation.where}: "
                         f"{violation.message}")
        self.violation = violation


class RuntimeFault(Exception):
    def __init__(self, code: str, message: str, kind: str = "error"):
        super().__init__(message)
        self.code = code
        self.kind = kind  # "error" | "fault": which handler may catch it


@dataclass
class Options:
    until: float = 60.0  # virtual seconds
    max_steps: int = 1_000_000  # operations and terminators executed
    nesting: int | None = None  # call depth; None: the profile's limits.nesting, else 16
    spin: int = 2000  # steps without any change before a loop counts as polling
    poll: float = 0.001  # seconds a polling loop advances while an axis moves
    samples: bool = True  # record sampled motion for the trace and plots
    # Where a polling loop pauses for time to pass: 0 where it goes round (a jump back); n > 0 n
    # steps after that, or where it goes round when a round is shorter (sim/verify.py tries the
    # points of a round to tell a race on an input from a changed program)
    poll_offset: int = 0
    # Jump over the rounds of a delay-paced polling loop that cannot differ from the last one
    # (Simulator._went_round); off, every round runs (the tests compare the two)
    skip_rounds: bool = True
    # Single step: the run stops before its (n+1)-th trace report, having run n of the program's
    # commands (a device in single-step mode; the trace reports mark where each command starts)
    commands: int | None = None
    # The machine's envelope (issue 27): (axis, min, max) in steps, None for an open end. A move
    # beyond it runs to the end of travel and the run stops there with S017, as the limit switch
    # would stop the axis (docs/SIMULATOR.md, "Envelope").
    travel: tuple[tuple[str, float | None, float | None], ...] = ()


@dataclass(slots=True)
class Wait:
    kind: str  # delay | motion | input | busy | poll
    until: float = 0.0
    axes: tuple[str, ...] = ()
    cond: ir.Cond | None = None
    retry: bool = False  # run the same operation again when the wait ends (a move on a busy axis)
    line: int | None = None  # the source line of the operation that waits


@dataclass(slots=True)
class Frame:
    routine: ir.Routine
    block: ir.Block
    index: int = 0
    handler: str = ""  # the event when this frame runs a handler
    wait: Wait | None = None


@dataclass
class Handler:
    event: str
    routine: str | None
    args: tuple = ()
    armed: bool = True
    last: bool = False  # "when": the condition's value at the last check (fires on a rising edge)
    fired_at: float = -1.0
    once: bool = False  # the IR's SetHandler facts, from the last installation
    gated: bool = False
    takes_over: bool = False


@dataclass(slots=True)
class RoundMark:
    """Where and when a loop last went round, and what the run had done by then."""

    frame: Frame
    label: str
    depth: int
    now: float
    quiet_changes: int  # changes other than delays ending
    delays: list[float]  # the delays of the round that ended here
    events: int
    prints: int
    steps: int
    marks: int  # passes of the main loop's headers recorded (Trace.cycle_marks)


class Stop(Exception):
    def __init__(self, stopped: str, reason: str):
        super().__init__(reason)
        self.stopped = stopped
        self.reason = reason


class Scheduled(tuple):
    """(t, seq, kind, payload): a plain tuple, so the heap compares it in C."""

    __slots__ = ()

    t = property(lambda self: self[0])
    kind = property(lambda self: self[2])
    payload = property(lambda self: self[3])


class Simulator:
    def __init__(self, module: ir.Module, scenario: Scenario | None = None, options: Options | None = None,
                 profile=None, checked: bool = False):
        # `checked`: the caller verified the contract of this very module (sim.verify runs one
        # module on many scenarios, and the verifier costs more than a short run)
        problems = [] if checked else ir_verify.verify(module)
        if problems:
            raise ContractError(problems[0])
        self.module = module
        self.scenario = scenario or Scenario()
        self.options = options or Options()
        if self.scenario.until is not None and options is None:
            self.options.until = self.scenario.until
        nesting = self.options.nesting
        if nesting is None and profile is not None:
            nesting = profile.get("sim.nesting", profile.get("limits.nesting"))
        self.nesting = int(nesting or DEFAULT_NESTING)
        self.routines = {r.name: r for r in module.routines}
        self.block_of = {b.label: b for _, b in module.blocks()}
        self.block_index = {b.label: n for r in module.routines for n, b in enumerate(r.blocks)}
        self.went_back = False  # the last terminator jumped back (to a block at or before its own)
        self.since_back = -1  # steps since the last jump back (-1: none yet)
        self.machine = Machine(inputs=dict(self.scenario.inputs), analog=dict(self.scenario.analog))
        # the product's machine (power-up settings, arithmetic, inputs): the profile given, else
        # the one the module was compiled for
        self.product = profile if profile is not None else profile_of(module)
        self.machine.shared["defaults"] = defaults(module.steps_per_rev, self.product)
        arithmetic = machine_table(self.product, "arithmetic")
        self.division = str(arithmetic.get("integer_division", "truncate"))
        self.motion_floor = arithmetic.get("float_to_motion") == "floor"
        # [width, decimals, notation, justification]; a malformed value in a user's profile is ignored
        fmt = arithmetic.get("float_print")
        self.float_format = fmt if isinstance(fmt, list) and 0 < len(fmt) <= 4 and all(
            isinstance(v, int) and not isinstance(v, bool) and 0 <= v <= 32 for v in fmt) else None
        self.float_pad = bool(arithmetic.get("float_print_pad", False))
        # inputs: the scenario gives electrical levels; I1.. read the logic state through the
        # polarity the program set (IS, INL) or the product's default (docs/SIMULATOR.md, "Inputs")
        inputs = machine_table(self.product, "inputs")
        self.active_high_default = bool(inputs.get("active_high", True))
        # the level of an input nothing drives; without one, the inactive level of its polarity
        idle = inputs.get("idle_level")
        self.idle_level = idle if idle in (0, 1) and not isinstance(idle, bool) else None
        count = inputs.get("count", 0)
        self.input_count = count if isinstance(count, int) and not isinstance(count, bool) and 0 <= count <= 64 else 0
        # the outputs a value for every output at once sets (Arcus DO, MCode OT): the product's own
        # (`[machine.outputs] count`), else every bit of the value up to the eighth
        count = machine_table(self.product, "outputs").get("count", 0)
        self.output_count = count if isinstance(count, int) and not isinstance(count, bool) and 0 < count <= 64 else 0
        self.active_high: dict[int, bool] = {}  # input -> its polarity, as the program set it
        self.machine.shared["sets"] = tuple(module.axis_sets)
        self.countdown_marks = countdown_marks(module)
        if profile is not None:  # the countdown timer's resolution (Arcus TR counts milliseconds, L791)
            self.machine.countdown_tick = float(profile.get("sim.countdown_tick", self.machine.countdown_tick))
        for axis in (profile.axes if profile is not None else ()):
            self.machine.axis(axis)
        self.default_type = module.default_type or ir.VarType.FLOAT64
        # a variable's type and whether a printed item reads a float, by name and by item: the
        # module does not change while it runs, and a print loop asks millions of times (issue 26)
        self.types: dict[str, ir.VarType] = {}
        self.float_items: dict[int, bool] = {}
        self.vars: dict[str, values.Number] = {}
        self.trace = Trace(module.path, module.dialect, module.steps_per_rev)
        self.diags = Diagnostics(self.trace.diagnostics)
        self.now = 0.0
        self.queue: list[Scheduled] = []
        self.seq = 0
        self.stack: list[Frame] = []
        self.handlers: dict[str, Handler] = {}
        self.pending: list[tuple[str, Handler]] = []
        self.motion_ids = 0
        self.motion_op: dict[int, ir.Op] = {}
        self.changes = 0  # bumped by anything a polling loop could be waiting for
        # the share of `changes` that are variables taking a new value: a round of a loop that sets
        # a flag and clears it again (a translation's condition computed into temporaries) changes
        # nothing when the variables are back where they were as it goes round (`_execute`)
        self.var_changes = 0
        self.natives: set[str] = set()
        self.unmodelled: set[str] = set()  # settings reported once each (S014)
        # the settings set in this run: (name, axis, input/output number) -> value
        self.settings: dict[tuple[str, str, int | None], values.Number] = {}
        self.paused_once = False  # S015 is reported once
        self.commands_run = 0  # trace reports reached: the commands of the program begun (Options.commands)
        self.fixed_watches: dict[str, list] = {}
        self.read_continuous = False  # the running stretch read something that changes with time
        self.slewing: dict[str, float] = {}  # axis -> the velocity it slews at (or ramps to)
        self.polling = False
        self.poll_changes = 0
        self.poll_vars: dict = {}
        self.poll_steps = 0
        # the stretch without a change that a poll ends: the events and steps when it began, and
        # the step of the last event (`Trace.repeats_from`)
        self.quiet_events, self.quiet_step, self.event_step = 0, 0, -1
        self.wakes = 0  # delays that ended: a round of a delay-paced loop changes nothing else
        self.round: RoundMark | None = None  # the last time the running loop went round
        self.round_reads: set[tuple[str, str]] = set()  # readings that change with time, this round
        self.round_delays: list[float] = []  # the delays this round waited, in order
        self.skipped = 0  # operations of the rounds jumped over (counted in trace.steps, never run)
        self.enable_mask = 0  # `handler_enable` (MCode TE): the events allowed to fire
        self.capture_input = self.scenario.capture  # None: the program's, else DEFAULT_CAPTURE_INPUT
        self.captured = 0  # the position at the last capture (reading captured_position)
        self.last_move: dict[str, str] = {}  # axis -> the kind of its last move command (reading last_move)
        self.travel = {axis: (low, high) for axis, low, high in self.options.travel}
        self.travel_hit: dict[str, tuple] = {}  # axis -> (move, requested target, the end it runs to)
        self.cycle_headers = loop_headers(self._entry())  # where a pass of the main loop starts
        # The stepping interface (a debugger: mcc.debug). When set, it is called in the running
        # thread as `observer("step", frame, item)` before each operation or terminator the program
        # executes (`frame` the routine's Frame, its stack `self.stack`; `item` the ir.Op or
        # terminator about to run, whose `span` gives the source line; `self.went_back` says whether
        # the last terminator jumped back), and as `observer("fault", frame, item, fault)` when a
        # runtime error no handler catches is about to stop the run, and as `observer("stop", frame,
        # None, stop)` once the run has stopped for any reason (`stop.stopped`), before the trace
        # is finished. The observer may read the
        # machine and the variables, change a variable (`set_variable`) or an input (`set_input`),
        # block for as long as it likes (virtual time does not pass), or raise `Stop` to end the run
        # (`run()` then finishes the trace as usual). None (the default): `run()` is unchanged.
        self.observer = None
        self.started = False  # `advance` has started the run
        self.ended = False  # `advance` has seen the program end (its moves may still run)
        self.end_time = 0.0  # when `advance` saw the program stop
        self.adopted: set[int] = set()  # the moves of other runs this one lets end (`adopt`)
        self.repeat_counters = None  # the module's round counters (sim/repeats.py), when first needed

    # -- public ----------------------------------------------------------------------------------

    def run(self) -> Trace:
        try:
            self._start()
            self._loop()
        except Stop as stop:
            self.trace.stopped, self.trace.reason = stop.stopped, stop.reason
            if self.observer is not None:  # the state the run stopped in, before the trace is finished
                try:
                    self.observer("stop", self.stack[-1] if self.stack else None, None, stop)
                except Stop:
                    pass
        self._finish()
        return self.trace

    def advance(self, until: float) -> str | None:
        """Run on up to virtual time `until` and stop there, to be advanced again later (a virtual
        device between its host's commands, link/device/machine.py). Returns None while the program
        still runs at `until`, else how it stopped (`trace.stopped`: "end", "waiting", "error",
        "step-limit"). Once the program has ended, advancing only lets the machine's events happen:
        the moves it left end at their time (and a homing goes on to its next phase). The trace is
        not finished (no `_finish`): the caller reads the machine and `vars`. Start the run at the
        device's clock by setting `now` before the first call."""
        self.options.until = until
        try:
            if not self.started:
                self.started = True
                self._start()
            if self.ended:
                while self._next_event_time() <= until:
                    self.now = max(self.now, self.queue[0].t)
                    self._process_events()
                    self.pending.clear()  # no program is left to run a handler
                self.now = max(self.now, until)
                return "end"
            self._loop()
        except Stop as stop:
            if stop.stopped == "time-limit":
                return None
            self.trace.stopped, self.trace.reason = stop.stopped, stop.reason
            self.ended = stop.stopped == "end"
            self.end_time = self.now
            return stop.stopped
        return None  # pragma: no cover - _loop only ends by Stop

    def adopt(self) -> None:
        """The moves another run left going on this machine (a virtual device's earlier command) end
        at their time in this run too, and their positions are watched, as if it had started them."""
        known = set(self.motion_op) | self.adopted
        for name, axis in self.machine.axes.items():
            motion = axis.motion
            if motion is not None and motion.ident not in known and motion.t_end > self.now:
                self._schedule(motion.t_end, "motion_end", (name, motion.ident))  # a slew's (INF) is not
                self._watch(axis)
                self.adopted.add(motion.ident)

    def set_variable(self, name: str, value) -> values.Number:
        """Give variable `name` a value while the run is paused (a debugger's setVariable): stored
        with the variable's type, as an assignment would, and counted as a change so a polling loop
        sees it. Returns the value stored."""
        try:
            stored = values.store(value, self._type(name))
        except values.ArithmeticFault as exc:
            raise ValueError(str(exc)) from None
        self.vars[name] = stored
        self.changes += 1
        self.var_changes += 1
        return stored

    def set_input(self, index: int, level: int) -> None:
        """Drive input `index` to an electrical level while the run is paused (a debugger): as a
        scenario change at the current time; the scenario's later changes still happen."""
        self._set_input(index, 1 if level else 0, by="debugger")
        self._check_when()

    def input_level(self, index: int) -> int:
        """Input `index`'s electrical level (the scenario's, the debugger's, else inactive)."""
        return self._level(index)

    def input_logic(self, index: int) -> int:
        """Input `index`'s logic state (1 active) through the polarity in force."""
        return self._logic(index)

    # -- the main loop ---------------------------------------------------------------------------

    def _start(self) -> None:
        for name, variable in self.module.variables.items():
            value = self._eval(variable.init) if variable.init is not None else 0
            self.vars[name] = values.store(value, variable.type)
        for n, event in enumerate(self.scenario.events):
            if event.at is not None:
                self._schedule(event.at, "input", (event.input, event.value))
        for incident in self.scenario.incidents:
            self._schedule(incident.at, incident.kind, (incident.axis,))
        entry = self._entry()
        if entry is None or entry.entry is None:
            raise Stop("end", "the module has no routine to run")
        self._event(None, "start", routine=entry.name)
        # Commands sent outside any program (MCode settings before PG, X150 set-up) run first, in
        # the order they were sent (X150 L177: buffered commands run "in sequential order"): the
        # first stretch on top of the stack. When the entry is itself the first stretch (an X150
        # stream without a main sequence), it is one of them, not run after them.
        if entry.kind is not ir.RoutineKind.IMMEDIATE:
            self.stack.append(Frame(entry, entry.entry))
        for routine in reversed(self.module.routines):
            if routine.kind is ir.RoutineKind.IMMEDIATE and routine.entry is not None:
                self.stack.append(Frame(routine, routine.entry))
        if len(self.stack) == 1:
            self._main_starts()

    def _main_starts(self) -> None:
        """The main routine starts its first block: a pass of the main loop when that is its header."""
        frame = self.stack[-1]
        if frame.index == 0 and frame.block.label in self.cycle_headers and not self.trace.cycle_marks:
            self.trace.cycle_marks.append((frame.block.label, self.now))

    def _entry(self) -> ir.Routine | None:
        for kind in (ir.RoutineKind.MAIN, ir.RoutineKind.POWERUP, ir.RoutineKind.IMMEDIATE):
            for routine in self.module.routines:
                if routine.kind is kind and routine.blocks:
                    return routine
        return self.module.routines[0] if self.module.routines else None

    def _loop(self) -> None:
        while True:
            self._fire_pending()
            self._execute()
            if not self.stack:
                if not self.started:  # `run`: the moves still going finish; `advance` lets them later
                    self._settle()
                raise Stop("end", "the program ended")
            wait = self.stack[-1].wait
            nxt = self._next_event_time()
            if wait is not None and wait.kind == "poll":
                moving = any(a.moving(self.now) for a in self.machine.axes.values())
                counting = self.machine.countdown_left(self.now) > 0
                if moving and self.read_continuous:  # it reads a position, a speed or a timer
                    nxt = min(nxt, self.now + self.options.poll)
                elif counting and self.read_continuous:  # the countdown: when a comparison can change
                    nxt = min(nxt, self._countdown_wake())
                elif nxt == INF and moving:  # an axis slews on while the loop sees nothing new
                    nxt = self.options.until + 1
                elif nxt == INF:
                    self._note_repeats()
                    raise Stop("waiting", "the program polls in a loop for a change the scenario never "
                                          f"makes (at line {self._line_now()})")
                self.stack[-1].wait = None
            elif nxt == INF:
                raise Stop("waiting", self._waiting_reason(wait))
            if nxt > self.options.until:
                self.now = max(self.now, self.options.until)
                raise Stop("time-limit", f"the time limit of {self.options.until:g} s was reached")
            self.now = nxt
            self._process_events()

    def _countdown_wake(self) -> float:
        """The next time a loop polling the countdown timer can see a different outcome: when the
        timer crosses a value the program compares it with (or the next tick, when it uses the
        reading otherwise), so that a wait of seconds costs a few rounds, not one per millisecond."""
        machine = self.machine
        start, loaded = machine.countdown
        tick = machine.countdown_tick
        if self.countdown_marks is None:
            return self.now + tick
        times = [start + loaded - mark + extra for mark in self.countdown_marks for extra in (0.0, tick)]
        later = [t for t in times if t > self.now + 1e-12]
        return min(later, default=machine.countdown_end())

    def _settle(self) -> None:
        """After the program ends, moves still running finish (the machine does not stop with the
        program); a slew, which never ends, is left where it is."""
        ends = [a.motion.t_end for a in self.machine.axes.values()
                if a.motion is not None and a.motion.t_end != INF and a.motion.t_end > self.now]
        last = min(max(ends, default=self.now), self.options.until)
        self.pending.clear()
        while self._next_event_time() <= last:
            self.now = max(self.now, self.queue[0].t)
            self._process_events()
            self.pending.clear()  # no program is left to run a handler

    def _waiting_reason(self, wait: Wait | None) -> str:
        line = wait.line if wait is not None and wait.line is not None else self._line_now()
        if wait is None:
            return f"the program waits at line {line}"
        if wait.kind == "input":
            return f"waiting at line {line} for an input the scenario never sets"
        if wait.kind in ("motion", "busy"):
            return f"waiting at line {line} for axis {', '.join(wait.axes)}, which never stops"
        return f"waiting at line {line}"

    def _line_now(self) -> int | None:
        if not self.stack:
            return None
        frame = self.stack[-1]
        ops = frame.block.ops
        item = ops[frame.index] if frame.index < len(ops) else frame.block.terminator
        return _line(getattr(item, "span", None)) or _line(frame.block.span)

    def _schedule(self, t: float, kind: str, payload: tuple = ()) -> None:
        if t == INF:
            return
        self.seq += 1
        heapq.heappush(self.queue, Scheduled((t, self.seq, kind, payload)))

    def _next_event_time(self) -> float:
        while self.queue and self._stale(self.queue[0]):
            heapq.heappop(self.queue)
        return self.queue[0].t if self.queue else INF

    def _stale(self, item: Scheduled) -> bool:
        if item.kind in ("motion_end", "cross"):
            axis = self.machine.axes.get(item.payload[0])
            return axis is None or axis.motion is None or axis.motion.ident != item.payload[1]
        if item.kind == "countdown":  # the timer was loaded again since
            return item.payload[0] != self.machine.countdown
        if item.kind == "timer":
            handler = self.handlers.get("time")
            return handler is None or not handler.armed or handler.fired_at != item.payload[0]
        return False

    def _process_events(self) -> None:
        while self.queue and self.queue[0].t <= self.now:
            item = heapq.heappop(self.queue)
            if self._stale(item):
                continue
            self.changes += 1
            if item.kind == "wake":
                self.wakes += 1
            elif item.kind == "input":
                self._set_input(item.payload[0], item.payload[1])
            elif item.kind == "motion_end":
                self._motion_end(self.machine.axes[item.payload[0]])
            elif item.kind == "cross":
                self._crossing(item.payload)
            elif item.kind == "timer":
                handler = self.handlers["time"]
                self._trigger("time", handler)
            elif item.kind in ("stall", "fault", "power"):
                self._incident(item.kind, item.payload[0])
        self._check_when()

    # -- executing the program -------------------------------------------------------------------

    def _execute(self) -> None:
        """Run the top frame until it waits or the program ends."""
        quiet, last_changes = 0, self.changes - self.var_changes
        round_states: set[tuple] = set()
        vars_seen = self.var_changes
        self.read_continuous = False
        # back from a poll with nothing changed: the loop is still polling, so recognise it sooner
        # and do not count its steps against the step limit (it is waiting, not running away)
        polling = self.polling and self.changes - self.var_changes == self.poll_changes \
            and self.vars == self.poll_vars
        threshold = POLL_RECHECK if polling else self.options.spin
        if not polling:
            self._quiet_begins()
        # read once: none of them is replaced while the program runs (a print loop makes 200,000 steps)
        stack, trace, max_steps, skip_rounds = self.stack, self.trace, self.options.max_steps, self.options.skip_rounds
        # rounds that repeat at this instant are appended rather than run (sim/repeats.py), from
        # `repeats_at` steps on; never under a debugger or single-stepping
        repeats = None  # made when the stretch reaches `repeats_at`
        repeats_at = trace.steps + REPEATS_AFTER \
            if skip_rounds and self.observer is None and self.options.commands is None else INF
        while stack:
            frame = stack[-1]
            if frame.wait is not None:
                if not self._wait_over(frame.wait):
                    return
                retry = frame.wait.retry
                frame.wait = None
                if not retry:
                    continue
            if self.observer is not None:  # a debugger (mcc.debug) may pause here: see `observer`
                ops = frame.block.ops
                self.observer("step", frame, ops[frame.index] if frame.index < len(ops) else frame.block.terminator)
            self.went_back = False
            trace.steps += 1
            if not trace.steps % CANCEL_EVERY:
                cancel.checkpoint()  # the editor's run of a stale version stops (lsp/cycles.py)
            if polling:
                self.poll_steps += 1
            if trace.steps - self.poll_steps > max_steps:
                trace.steps -= 1
                raise Stop("step-limit", f"the step limit of {max_steps} operations was reached "
                                         f"(at line {self._line_now()})")
            ops = frame.block.ops
            if frame.index < len(ops):
                op = ops[frame.index]
                frame.index += 1
                try:
                    wait = OP_METHODS[type(op)](self, op)  # `_op`, without a call more per operation
                except RuntimeFault as fault:
                    self._fault(fault, op)
                    wait = None
                if wait is not None:
                    wait.line = _line(op.span)
                    if wait.retry:
                        frame.index -= 1
                    frame.wait = wait
                    continue
            else:
                try:
                    self._terminator(frame)
                except RuntimeFault as fault:
                    self._fault(fault, frame.block.terminator)
                if self.went_back and skip_rounds and stack and stack[-1] is frame:
                    self._went_round(frame)
            if self.handlers:
                self._check_when()
                self._fire_pending()
            # a change other than a variable's resets the count at once; variables count as
            # changed when, going round, they are not what they were the last time round
            changed = self.changes - self.var_changes != last_changes
            if changed:
                round_states.clear()
            elif self.went_back and self.var_changes != vars_seen:
                # a state (where the loop goes round, every variable) seen before since the last
                # other change: the loop cycles through states it has been in, as a dispatch loop
                # (`WHILE V63!=0` with one IF arm per block) does with its state variable
                vars_seen = self.var_changes
                state = (frame.block.label, tuple(self.vars.items()))
                changed = state not in round_states
                if changed:
                    if len(round_states) >= ROUND_STATES:
                        round_states.clear()
                    round_states.add(state)
            if changed:
                quiet, last_changes = 0, self.changes - self.var_changes
                self._quiet_begins()
                self.read_continuous = False
                polling, threshold = False, self.options.spin
            else:
                quiet += 1
                # a polling loop pauses where it goes round (a jump back), never between two reads
                # of one round: a translation that splits a condition over several statements
                # then sees the inputs change at the same point of the loop as its source
                if quiet >= threshold and stack and self._poll_point():
                    stack[-1].wait = Wait("poll", line=self._line_now())
                    self.polling, self.poll_changes = True, self.changes - self.var_changes
                    self.poll_vars = dict(self.vars)
                    return
            if self.went_back and trace.steps >= repeats_at:
                if repeats is None:
                    repeats = Repeats(self)
                moved_changes, moved_vars = repeats.at_jump_back(quiet, last_changes, vars_seen, round_states,
                                                                 polling, threshold)
                last_changes, vars_seen = last_changes + moved_changes, vars_seen + moved_vars
                repeats_at = repeats.next_at
        self.polling = False

    def _quiet_begins(self) -> None:
        self.quiet_events, self.quiet_step = len(self.trace.events), self.trace.steps

    def _note_repeats(self) -> None:
        """Before a run stops polling for good: when its loop made events in the later half of the
        stretch without a change, those rounds repeat for ever (`Trace.repeats_from`); a loop that
        made a few events and then only polled quietly does not."""
        quiet = self.trace.steps - self.quiet_step
        if self.event_step >= self.quiet_step and self.trace.steps - self.event_step < quiet / 2:
            self.trace.repeats_from = self.quiet_events

    def _poll_point(self) -> bool:
        """Whether a quiet loop pauses here: where it goes round, or `poll_offset` steps later."""
        offset = self.options.poll_offset
        if self.went_back:
            short = 0 <= self.since_back < offset  # a whole round ended before the offset was reached
            self.since_back = 0
            return offset == 0 or short
        if self.since_back >= 0:
            self.since_back += 1
        return offset > 0 and self.since_back == offset

    def _went_round(self, frame: Frame) -> None:
        """Skip the rounds of a delay-paced loop that cannot differ from the one just run.

        A loop that polls with a delay (`WHILE DI1=0 / DELAY=5 / ENDWHILE`) goes round hundreds of
        times a second of virtual time; run one by one, an hour of it costs millions of operations
        though nothing happens. When a round took time but changed nothing (no variable, output,
        print, motion or event other than its own delays ending, and read nothing that changes with
        time, such as a moving position or the timer), the next round starts from the same state and
        does exactly the same: so time jumps over the whole rounds that end before anything else can
        happen (the next scheduled event, the time limit, a ramp ending under a speed reading), and the
        loop runs on normally from there. The jump keeps the loop's phase, so the program sees an input
        change at the same round as when every round runs; a polling round costs the same whatever its
        period (docs/SIMULATOR.md, "Time").
        """
        marks = self.trace.cycle_marks
        mark = RoundMark(frame, frame.block.label, len(self.stack), self.now, self.changes - self.wakes,
                         self.round_delays, len(self.trace.events), len(self.trace.prints), self.trace.steps,
                         len(marks))
        last, self.round = self.round, mark
        reads, self.round_reads, self.round_delays = self.round_reads, set(), []
        if (last is None or last.frame is not frame or last.label != mark.label or last.depth != mark.depth
                or (last.quiet_changes, last.events, last.prints) != (mark.quiet_changes, mark.events, mark.prints)
                or self.pending or frame.wait is not None or not mark.delays):
            return
        period, steps = mark.now - last.now, mark.steps - last.steps
        if period <= 0 or steps <= 0:
            return  # no time passed: a spinning loop is the polling detector's (`Options.spin`)
        horizon = min(self._next_event_time(), self.options.until, self._stable_until(reads))
        rounds = int((horizon - self.now) / period) - 1
        budget = self.options.max_steps - (self.trace.steps - self.poll_steps)
        rounds = min(rounds, budget // steps - 1)  # a run that would hit the step limit still does
        if rounds < 1:
            return
        # the passes of the main loop the round recorded, each after the delays that came before it
        passes = _passes(marks[last.marks:mark.marks], last.now, mark.delays)
        if passes is None:
            return
        now = self.now
        for _ in range(rounds):  # the same additions as round by round: the same times to the last bit
            started = now
            for seconds in mark.delays:
                now += seconds
            if passes:
                times = [started]
                for seconds in mark.delays:
                    times.append(times[-1] + seconds)
                marks.extend((label, times[after]) for label, after in passes)
        self.now = now
        mark.marks = len(marks)
        self.trace.steps += rounds * steps
        self.skipped += rounds * steps
        mark.now, mark.steps = self.now, self.trace.steps

    def _stable_until(self, reads: set[tuple[str, str]]) -> float:
        """Until when the readings a round made keep their values (now: they change with time)."""
        until = INF
        for meaning, name in reads:
            if meaning == "timer" or (meaning == "countdown" and self.machine.countdown_left(self.now) > 0):
                return self.now
            axis = self.machine.axes.get(name)
            if meaning == "moving" or axis is None or not axis.moving(self.now):
                continue  # a motion's end is a scheduled event, which bounds the jump anyway
            if meaning != "velocity" or axis.motion.path.arc is not None:
                return self.now  # a position of a moving axis, or a speed along an arc
            segment = axis.motion.segment_at(self.now)
            if segment.v0 != segment.v1:
                return self.now  # ramping
            until = min(until, segment.t1)
        return until

    def _wait_over(self, wait: Wait) -> bool:
        if wait.kind == "delay":
            return self.now >= wait.until
        if wait.kind in ("motion", "busy"):
            return not any(self._axis(a).moving(self.now) for a in self._expand(wait.axes))
        if wait.kind == "input":
            return self._cond(wait.cond)
        return False  # "poll": the main loop clears it after advancing time

    def _terminator(self, frame: Frame) -> None:
        term = frame.block.terminator
        kind = type(term)  # (the IR's terminators have no subclasses: `is` instead of isinstance)
        if kind is ir.Branch or kind is ir.Jump:
            if kind is ir.Jump:
                target = term.target
            else:
                target = term.then if self._cond(term.cond) else term.otherwise
            block_index = self.block_index
            self.went_back = block_index.get(target, 0) <= block_index.get(frame.block.label, 0)
            frame.block, frame.index = self.block_of[target], 0
            if target in self.cycle_headers and len(self.stack) == 1:
                self.trace.cycle_marks.append((target, self.now))
        elif isinstance(term, ir.Return) or (isinstance(term, ir.FallOff) and len(self.stack) > 1):
            self.stack.pop()
            if frame.routine.kind is ir.RoutineKind.IMMEDIATE and len(self.stack) == 1:
                self._main_starts()
            if frame.routine.kind is not ir.RoutineKind.IMMEDIATE:
                self._event(term, "return", routine=frame.routine.name)
        elif isinstance(term, ir.GotoRoutine):
            routine = self._routine(term.routine)
            frame.routine, frame.block, frame.index = routine, routine.entry, 0
            self.went_back = True
            self._event(term, "goto", routine=routine.name)
        else:  # End, FallOff of the main program, or no terminator
            self.stack.clear()
            self._event(term, "end")

    def _routine(self, name: str) -> ir.Routine:
        routine = self.routines.get(name)
        if routine is None or routine.entry is None:
            raise RuntimeFault("S005", f"routine '{name}' is stored on the controller; its body is not in this "
                                       "file, so it cannot be simulated")
        return routine

    def _push(self, routine: ir.Routine, handler: str = "") -> None:
        if len(self.stack) >= self.nesting + 1:
            raise RuntimeFault("S003", f"stack overflow: calling '{routine.name}' would nest more than "
                                       f"{self.nesting} calls deep", kind="fatal")
        self.stack.append(Frame(routine, routine.entry, handler=handler))

    def _fault(self, fault: RuntimeFault, item) -> None:
        span = getattr(item, "span", None)
        self._event(item, "error", code=fault.code, message=str(fault))
        handler = None
        for event in HANDLER_CHAIN.get(fault.kind, ()):
            found = self.handlers.get(event)
            if found is not None and found.armed and found.routine:
                handler = found
                break
        if handler is not None:
            self.diags.add(fault.code, span or _file_span(self.module.path),
                           f"{fault} (handled by '{handler.routine}')", severity=_severity("warning"))
            if handler.takes_over:
                self.stack.clear()  # the fault sequence replaces the program (a kill ends loops and waits)
                self.pending = [p for p in self.pending if p[0] != "fault"]
            self._trigger(handler.event, handler)
            return
        if self.observer is not None:  # before the run stops: the state is still the error's
            self.observer("fault", self.stack[-1] if self.stack else None, item, fault)
        self.diags.add(fault.code, span or _file_span(self.module.path), str(fault))
        raise Stop("error", f"{fault} (line {_line(span)})")

    # -- operations ------------------------------------------------------------------------------

    def _op(self, op: ir.Op, frame: Frame) -> Wait | None:
        # one handler per operation of the table (compiler/ir_ops.py); tests/ir/test_handlers.py
        # checks that every operation has one, so none is skipped silently
        return OP_METHODS[type(op)](self, op)

    def _do_save(self, op) -> Wait | None:
        """Storing the settings in non-volatile memory changes nothing a run observes."""
        return None

    def _do_assign(self, op) -> Wait | None:
        name = op.target.name
        vtype = self._type(name)
        # an expression assigned to a float64 variable computes in floating point (MCode F1-F8,
        # lexium-mcode.txt L1249, L2834: F1=Q2/Q1 is 1.2)
        try:
            value = values.store(self._eval(op.value, vtype is ir.VarType.FLOAT64), vtype)
        except values.ArithmeticFault as exc:  # a value the variable cannot hold: the run's error
            raise RuntimeFault("S002", str(exc)) from None
        if self.vars.get(name) != value:
            self.changes += 1
            self.var_changes += 1
        self.vars[name] = value
        return None

    def _do_setmotion(self, op) -> Wait | None:
        value = float(self._eval(op.value))
        self.machine.set_motion(op.param, op.axis, value)
        return None

    def _do_move(self, op) -> Wait | None:
        axes = tuple(a for a, _ in op.targets)
        if any(self._axis(a).moving(self.now) for a in self._expand(axes)):
            return Wait("busy", axes=axes, retry=True)
        for name in self._expand(axes):
            self.last_move[name] = op.mode.value
        self._move(op)
        return None

    def _do_arc(self, op) -> Wait | None:
        if any(self._axis(a).moving(self.now) for a in op.axes):
            return Wait("busy", axes=op.axes, retry=True)
        self._arc(op)
        return None

    def _do_slew(self, op) -> Wait | None:
        for name in self._each(op.axis):
            self.last_move[name] = "slew"
            self._slew(op, name)
        return None

    def _do_home(self, op) -> Wait | None:
        names = self._each(op.axis)
        if any(self._axis(name).moving(self.now) for name in names):
            return Wait("busy", axes=tuple(names), retry=True)
        for name in names:
            self._home(op, name)
        return None

    def _do_stop(self, op) -> Wait | None:
        for name in self._expand((op.axis,)):
            self._stop_axis(self._axis(name), op.ramp, op)
        return None

    def _do_setposition(self, op) -> Wait | None:
        value = float(self._eval(op.value))
        for name in self._expand((op.axis,)):
            axis = self._axis(name)
            machine_pos = axis.at(self.now) + axis.offset
            self._cut(axis)
            axis.position, axis.offset = value, machine_pos - value
            self._sample_point(axis)
            self._event(op, "set_position", axis=name, position=value)
        return None

    def _do_waitmotion(self, op) -> Wait | None:
        axes = (op.axis,)
        if any(self._axis(a).moving(self.now) for a in self._expand(axes)):
            return Wait("motion", axes=axes)
        return None

    def _do_delay(self, op) -> Wait | None:
        seconds = float(self._eval(op.duration))
        if seconds > 0:
            self.round_delays.append(seconds)
            self._schedule(self.now + seconds, "wake")
            return Wait("delay", until=self.now + seconds)
        return None

    def _do_setoutput(self, op) -> Wait | None:
        self._set_outputs(op)
        return None

    def _do_waitinput(self, op) -> Wait | None:
        if not self._cond(op.cond):
            return Wait("input", cond=op.cond)
        return None

    def _do_print(self, op) -> Wait | None:
        if op.traced:
            self.commands_run += 1
            if self.options.commands is not None and self.commands_run > self.options.commands:
                raise Stop("step", f"single step: {self.options.commands} commands ran; the next waits for the "
                                   "host's step request")
            if not self._tracing(op.axis):
                return None
        formats = list(op.formats) + [""] * (len(op.items) - len(op.formats))
        text = "".join(self._text(item, op.signed, spec) for item, spec in zip(op.items, formats)) \
            + ("\n" if op.newline else "")
        self.trace.prints.append((self.now, text))
        self.changes += 1
        # a trace report names the program's own commands, which a translation rewrites: its own
        # event kind, which the behaviour oracle does not compare (docs/SIMULATOR.md, "Trace reports")
        self._event(op, "trace" if op.traced else "print", text=text)
        return None

    def _tracing(self, axis: str) -> bool:
        """Whether the `trace` setting is on for the device `axis` names, or for any device when the
        print names none (an unaddressed program: the device that runs it is not known statically)."""
        return any(value for (name, where, _), value in self.settings.items()
                   if name == "trace" and (not axis or where in (axis, ir.ALL_AXES)))

    def _do_driveenable(self, op) -> Wait | None:
        on = 1 if self._eval(op.on) else 0
        for name in self._expand((op.axis,)):
            self._axis(name).enabled = on
        self._event(op, "drive", axis=op.axis, on=on)
        return None

    def _do_call(self, op) -> Wait | None:
        if op.cond is None or self._cond(op.cond):
            routine = self._routine(op.routine)
            self._event(op, "call", routine=routine.name)
            self._push(routine)
        return None

    def _do_sethandler(self, op) -> Wait | None:
        self._set_handler(op)
        return None

    def _do_setting(self, op) -> Wait | None:
        """The settings the model has: which handlers are enabled, which input captures; every
        setting's value is kept for the readings that report it (SETTING_READINGS)."""
        value = self._eval_quiet(op.value) if not isinstance(op.value, ir.Text) else None
        info = ir_names.SETTINGS.get(op.name)
        if isinstance(op.value, ir.Text):
            value = op.value.value  # kept as text: a format, an input's function, read back as written
        elif info is not None and info.value_type == "float" and value is not None:
            value = float(value)
        if value is not None:
            if op.axis == ir.ALL_AXES:  # every device now has this value
                for key in [k for k in self.settings if (k[0], k[2]) == (op.name, op.index)]:
                    del self.settings[key]  # in place: a virtual device keeps this table between runs
            self.settings[(op.name, op.axis, op.index)] = value
        if op.name == "input_function" and op.index is not None:  # which inputs a homing may use
            if isinstance(op.value, ir.Text) and op.value.value == "home":
                self.machine.home_inputs.add(op.index)
            else:
                self.machine.home_inputs.discard(op.index)
        if op.name == "input_active_high" and op.index is not None and value is not None:
            self.active_high[op.index] = bool(value)
            self.changes += 1  # a polling loop reads its inputs anew
        if op.name == "countdown" and value is not None:  # it counts down from now (Arcus TR=n, L789-L793)
            self.machine.load_countdown(self.now, float(value))
            self._schedule(self.machine.countdown_end(), "countdown", (self.machine.countdown,))
        if op.name == "home_accel":
            for name in self._expand((op.axis,)):
                self._axis(name).home_accel = float(value) if value is not None else None
        elif op.name == "home_final_speed":
            for name in self._expand((op.axis,)):
                self._axis(name).home_final_speed = float(value) if value is not None else None
        elif op.name == "handler_enable":
            mask = self._eval_quiet(op.value)
            if mask is not None:
                self._set_enable_mask(op, int(mask))
        elif op.name == "input_function" and isinstance(op.value, ir.Text) and op.value.value == "capture" \
                and self.scenario.capture is None and op.index is not None:
            self.capture_input = op.index
        elif op.name in UNMODELLED and self._eval_quiet(op.value) != 0 and op.name not in self.unmodelled:
            self.unmodelled.add(op.name)
            self.diags.add("S014", op.span or _file_span(self.module.path),
                           f"the setting {op.name} changes how the machine runs ({UNMODELLED[op.name]}), which the "
                           "simulator does not model: it goes on as if the setting were 0")
        return None

    def _do_pause(self, op) -> Wait | None:
        """The host resumes at once (X150 C, MCode RS): what the program does after the pause is the
        same whenever the resume comes. A move a stopping pause catches runs on (S015 says so)."""
        moving = op.stop_motion and any(self._axis(name).moving(self.now) for name in self._expand((op.axis,)))
        self._event(op, "pause", axis=op.axis)
        if not self.paused_once or moving:
            self.paused_once = True
            what = " A move in progress would ramp down and restart on resume; here it runs on." if moving else ""
            self.diags.add("S015", op.span or _file_span(self.module.path),
                           "the program pauses here until the host resumes it; the simulator resumes at once." + what)
        return None

    def _do_resume(self, op) -> Wait | None:
        self._event(op, "resume", axis=op.axis)
        return None

    def _do_step(self, op) -> Wait | None:
        """Single-step mode is not modelled (S014 at its setting): a step request changes nothing."""
        self._event(op, "step", axis=op.axis, value=values.plain(self._eval(op.count)))
        return None

    def _setting_reading(self, meaning: str, axis: str) -> values.Number:
        """A setting read back: the value this run set for the axis (or for every axis); before
        that, the factory default (X150: following at 100 %, L1461; every input and output active
        low, L2120, L3023)."""
        name, default = SETTING_READINGS[meaning]

        def value(index: int | None):
            found = self.settings.get((name, axis, index))
            return found if found is not None else self.settings.get((name, ir.ALL_AXES, index))

        if name == "following_ratio":
            found = value(None)
            return found if found is not None else default
        indices = {index for setting, _, index in self.settings if setting == name and index}
        return sum(1 << (index - 1) for index in indices if value(index))

    def _setting_value(self, name: str, axis: str, index: int | None = None):
        """The value of a setting in force: the one this run set for the axis (or for every axis),
        else the product's (`Module.device_values`), else 0; a float setting reads as a float."""
        found = self.settings.get((name, axis, index))
        if found is None:
            found = self.settings.get((name, ir.ALL_AXES, index))
        if found is None:
            found = next((v for (n, _a, i), v in self.settings.items() if n == name and i == index), None)
        if found is None:
            found = self.module.device_values.get(name, 0)
        info = ir_names.SETTINGS.get(name)
        if info is not None and info.value_type == "float" and isinstance(found, (int, Decimal)):
            return float(found)
        return found

    def _do_native(self, op) -> Wait | None:
        args = [values.plain(v) if (v := self._eval_quiet(a)) is not None else ir_print.expr_text(a)
                for a in op.args]
        self._event(op, "native", dialect=op.dialect, mnemonic=op.mnemonic, args=args, axis=op.axis)
        if op.mnemonic not in self.natives:
            self.natives.add(op.mnemonic)
            self.diags.add("S006", op.span or _file_span(self.module.path),
                           f"{op.dialect} '{op.mnemonic}' has no neutral meaning; the simulator skips it")
        return None


    def _type(self, name: str) -> ir.VarType:
        found = self.types.get(name)
        if found is None:
            declared = self.module.type_of(name)  # the lowering declares variables and registers
            found = self.types[name] = declared if declared is not None else self.default_type
        return found

    def _axis(self, name: str) -> Axis:
        found = self.machine.axes.get(name)
        return found if found is not None else self.machine.axis(name)

    def _each(self, name: str) -> list[str]:
        """The axes an operation on `name` drives: every axis of the machine for ALL_AXES (an
        unaddressed X150 command reaches each device), else the one named."""
        return self._expand((name,)) or [name]

    def _expand(self, axes) -> list[str]:
        out: list[str] = []
        for name in axes:
            if name == ir.ALL_AXES:
                out += [a for a in self.machine.axes if a not in out]
            elif name not in out:
                out.append(name)
        return out

    # -- motion ----------------------------------------------------------------------------------

    def _move(self, op: ir.Move) -> None:
        targets: dict[str, float] = {}
        for name, expr in op.targets:
            value = self._motion_value(expr)
            for axis_name in self._expand((name,)):
                axis = self._axis(axis_name)
                targets[axis_name] = value if op.mode is ir.MoveMode.ABSOLUTE else axis.position + value
        hits = self._beyond_travel(op, targets)
        start = {name: self._axis(name).position for name in targets}
        deltas = {name: targets[name] - start[name] for name in targets}
        length = math.sqrt(sum(d * d for d in deltas.values()))
        self._event(op, "move", mode=op.mode.value, **{"from": dict(start)}, to=dict(targets))
        self.travel_hit.update(hits)
        if length == 0:
            for name in hits:
                self._travel_stop(self._axis(name))
            return
        lead = self._axis(next(iter(targets)))
        path = Path(start, length, {name: d / length for name, d in deltas.items()})
        self._begin(op, path, lead.limits(self.machine.shared), targets=targets, plan_length=length)

    def _beyond_travel(self, op, targets: dict[str, float]) -> dict[str, tuple]:
        """The axes a move would take past their travel, each target cut to the end it reaches."""
        hits = {}
        for name, target in targets.items():
            low, high = self.travel.get(name, (None, None))
            end = high if high is not None and target > high else low if low is not None and target < low else None
            if end is not None:
                hits[name] = (op, target, end)
                targets[name] = end
        return hits

    def _travel_stop(self, axis: Axis) -> None:
        """The axis reached its end of travel: the limit switch stops it, and the run (S017)."""
        op, target, end = self.travel_hit.pop(axis.name)
        span = getattr(op, "span", None)
        asked = f"the move asked for {target:g}" if target != end else "it was running at a constant speed"
        message = (f"axis {axis.name} reached its end of travel at {end:g} ({asked}): the limit "
                   "switch stops it here; keep the axis inside its travel ([tool.mcc.axes] min/max)")
        self._event(op, "travel", axis=axis.name, position=_round(end), target=_round(target))
        self.diags.add("S017", span or _file_span(self.module.path), message)
        raise Stop("travel", f"{message} (line {_line(span)})")

    def _motion_value(self, expr) -> float:
        """A move target or slew speed: a float value rounded down where the product says so
        (MCode `MA F5`, `SL=F2`: "rounded down to the nearest integer", lexium-mcode.txt L2815)."""
        value = self._eval(expr)
        if self.motion_floor and isinstance(value, float) and math.isfinite(value):
            return float(math.floor(value))
        return float(value)

    def _arc(self, op: ir.Arc) -> None:
        ax, ay = op.axes
        cx, cy = float(self._eval(op.center[0])), float(self._eval(op.center[1]))
        x0, y0 = self._axis(ax).position, self._axis(ay).position
        radius = math.hypot(x0 - cx, y0 - cy)
        degrees = float(self._eval(op.angle)) if op.angle is not None else None
        angle0 = math.atan2(y0 - cy, x0 - cx)
        sweep = _sweep(angle0, degrees, op.clockwise)
        length = radius * abs(sweep)
        end = (cx + radius * math.cos(angle0 + sweep), cy + radius * math.sin(angle0 + sweep))
        self._event(op, "arc", axes=[ax, ay], center=[cx, cy], degrees=degrees, clockwise=op.clockwise)
        if length == 0:
            return
        path = Path({ax: x0, ay: y0}, length, arc=(ax, ay, cx, cy, radius, angle0, sweep))
        self._begin(op, path, self._axis(ax).limits(self.machine.shared), targets={ax: end[0], ay: end[1]},
                    plan_length=length)

    def _slew(self, op: ir.Slew, name: str) -> None:
        axis = self._axis(name)
        lim = axis.limits(self.machine.shared)
        velocity = self._motion_value(op.velocity) if op.velocity is not None else op.direction * lim.maximum
        current = axis.speed(self.now)
        # the same slew again (a loop that keeps commanding it) changes nothing: no event, so a
        # loop doing only that is recognised as polling and time can pass
        if velocity == self.slewing.get(name, 0.0 if not axis.moving(self.now) else None):
            return
        self._event(op, "slew", axis=name, velocity=velocity)
        start = axis.at(self.now)
        self._cut(axis)
        if velocity == 0:
            segments = plan_stop(self.now, abs(current), lim.decel, lim.smooth)
            direction = 1.0 if current >= 0 else -1.0
            length = sum(s.length for s in segments)
        else:
            direction = 1.0 if velocity > 0 else -1.0
            v_from = abs(current) if (current >= 0) == (velocity > 0) else 0.0
            segments = plan_slew(self.now, v_from, abs(velocity), lim.accel, lim.smooth)
            length = INF
        if not segments:
            return
        path = Path({name: start}, length, {name: direction})
        self._install(op, path, segments, None)
        self.slewing[name] = velocity

    def _home(self, op: ir.Home, name: str) -> None:
        """Homing as the IR says (docs/SIMULATOR.md, "Homing"): seek the switch, brake past it,
        creep back onto its edge when the operation creeps toward it, and zero the counter where
        `op.zero` says. The seek runs toward the switch from whichever side it lies (a device that
        seeks away from it reverses at a limit; that detour is not modelled)."""
        if op.needs_input and not self.machine.home_inputs:
            raise RuntimeFault("S016", "the homing needs an input set up as the home switch (input function "
                                       "'home'), and none is: set one up before homing")
        axis = self._axis(name)
        switch = self.scenario.switches(name).home
        self._event(op, "home", axis=name, method=op.method)
        limits = axis.limits(self.machine.shared)
        # (Limits built field by field: dataclasses.replace costs a tenth of a homing loop's run)
        if op.speed is not None:  # a homing speed of its own, not the max speed
            limits = Limits(limits.initial, abs(float(self._eval(op.speed))), limits.accel, limits.decel,
                            limits.smooth)
        ramp = axis.home_accel  # the program's homing acceleration, else the operation's (0: at once)
        if ramp is None and op.accel is not None:
            ramp = abs(float(self._eval(op.accel)))
        if ramp is not None:
            limits = Limits(limits.initial, limits.maximum, ramp, ramp, limits.smooth)
        creep = 0.0
        if op.creep:
            if op.creep_speed is not None:  # the product's final speed, unless the program set its own
                creep = axis.home_final_speed if axis.home_final_speed is not None \
                    else abs(float(self._eval(op.creep_speed)))
            else:
                creep = limits.initial
            if creep <= 0:
                raise RuntimeFault("S007", "the homing would creep off the switch at speed 0 and never end "
                                           "(set the initial speed first)")
        run = HomeRun(op, switch, limits, creep)
        delta = switch - (axis.position + axis.offset)
        if delta == 0:  # on the switch already: it trips at once
            before = (axis.position, axis.offset)
            still = axis.homed == (*before, self.motion_ids)  # where the last homing ended
            count = len(self.trace.events)
            self._home_tripped(axis, run, 0.0)
            if still and axis.homing is None and (axis.position, axis.offset) == before:
                for event in self.trace.events[count - 1:]:  # it changed nothing, as a move to where
                    if event.kind in ("home", "home_end"):  # the axis is does not (sim/verify.py)
                        event.data["idle"] = True
            return
        try:
            segments, speed = plan_seek(self.now, abs(delta), limits)
        except ValueError as exc:
            raise RuntimeFault("S007", f"{exc} (set a maximum speed first)") from None
        run.direction = 1.0 if delta > 0 else -1.0
        self._home_phase(axis, run, "seek", abs(delta), segments)
        run.speed = speed

    def finish_homing(self, until: float) -> None:
        """Run on the homing phases a finished program left going, up to `until`: each phase starts
        when the one before ends, so a caller that freezes the machine after the program (the
        virtual device between commands) must let them follow one another first."""
        for axis in self.machine.axes.values():
            while axis.on_end == "home" and axis.motion is not None and axis.motion.t_end <= until:
                self.now = max(self.now, axis.motion.t_end)
                self._motion_end(axis)

    def _home_phase(self, axis: Axis, run: HomeRun, stage: str, length: float, segments) -> None:
        start = axis.position
        path = Path({axis.name: start}, length, {axis.name: run.direction})
        self._install(run.op, path, segments, {axis.name: start + run.direction * length})
        run.stage = stage
        axis.on_end, axis.homing = "home", run

    def _home_next(self, axis: Axis) -> None:
        """A phase of the homing has ended: go on with the next one."""
        run = axis.homing
        if run.stage == "seek":
            self._home_tripped(axis, run, run.speed)
        elif run.stage == "brake":
            self._home_creep(axis, run)
        else:
            self._home_done(axis, run)

    def _home_tripped(self, axis: Axis, run: HomeRun, speed: float) -> None:
        """The switch trips with the axis at `speed`: zero here if so told, then brake past it."""
        if run.op.zero == "switch":
            axis.position, axis.offset = axis.position + axis.offset - run.switch, run.switch
        segments = plan_brake(self.now, speed, run.limits.initial, run.limits.decel, run.limits.smooth)
        if segments:
            self._home_phase(axis, run, "brake", segments[0].length, segments)
        else:
            self._home_creep(axis, run)

    def _home_creep(self, axis: Axis, run: HomeRun) -> None:
        """Creep in the operation's direction until the switch is left: back onto its edge when the
        creep goes toward it; a creep away from a switch already passed ends at once."""
        back = run.switch - (axis.position + axis.offset)
        if run.op.creep and back * run.op.creep > 0:
            run.direction = float(run.op.creep)
            self._home_phase(axis, run, "creep", abs(back), plan_creep(self.now, abs(back), run.creep))
        else:
            self._home_done(axis, run)

    def _home_done(self, axis: Axis, run: HomeRun) -> None:
        if run.op.zero == "end":
            axis.position, axis.offset = 0.0, axis.position + axis.offset
        axis.on_end, axis.homing = "", None
        axis.homed = (axis.position, axis.offset, self.motion_ids)
        machine = axis.position + axis.offset
        self._event(run.op, "home_end", axis=axis.name, position=_round(axis.position), machine=_round(machine),
                    zero=_round(axis.offset))

    def _begin(self, op, path: Path, lim: Limits, targets: dict[str, float], plan_length: float) -> None:
        try:
            segments = plan(self.now, plan_length, lim)
        except ValueError as exc:
            raise RuntimeFault("S007", f"{exc} (set a maximum speed first)") from None
        self._install(op, path, segments, targets)

    def _install(self, op, path: Path, segments, targets) -> None:
        self.motion_ids += 1
        motion = Motion(self.motion_ids, path, segments, targets)
        self.motion_op[motion.ident] = op
        self.changes += 1
        names = list(path.start)
        for name in names:
            self.slewing.pop(name, None)
            axis = self._axis(name)
            axis.motion = motion
            axis.on_end = ""
            self._schedule(motion.t_end, "motion_end", (name, motion.ident))
            self._watch(axis)

    def _watch(self, axis: Axis) -> None:
        """Schedule the crossings of watched machine positions by the axis's current motion."""
        motion = axis.motion
        if motion is None or motion.path.arc is not None:
            return
        rate = motion.path.direction.get(axis.name, 0.0)
        if rate == 0:
            return
        base = motion.path.start[axis.name] + axis.offset
        s_now = motion.distance(self.now)
        for key, where in self._watched(axis.name):
            s = (where - base) / rate
            if s > s_now + 1e-9 and s <= motion.path.length + 1e-9:
                t = motion.time_at(s)
                if t != INF:
                    self._schedule(max(t, self.now), "cross", (axis.name, motion.ident, key, where))

    def _watched(self, name: str) -> list[tuple[tuple, float]]:
        fixed = self.fixed_watches.get(name)
        if fixed is None:
            fixed = self.fixed_watches[name] = self._fixed_watches(name)
        out = list(fixed)
        axis = self._axis(name)
        if name in self.travel and axis.motion is not None and axis.motion.path.length == INF:
            # a slew runs until something stops it: its end of travel (a move is cut to it in _move)
            offset = axis.offset
            for end, where in zip(("min", "max"), self.travel[name]):
                if where is not None:
                    out.append((("travel", end), where + offset))
        handler = self.handlers.get("position")
        if handler is not None and handler.armed and handler.args and name == self._handler_axis():
            try:
                out.append((("handler", "position"), float(self._eval(handler.args[0]))))
            except RuntimeFault:
                pass
        return out

    def _fixed_watches(self, name: str) -> list[tuple[tuple, float]]:
        """The scenario's positions on axis `name`: inputs set when it passes, limit switches."""
        out: list[tuple[tuple, float]] = []
        for n, event in enumerate(self.scenario.events):
            if event.at is None and event.axis == name:
                out.append((("scenario", n), event.passes))
        switches = self.scenario.switches(name)
        if switches.limit_plus is not None:
            out.append((("limit", "plus"), switches.limit_plus))
        if switches.limit_minus is not None:
            out.append((("limit", "minus"), switches.limit_minus))
        return out

    def _handler_axis(self) -> str:
        """The axis position handlers watch: the module's first axis (MCode has one)."""
        return next(iter(self.machine.axes), "1")

    def _crossing(self, payload: tuple) -> None:
        name, _, key, where = payload
        axis = self.machine.axes[name]
        if key[0] == "scenario":
            event = self.scenario.events[key[1]]
            self._set_input(event.input, event.value, passes=where, axis=name)
        elif key[0] == "limit":
            op = self.motion_op.get(axis.motion.ident) if axis.motion else None
            self._stop_axis(axis, False, None, record=False)
            axis.fault = 1
            self._event(op, "limit", axis=name, switch=key[1], position=axis.position)
            self._fault(RuntimeFault("S004", f"axis {name} hit its {key[1]} limit switch at {where:g} steps",
                                     kind="fault"), op)
        elif key[0] == "travel":
            op = self.motion_op.get(axis.motion.ident) if axis.motion else None
            self._stop_axis(axis, False, None, record=False)
            end = where - axis.offset
            self.travel_hit[name] = (op, end, end)
            self._travel_stop(axis)
        elif key[0] == "handler":
            handler = self.handlers.get("position")
            if handler is not None and handler.armed:
                self._trigger("position", handler)

    def _incident(self, kind: str, axis_name: str) -> None:
        """A scenario's stall, drive fault or power loss (docs/SIMULATOR.md, "Incidents")."""
        if kind == "power":
            for axis in list(self.machine.axes.values()):
                self._stop_axis(axis, False, None, record=False)
            self._event(None, "power_loss")
            self._fault(RuntimeFault("S013", "the main power was lost", kind="power"), None)
            return
        names = [axis_name] if axis_name else list(self.machine.axes)
        running = None  # the move that was running: the diagnostic's line
        for name in names:
            axis = self._axis(name)
            op = self.motion_op.get(axis.motion.ident) if axis.motion else None
            running = running or op
            self._stop_axis(axis, False, None, record=False)
            if kind == "stall":
                axis.stalled = 1
            axis.fault = 1
            self._event(op, kind, axis=name, position=_round(axis.at(self.now)))
        what = f"axis {axis_name}" if axis_name else "the drive"
        if kind == "stall":
            self._fault(RuntimeFault("S011", f"{what} stalled", kind="stall"), running)
        else:
            self._fault(RuntimeFault("S012", f"{what} reported a fault", kind="fault"), running)

    def _motion_end(self, axis: Axis) -> None:
        motion = axis.motion
        if motion is None:
            return
        self._sample_motion(axis, motion, motion.t_end)
        end = motion.positions(motion.t_end)
        axis.position = end[axis.name]
        axis.motion = None
        if axis.on_end == "home":
            axis.on_end = ""
            self._home_next(axis)
        else:
            self._event(self.motion_op.get(motion.ident), "move_end", axis=axis.name,
                        position=_round(axis.position))
        if not any(a.motion is motion for a in self.machine.axes.values()):
            self.motion_op.pop(motion.ident, None)
        if axis.name in self.travel_hit:
            self._travel_stop(axis)

    def _cut(self, axis: Axis) -> None:
        """End the axis's motion now where it is (before a new motion or a position change)."""
        motion = axis.motion
        if motion is None:
            return
        for name in list(motion.path.start):
            other = self._axis(name)
            if other.motion is motion:
                self._sample_motion(other, motion, self.now)
                other.position = motion.positions(self.now)[name]
                other.motion = None
                other.on_end = ""
                self.slewing.pop(name, None)

    def _stop_axis(self, axis: Axis, ramp: bool, op, record: bool = True) -> None:
        moving = axis.moving(self.now)
        if record:
            self._event(op, "stop", axis=axis.name, ramp=ramp, **({} if moving else {"idle": True}))
        if not moving:
            return
        speed = axis.motion.speed(self.now)
        names = list(axis.motion.path.start)
        motion = axis.motion
        lim = axis.limits(self.machine.shared)
        s_now = motion.distance(self.now)
        self._cut(axis)
        if not ramp or motion.path.arc is not None:
            return
        segments = plan_stop(self.now, speed, lim.decel, lim.smooth)
        if not segments:
            return
        length = segments[0].length
        start = {n: self._axis(n).position for n in names}
        path = Path(start, length, {n: motion.path.axis_rate(n, s_now) for n in names})
        self._install(op, path, segments, None)

    def _sample_point(self, axis: Axis) -> None:
        if self.options.samples:
            self.trace.points.append((axis.name, self.now, axis.at(self.now)))

    def _sample_motion(self, axis: Axis, motion: Motion, until: float) -> None:
        if self.options.samples:
            self.trace.motion_log.append((axis.name, motion, until))

    # -- inputs, outputs, handlers ---------------------------------------------------------------

    def _level(self, index: int) -> int:
        """Input `index`'s electrical level: the scenario's, else the inactive level of the polarity
        in force (an input nothing drives is not active, whichever way it is wired)."""
        level = self.machine.inputs.get(index)
        if level is None:
            if self.idle_level is not None:  # the product's inputs rest at a level (pulled up)
                return self.idle_level
            return 0 if self.active_high.get(index, self.active_high_default) else 1
        return level

    def _logic(self, index: int) -> int:
        """Input `index`'s logic state (1 active): its level through the polarity the program set,
        else the product's (MCode I1-I4 are low-active by default, lexium-mcode.txt L3273, L3500)."""
        level = self._level(index)
        return level if self.active_high.get(index, self.active_high_default) else 1 - level

    def _levels(self) -> int:
        """Every input's level as a bit mask, input 1 in bit 0 (MCode IN, L3433-L3435)."""
        # the product's own inputs: a scenario may drive more (the source's, in a conversion), which
        # a device with fewer does not read (MCode IN: inputs 1-4, L3433; Arcus DI: 1-8, L797)
        top = self.input_count or max(self.machine.inputs, default=0)
        return sum(1 << (n - 1) for n in range(1, top + 1) if self._level(n))

    def _set_input(self, index: int, value: int, **where) -> None:
        old = self._logic(index)
        self.machine.inputs[index] = value
        self._event(None, "input", input=index, value=value, **where)
        value = self._logic(index)  # capture and input handlers fire on the logic state
        if old != value:
            self.changes += 1
            capture = self.capture_input if self.capture_input is not None else DEFAULT_CAPTURE_INPUT
            if index == capture and value == 1:
                self._event(None, "capture", input=index,
                            positions={n: _round(a.at(self.now)) for n, a in self.machine.axes.items()})
                handler = self.handlers.get("capture")
                if handler is not None and handler.armed:
                    self._trigger("capture", handler)
            handler = self.handlers.get("input")
            if handler is not None and handler.armed:
                wanted = handler.args
                index_ok = not wanted or self._eval_quiet(wanted[0]) == index
                level = self._eval_quiet(wanted[1]) if len(wanted) > 1 else 1
                if index_ok and value == level:
                    self._trigger("input", handler)

    def _set_outputs(self, op: ir.SetOutput) -> None:
        changed: dict[int, int] = {}
        if op.index is not None:
            changed[op.index] = 1 if self._eval(op.value) else 0
        elif isinstance(op.value, ir.Pattern):
            for n, bit in enumerate(op.value.bits, 1):
                if bit in "01":
                    changed[n] = int(bit)
        else:
            mask = int(self._eval(op.value))
            # a device sets the outputs it has: Arcus DO outputs 1-8 (arcus-pmx-4ex-sa.txt L757), MCode
            # OT outputs 1-3 (lexium-mcode.txt L851, L4669); unknown: every bit up to the eighth
            top = self.output_count or max([8, mask.bit_length(), *self.machine.outputs])
            for n in range(1, top + 1):
                changed[n] = (mask >> (n - 1)) & 1
        for n, v in changed.items():
            if self.machine.outputs.get(n) != v:
                self.changes += 1
                self.machine.outputs[n] = v
                self._event(op, "output", output=n, value=v)

    def _set_handler(self, op: ir.SetHandler) -> None:
        handler = self.handlers.get(op.event)
        if op.routine is None and not op.args:
            if handler is not None:
                handler.armed = False
            self._event(op, "handler_off", event=op.event)
            return
        if handler is None:
            handler = self.handlers[op.event] = Handler(op.event, op.routine, op.args)
        if op.routine is not None:
            handler.routine = op.routine
        if op.args:
            handler.args = op.args
        handler.once, handler.gated, handler.takes_over = op.once, op.gated, op.takes_over
        handler.armed = self._enabled(handler)
        handler.last = False
        self._event(op, "handler_on", event=op.event, routine=handler.routine)
        if op.event == "time" and handler.args:
            handler.fired_at = self.now
            self._schedule(self.now + float(self._eval(handler.args[0])), "timer", (self.now,))
        elif op.event == "position":
            axis = self.machine.axes.get(self._handler_axis())
            if axis is not None:
                self._watch(axis)
        elif op.event == "when":
            self._check_when()

    def _enabled(self, handler: Handler) -> bool:
        """Whether a handler may fire: a gated one (an MCode trip) only while its TE bit is set."""
        if not handler.gated or handler.event not in ENABLE_BITS:
            return True
        return bool(self.enable_mask & ENABLE_BITS[handler.event])

    def _set_enable_mask(self, op, mask: int) -> None:
        self.enable_mask = mask
        for event, handler in self.handlers.items():
            if event in ENABLE_BITS and handler.routine:
                was = handler.armed
                handler.armed = self._enabled(handler)
                if handler.armed and not was:
                    if event == "position":
                        axis = self.machine.axes.get(self._handler_axis())
                        if axis is not None:
                            self._watch(axis)
                    elif event == "time" and handler.args:
                        handler.fired_at = self.now
                        self._schedule(self.now + float(self._eval(handler.args[0])), "timer", (self.now,))
        self._event(op, "handler_enable", mask=mask)

    def _trigger(self, event: str, handler: Handler) -> None:
        if not handler.routine:
            return
        if event not in ("position", "relative") and self.machine.axes:  # PC: any trip but TP, TR (L4717-L4743)
            self.captured = _round(next(iter(self.machine.axes.values())).at(self.now))
        if handler.once or event in ONCE_EVENTS:
            handler.armed = False
            if handler.gated and event in ENABLE_BITS:
                self.enable_mask &= ~ENABLE_BITS[event]  # a fired trip clears its TE bit (L5657)
        self.pending.append((event, handler))

    def _fire_pending(self) -> None:
        while self.pending and not any(f.handler for f in self.stack):
            event, handler = self.pending.pop(0)
            try:
                routine = self._routine(handler.routine)
                self._event(None, "handler", event=event, routine=routine.name)
                self._push(routine, handler=event)
            except RuntimeFault as fault:
                self._fault(fault, None)

    def _check_when(self) -> None:
        handler = self.handlers.get("when")
        if handler is None or not handler.armed or not handler.args:
            return
        cond = handler.args[0]
        try:
            now = self._cond(cond) if not isinstance(cond, (ir.Const, ir.Var, ir.Status, ir.BinOp)) \
                else bool(self._eval(cond))
        except RuntimeFault:
            return
        if now and not handler.last:
            handler.last = True
            self._trigger("when", handler)
        elif not now:
            handler.last = False

    # -- expressions -----------------------------------------------------------------------------

    def _eval(self, expr, real: bool = False) -> values.Number:
        """The value of `expr`; `real`: computed in floating point (an expression assigned to a
        float64 variable), integers taken as floats before any operator applies."""
        if isinstance(expr, ir.Const):
            return expr.value
        if isinstance(expr, ir.Var):
            if expr.name not in self.vars:
                self.vars[expr.name] = values.store(0, self._type(expr.name))
            return self.vars[expr.name]
        if isinstance(expr, ir.BinOp):
            left = self._eval(expr.left, real)
            right = self._eval(expr.right, real)
            if real:
                left, right = values.real(left), values.real(right)
            elif self.default_type is ir.VarType.DECIMAL and expr.op in ("/", "%") \
                    and isinstance(left, int) and isinstance(right, int):
                left = Decimal(left)  # X150 computes in decimals: 1/3 of two literals too
            try:
                return values.binary(expr.op, left, right, self.division)
            except values.ArithmeticFault as exc:
                raise RuntimeFault("S002", str(exc)) from None
        if isinstance(expr, ir.UnOp):
            return values.unary(expr.op, self._eval(expr.operand, real))
        if isinstance(expr, ir.Func):
            try:
                radians = bool(self._setting_value("trig_radians", "")) if expr.name in TRIG else False
                return values.function(expr.name, [self._eval(a, real) for a in expr.args], radians)
            except values.ArithmeticFault as exc:
                raise RuntimeFault("S002", str(exc)) from None
        if isinstance(expr, ir.Status):
            return self._reading(expr)
        if isinstance(expr, ir.Pattern):
            return sum(1 << n for n, bit in enumerate(expr.bits) if bit == "1")
        raise RuntimeFault("S008", f"{type(expr).__name__} has no numeric value")

    def _eval_quiet(self, expr):
        try:
            return self._eval(expr)
        except RuntimeFault:
            return None

    def _reading(self, status: ir.Status) -> values.Number:
        meaning, index = status.meaning, status.index
        m = self.machine
        if meaning == "input":
            return self._logic(index or 0)
        if meaning == "inputs":  # the raw levels (MCode IN, lexium-mcode.txt L3433-L3435)
            return self._levels() if self.input_count else m.input_mask()
        if meaning == "output":
            return m.outputs.get(index or 0, 0)
        if meaning == "outputs":
            return m.output_mask()
        if meaning == "analog":
            return m.analog.get(index or 0, 0)
        if meaning == "timer":
            self.read_continuous = True
            self.round_reads.add((meaning, ""))
            return self.now
        if meaning == "countdown":
            left = m.countdown_left(self.now)
            if left > 0:  # it changes with time until it reaches 0 (a scheduled event)
                self.read_continuous = True
                self.round_reads.add((meaning, ""))
            # whole ticks in seconds, exactly: `countdown * 1000` (Arcus V1=TR) is then whole ms
            return Decimal(repr(left)) if left != int(left) else int(left)
        if meaning in SETTING_READINGS:
            return self._setting_reading(meaning, status.axis or ir.ALL_AXES)
        if meaning in ir_names.SETTINGS:  # a setting read back (docs/SIMULATOR.md, "Drive registers")
            return self._setting_value(meaning, status.axis, index)
        if meaning in UNCAUSED:  # the identity is a text: none when the profile gives none
            return self.module.device_values.get(meaning, "" if meaning in ("part_number", "firmware_version") else 0)
        if meaning == "captured_position":
            return self.captured
        if meaning == "last_move":
            return self.last_move.get(self._each(status.axis or self._handler_axis())[0], "")
        axis = self._axis(self._each(status.axis or self._handler_axis())[0])  # '*': the first device's
        if meaning in CONTINUOUS:
            self.read_continuous = True
            self.round_reads.add((meaning, axis.name))
        if meaning in ("position", "encoder"):
            return _round(axis.at(self.now))
        if meaning == "device_address":  # a numbered device's address; 0 for an axis with a letter
            return int(axis.name) if axis.name.isdigit() else 0
        if meaning in ("velocity", "measured_velocity"):  # no slip: the encoder measures the velocity
            return axis.speed(self.now)
        if meaning == "moving":
            return 1 if axis.moving(self.now) else 0
        if meaning == "moving_to_position":   # a move to a position runs (a slew is not one)
            return 1 if axis.moving(self.now) and axis.motion is not None and axis.motion.t_end != float("inf") else 0
        if meaning == "velocity_changing":  # the speed changes: a ramp runs (MCode VC, L6047-L6079)
            self.read_continuous = True
            self.round_reads.add(("velocity", axis.name))
            return 1 if axis.moving(self.now) and abs(axis.speed(self.now + 1e-6) - axis.speed(self.now)) > 1e-9 else 0
        if meaning == "resolution":  # steps per revolution in force
            return values.plain(axis.settings.get(ir.MotionParam.RESOLUTION, self.module.steps_per_rev))
        if meaning == "fault":
            return axis.fault
        if meaning == "enabled":
            return axis.enabled
        if meaning == "error":
            return 1 if axis.fault else 0
        if meaning == "home_switch":
            self.round_reads.add(("position", axis.name))
            return 1 if abs(axis.at(self.now) + axis.offset - self.scenario.switches(axis.name).home) < 0.5 else 0
        if meaning in ("limit_plus", "limit_minus"):
            return 0 if not axis.fault else 1
        if meaning == "accel_time" or (meaning in ("max_speed", "initial_speed") and m.shared.get("sets")):
            return m.register(ir.MotionParam(meaning), status.axis or ir.ALL_AXES)
        if meaning in ("max_speed", "initial_speed", "accel", "decel"):
            lim = axis.limits(m.shared)
            return {"max_speed": lim.maximum, "initial_speed": lim.initial, "accel": lim.accel,
                    "decel": lim.decel}[meaning]
        if meaning == "stalled":
            return axis.stalled
        return 0

    def _cond(self, cond) -> bool:
        if isinstance(cond, ir.Compare):
            left, right = self._eval(cond.left), self._eval(cond.right)
            return values.compare(cond.op, left, right)
        if isinstance(cond, ir.Logic):
            # left to right, the right only when the left does not decide (a division by zero on
            # the right of a false `and` does not fault): how the backends write it, nested IFs
            left = self._cond(cond.left)
            if left == (cond.op == "or"):
                return left
            return self._cond(cond.right)
        if isinstance(cond, ir.Truth):
            return self._eval(cond.expr) != 0
        if isinstance(cond, ir.InputMatch):
            for n, bit in enumerate(cond.pattern.bits, 1):
                if bit in "01" and self._logic(n) != int(bit):
                    return False
            return True
        if isinstance(cond, ir.Not):
            return not self._cond(cond.cond)
        return self._eval(cond) != 0

    def _text(self, item, signed: bool = False, spec: str = "") -> str:
        if isinstance(item, ir.Text):
            return item.value
        if spec:  # a print format (docs/IR.md, "Print formats")
            return values.formatted(self._eval(item), spec, signed)
        texts = self.module.print_texts.get(item.meaning) if isinstance(item, ir.Status) else None
        if texts is not None:  # a reading printed as the device writes its values (MCode PR MD)
            value = self._eval(item)
            return texts.get(value, str(value))
        fmt = self._float_format()
        if fmt and self._reads_float(item):
            return values.float_text(float(self._eval(item)), fmt, self.float_pad)
        value = values.plain(self._eval(item))
        if isinstance(value, str):  # a text setting or reading (a format, the device's identity)
            return value
        text = str(int(value)) if isinstance(value, float) and value.is_integer() else str(value)
        return "+" + text if signed and not text.startswith("-") else text  # `Print.signed`: +0, +4000

    def _reads_float(self, item) -> bool:
        """Whether a printed item reads a float64 variable or a float setting: then it prints in
        the product's float format (MCode PF, lexium-mcode.txt L4744-L4777). Asked once per item
        (`float_items`: the item is the module's, alive as long as the run)."""
        found = self.float_items.get(id(item))
        if found is None:
            found = self.float_items[id(item)] = any(
                isinstance(node, ir.Var) and self._type(node.name) is ir.VarType.FLOAT64
                or isinstance(node, ir.Status) and getattr(ir_names.SETTINGS.get(node.meaning), "value_type",
                                                           "") == "float"
                for node in ir.walk_expr(item))
        return found

    def _float_format(self):
        """The float format in force: the `float_format` setting the run set, else the product's
        (`[machine.arithmetic] float_print`)."""
        found = next((v for (n, _a, _i), v in self.settings.items() if n == "float_format"), None)
        parsed = values.float_format(found) if found is not None else None
        return parsed or self.float_format

    # -- the trace -------------------------------------------------------------------------------

    def _event(self, item, kind: str, **data) -> None:
        if self.polling and kind in QUIET_KINDS:
            return  # a polling loop's calls and returns would fill the trace with nothing new
        if kind not in QUIET_KINDS:
            self.event_step = self.trace.steps
        self.trace.events.append(Event(self.now, kind, _line(getattr(item, "span", None)), data))

    def _finish(self) -> None:
        for axis in self.machine.axes.values():
            if axis.motion is not None:
                self._sample_motion(axis, axis.motion, min(self.now, axis.motion.t_end))
            self._sample_point(axis)
        self.trace.time = self.now
        self.trace.axes = {name: _round(axis.at(self.now)) for name, axis in self.machine.axes.items()}
        self.trace.outputs = dict(self.machine.outputs)
        self.trace.variables = {name: values.plain(v) for name, v in self.vars.items()}
        self.trace.events.append(Event(self.now, "stopped", None, {"stopped": self.trace.stopped,
                                                                     "reason": self.trace.reason}))


def _passes(made: list[tuple[str, float]], start: float, delays: list[float]) -> list[tuple[str, int]] | None:
    """The passes of the main loop a round recorded (`made`, with their times), each as its header
    and the number of the round's delays before it: the round started at `start` and its time
    advanced by `delays`, in order. None when a time is not one of those sums (the round cannot be
    repeated by adding its delays)."""
    times = [start]
    for seconds in delays:
        times.append(times[-1] + seconds)
    out, after = [], 0
    for label, t in made:
        while after < len(times) and times[after] != t:
            after += 1
        if after == len(times):
            return None
        out.append((label, after))
    return out


def loop_headers(routine: ir.Routine | None) -> dict[str, int]:
    """The blocks of the main routine a later block jumps back to (loop headers), by position: a
    pass through the outermost one is a machine cycle (sim/cycles.py)."""
    if routine is None:
        return {}
    index = {block.label: n for n, block in enumerate(routine.blocks)}
    out: dict[str, int] = {}
    for n, block in enumerate(routine.blocks):
        term = block.terminator
        targets = (term.target,) if isinstance(term, ir.Jump) else (term.then, term.otherwise) \
            if isinstance(term, ir.Branch) else ()
        for target in targets:
            if target in index and index[target] <= n:
                out[target] = index[target]
    return out


def countdown_marks(module: ir.Module) -> frozenset[float] | None:
    """The readings of the countdown timer (seconds) the program compares it with: `countdown`
    (times a constant) against a constant. None when it uses the reading any other way."""
    marks: set[float] = set()
    for _, block in module.blocks():
        exprs = [e for op in block.ops for e in ir.op_exprs(op)] + list(ir.term_exprs(block.terminator))
        for expr in exprs:
            compared: set[int] = set()
            for node in ir.walk_expr(expr):
                if isinstance(node, ir.Compare):
                    for side, other in ((node.left, node.right), (node.right, node.left)):
                        scale = _countdown_scale(side)
                        if scale and isinstance(other, ir.Const):
                            marks.add(float(other.value) / scale)
                            compared.update(id(n) for n in ir.walk_expr(side))
                elif isinstance(node, ir.Status) and node.meaning == "countdown" and id(node) not in compared:
                    return None
    return frozenset(marks)


def _countdown_scale(expr) -> float | None:
    """k when `expr` is the countdown reading times the constant k (1 for the reading alone)."""
    if isinstance(expr, ir.Status) and expr.meaning == "countdown":
        return 1.0
    if isinstance(expr, ir.BinOp) and expr.op == "*":
        for a, b in ((expr.left, expr.right), (expr.right, expr.left)):
            if isinstance(a, ir.Status) and a.meaning == "countdown" and isinstance(b, ir.Const) and b.value:
                return float(b.value)
    return None


OP_METHODS = {
    ir.Assign: Simulator._do_assign,
    ir.SetMotion: Simulator._do_setmotion,
    ir.Move: Simulator._do_move,
    ir.Arc: Simulator._do_arc,
    ir.Slew: Simulator._do_slew,
    ir.Home: Simulator._do_home,
    ir.Stop: Simulator._do_stop,
    ir.SetPosition: Simulator._do_setposition,
    ir.WaitMotion: Simulator._do_waitmotion,
    ir.Delay: Simulator._do_delay,
    ir.SetOutput: Simulator._do_setoutput,
    ir.WaitInput: Simulator._do_waitinput,
    ir.Print: Simulator._do_print,
    ir.DriveEnable: Simulator._do_driveenable,
    ir.Call: Simulator._do_call,
    ir.SetHandler: Simulator._do_sethandler,
    ir.Native: Simulator._do_native,
    ir.Setting: Simulator._do_setting,
    ir.Pause: Simulator._do_pause,
    ir.Resume: Simulator._do_resume,
    ir.Step: Simulator._do_step,
    ir.Save: Simulator._do_save,
}


def _round(value: float) -> float:
    """Positions as the trace reports them: exact steps when the float is within 1e-6 of one."""
    nearest = round(value)
    return float(nearest) if abs(value - nearest) < 1e-6 else value


def _line(span: Span | None) -> int | None:
    return span.line if span is not None else None


def _file_span(path: str) -> Span:
    return Span(path or "<ir>", 1, 1, 1, 1, 0, 0)


def _severity(name: str):
    from mcc.compiler.diagnostics import Severity

    return Severity(name)


def _sweep(start: float, degrees: float | None, clockwise: bool) -> float:
    """The signed angle (radians, counter-clockwise positive) an arc turns through from the
    direction `start` (radians, from the centre) to its end: `degrees` is the end point's
    direction from the centre, measured clockwise from the negative first axis (docs/IR.md,
    "Arcs"); the arc runs in its direction for less than a turn, a full turn when the end is the
    start or when it has no end angle (a circle)."""
    turn = 2 * math.pi
    if degrees is None:
        return -turn if clockwise else turn
    theta = math.radians(degrees)
    end = math.atan2(math.sin(theta), -math.cos(theta))  # clockwise from (-1, 0): (-cos, sin)
    sweep = ((start - end) if clockwise else (end - start)) % turn
    if sweep < 1e-9 or turn - sweep < 1e-9:
        sweep = turn
    return -sweep if clockwise else sweep


def machine_table(profile, name: str) -> dict:
    """The profile's `[machine.<name>]` table ({} without one): the product's machine as data."""
    table = profile.get(f"machine.{name}", {}) if profile is not None else {}
    return table if isinstance(table, dict) else {}


def profile_of(module: ir.Module):
    """The built-in profile the module names, or None (a user's profile file is not known here)."""
    from mcc.compiler.profiles import ProfileError, load

    try:
        return load(module.profile) if module.profile else None
    except ProfileError:
        return None


def simulate(module: ir.Module, scenario: Scenario | None = None, options: Options | None = None,
             profile=None, checked: bool = False) -> Trace:
    """Run `module` (which must keep the IR contract) and return its trace."""
    return Simulator(module, scenario, options, profile, checked).run()


__all__ = ["ContractError", "Options", "Simulator", "simulate"]
