"""The machine behind a virtual device: mcc.sim's machine, kept between commands.

A virtual device stores programs as text (what its host protocol documents) and runs them, and the
immediate commands it receives, through the simulator (`mcc.sim`): it compiles the text with
mcc's own frontend into the IR and hands the module to `sim.interpreter.Simulator`, on one
`sim.machine.Machine` that lives as long as the device (positions, settings, outputs, inputs) and
one table of variables. The device's replies to status, position and variable queries read that
state, so there is a single interpreter for programs in mcc.

Virtual time (docs/LINK.md, "Running a program"): the device's clock advances only while it runs
something. A command that runs on the machine is run to its end in virtual time before the device
answers it: until the program ends and its moves have finished, until it waits for something
nothing on a virtual device can cause (an input no one sets), until `run_limit` virtual
seconds have passed, or after MAX_STEPS operations (a loop that never waits). No time passes
between commands. A run that did not end leaves the
program "running" (MCode BY=1, X150 busy, Arcus SASTAT 1) with the machine frozen where it was; a
later command starts from that state, and a stop command ends the program.
"""

from __future__ import annotations

import copy
import dataclasses
from dataclasses import dataclass, field

from mcc.compiler import ir
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


class DeviceMachine:
    """The simulator's machine and variables of one virtual device, and the state of its program."""

    def __init__(self, dialect: str, run_limit: float = RUN_LIMIT, profile=None) -> None:
        self.dialect = dialect
        self.run_limit = run_limit
        self.profile = profile if profile is not None else default_profile(dialect)
        self.machine = Machine()
        for axis in (self.profile.axes if self.profile is not None else ()):
            self.machine.axis(axis)   # the product's axes exist from power-up, as in `mcc sim`
        self.variables: dict[str, int | float] = {}
        # the settings the commands and programs set (an input's polarity, a register's value), kept
        # from one run to the next as the drive keeps them: the simulator's `settings` and
        # `active_high` tables of every run are these
        self.settings: dict[tuple[str, str, int | None], object] = {}
        self.active_high: dict[int, bool] = {}
        self.clock = 0.0                      # virtual seconds the device has run
        self.status = "idle"                  # of the program: idle | running | error
        self.reason = ""
        self.moving: dict[str, float] = {}    # axis -> speed, for axes still moving when the last run stopped
        self.slewing: dict[str, float] = {}   # axis -> velocity, for slews (jogs) that run on between commands
        self.last: Trace | None = None       # the trace of the last run
        self.outcome: Outcome | None = None   # how the last run (a program or a command) ended
        # the device settings the runs set (the simulator's `settings`: (name, axis, index) -> value)
        # and the input polarities: a device keeps them from one command or program to the next,
        # so the host reads back what a stored program set and a report reads what earlier
        # commands set
        self.settings: dict = {}
        self.active_high: dict[int, bool] = {}

    # -- the state the host protocol reads -------------------------------------------------------
    def position(self, axis: str) -> float:
        found = self.machine.axes.get(axis)
        return found.position if found is not None else 0.0

    def positions(self) -> dict[str, float]:
        return {name: axis.position for name, axis in self.machine.axes.items()}

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
        """The program is stopped (a stop command): it no longer runs and nothing moves."""
        self.status, self.reason = "idle", "stopped"
        self.moving.clear()
        self.slewing.clear()

    # -- running ---------------------------------------------------------------------------------
    def snapshot(self) -> dict:
        """The device's state, to run a program again from it (single step: each step request
        replays the program from where it started, up to one more command)."""
        return copy.deepcopy({"machine": self.machine, "variables": self.variables, "settings": self.settings,
                              "active_high": self.active_high, "clock": self.clock})

    def restore(self, state: dict) -> None:
        state = copy.deepcopy(state)
        self.machine, self.variables, self.settings = state["machine"], state["variables"], state["settings"]
        self.active_high, self.clock = state["active_high"], state["clock"]

    def run(self, module: ir.Module, entry: tuple[str, str | None] | None = None, program: bool = True,
            commands: int | None = None) -> Outcome:
        """Run `module` from `entry` (see `starting_at`) on the device's machine and variables.
        `program`: this run is the device's program (its end sets the program's status); an
        immediate command runs on the same machine without changing the program's status."""
        module = self._slews_go_on(starting_at(module, entry))
        for name in variables_used(module):
            if name not in self.variables:
                continue
            declared = module.variables.get(name)
            vtype = module.type_of(name) or module.default_type or ir.VarType.FLOAT64  # registers: the lowering's
            scope = declared.scope if declared is not None else "global"
            module.variables[name] = ir.Variable(name, vtype, ir.Const(self.variables[name]), scope)
        options = Options(until=self.run_limit, max_steps=MAX_STEPS, samples=False, commands=commands)
        try:
            simulator = Simulator(module, Scenario(inputs=dict(self.machine.inputs)), options, self.profile)
        except ContractError as exc:
            return self._ended(Outcome("error", f"cannot run: {exc}"), program)
        self.machine.shared["defaults"] = defaults(module.steps_per_rev, simulator.product)
        self.machine.shared["sets"] = tuple(module.axis_sets)
        simulator.machine = self.machine      # the device's machine: what earlier commands left
        simulator.settings = self.settings
        simulator.active_high = self.active_high
        self.moving.clear()
        self.slewing.clear()
        try:
            trace = simulator.run()
        except Exception as exc:  # noqa: BLE001 - a device keeps answering; the run is reported failed
            for axis in self.machine.axes.values():
                axis.motion, axis.on_end = None, ""
            return self._ended(Outcome("error", f"internal error in the simulator ({type(exc).__name__}: {exc}); "
                                                "this is a bug in mcc, please report it"), program)
        self.last = trace
        self.settings, self.active_high = simulator.settings, simulator.active_high
        simulator.finish_homing(max(self.run_limit, trace.time))  # its phases follow one another
        end = trace.time
        if trace.stopped == "end":
            # The program ended while moves it started were still running: they go on to their
            # end, or up to the run limit (the trace stops at the program's end when the moves
            # would finish after the limit).
            ends = [a.motion.t_end for a in self.machine.axes.values()
                    if a.motion is not None and end < a.motion.t_end < float("inf")]
            end = min(max(ends, default=end), max(self.run_limit, end))
        self.clock += end
        # the countdown timer ran for the same time; the next run starts its clock at 0 again
        self.machine.countdown = (0.0, self.machine.countdown_left(end))
        for name, axis in self.machine.axes.items():
            if axis.motion is not None:       # freeze: no virtual time passes between commands
                if axis.moving(end):
                    self.moving[name] = axis.speed(end)
                    if axis.motion.t_end == float("inf"):   # a slew: it reports the speed it runs at
                        self.moving[name] = self.slewing[name] = axis.speed(end + 3600.0)
                axis.position = round(axis.at(end), 6)
                axis.motion = None
                axis.on_end = ""
        self.variables.update(trace.variables)
        prints = [text for _t, text in trace.prints]
        status = {"end": "idle", "error": "error"}.get(trace.stopped, "running")
        return self._ended(Outcome(status, trace.reason, trace, prints), program)

    def _slews_go_on(self, module: ir.Module) -> ir.Module:
        """A slew left running by an earlier command runs on: the run starts by commanding it
        again (from rest: the machine was frozen between the two commands)."""
        if not self.slewing:
            return module
        for index, routine in enumerate(module.routines):
            if routine.kind is ir.RoutineKind.MAIN or (routine.kind is ir.RoutineKind.IMMEDIATE and not any(
                    r.kind is ir.RoutineKind.MAIN for r in module.routines)):
                first = routine.blocks[0]
                slews = [ir.Slew(axis, ir.Const(velocity, ir.Unit.STEPS_PER_S))
                         for axis, velocity in self.slewing.items()]
                blocks = [dataclasses.replace(first, ops=slews + list(first.ops)), *routine.blocks[1:]]
                module.routines[index] = dataclasses.replace(routine, blocks=blocks)
                break
        return module

    def _ended(self, outcome: Outcome, program: bool) -> Outcome:
        self.outcome = outcome
        if program:
            self.status, self.reason = outcome.status, outcome.reason
        return outcome
