"""Rounds that repeat at one instant, appended to the trace instead of run.

A loop that makes events without ever waiting (a PRINT loop, a HOME on a switch that is already
active, over and over at one instant) runs until the step limit: 200,000 operations for a
validation run, about half a second each in Python, for every scenario and both sides of every
compile (issue 26: most of the time of the test suite's random programs).

Within one stretch of the run (`Simulator._execute`, until the program waits) virtual time does not
pass, so nothing outside the program can change what it does: the interpreter is a deterministic
machine over its own state. When a jump back finds the run in exactly the state of an earlier jump
back, every round from then on does what the rounds between the two did, to the bit. The state is
everything the simulator holds (variables, frames, settings, axes, outputs, handlers, scheduled
events, what it has reported once), compared as pickled bytes, with the IR and the run's fixed
inputs (module, scenario, options, profile) by identity, and the counters the interpreter keeps only
to compare with each other (changes, steps, events made) taken relative to each other. Byte-equal
state is the same state (pickling tells 1 from 1.0 and 0.0 from -0.0); two equal states that
pickle differently (a dict filled in another order) are only a repeat not seen, which costs time,
never a wrong trace.

The whole rounds that fit before the step limit, less one, are then appended to the trace (their
events, prints and marks) and counted in the steps and the counters, instead of run; the last rounds
run normally, so the run stops at the same operation, with the same reason, as when every round
runs. `Options.skip_rounds` off runs every round (tests/sim/test_sim_repeats.py compares the two on
generated programs); a debugger's observer and single-stepping (`Options.commands`) turn it off too.
"""

from __future__ import annotations

import io
import pickle
from dataclasses import dataclass

from mcc.compiler import cancel
from mcc.sim.trace import Event

# The simulator's fields that a run never changes (the module and its indexes, the scenario, the
# options, the profile's arithmetic): left out of the state, so that the IR is not pickled each time.
FIXED = frozenset({
    "module", "scenario", "options", "routines", "block_of", "block_index", "product", "division", "motion_floor",
    "float_format", "float_pad", "active_high_default", "idle_level", "input_count", "output_count",
    "countdown_marks", "default_type", "cycle_headers", "travel", "nesting", "observer", "trace",
})
# Counters the simulator compares only with each other (or with a value taken from themselves):
# left out of the state, their differences in it, and moved on by the replayed rounds.
COUNTERS = ("changes", "var_changes", "wakes", "seq", "motion_ids", "commands_run", "skipped", "poll_steps",
            "poll_changes", "quiet_events", "quiet_step", "event_step")
# The trace's lists a round appends to.
TRACE_LISTS = ("events", "prints", "diagnostics", "motion_log", "points", "cycle_marks")
AFTER = 4096  # steps of one stretch before its jumps back are compared (most stretches are shorter)
MARKS = 256  # states kept; when full, they are dropped and the next look is twice as far away
IR_MODULE = "mcc.compiler.ir"


@dataclass
class Mark:
    """What the run had done at a jump back: the counters, the trace's lengths and the locals of
    `_execute` that count (`last_changes`, `vars_seen`)."""

    steps: int
    counters: tuple[int, ...]
    lengths: tuple[int, ...]
    last_changes: int
    vars_seen: int


def _ir_object(ident: int) -> None:
    """Stands for an IR object in a pickled state (never called: the state is only compared)."""


def _by_identity(obj) -> tuple:
    return _ir_object, (id(obj),)


class _StatePickler(pickle.Pickler):
    """Pickles the IR (operations, blocks, routines, conditions, its enums) by identity: the run
    never changes it. Through the dispatch table, so that the other objects cost no Python call."""

    dispatch_table = {}

    @classmethod
    def know_ir(cls) -> None:
        if not cls.dispatch_table:
            from mcc.compiler import ir

            cls.dispatch_table = {kind: _by_identity for kind in vars(ir).values()
                                  if isinstance(kind, type) and kind.__module__ == IR_MODULE}


class Repeats:
    """The states of one stretch's jumps back, and the replay of the rounds between two equal ones."""

    def __init__(self, sim) -> None:
        self.sim = sim
        # where each loop went round (its frames and variables, a cheap necessary condition of the
        # same state): None the first time, then the whole state the second time, compared the third
        self.places: dict[tuple, tuple[bytes, Mark] | None] = {}
        self.gap = AFTER
        # `_execute` makes this object AFTER steps into a stretch, and calls `at_jump_back` from
        # `next_at` on: at once, then later each time the places fill up
        self.next_at = sim.trace.steps

    def at_jump_back(self, quiet: int, last_changes: int, vars_seen: int, round_states: set, polling: bool,
                     threshold: int) -> tuple[int, int]:
        """Called where a loop went round, with `_execute`'s locals as the next step sees them.
        Answers how far `last_changes` and `vars_seen` move (0, 0 when nothing was replayed)."""
        sim = self.sim
        place = (tuple((id(frame.block), frame.index) for frame in sim.stack), tuple(sim.vars.items()))
        if place not in self.places:
            if len(self.places) >= MARKS:  # a loop whose variables keep changing: look again later
                self.places.clear()
                self.gap *= 2
                self.next_at = sim.trace.steps + self.gap
            self.places[place] = None
            return 0, 0
        key = self._state(quiet, last_changes, vars_seen, round_states, polling, threshold)
        if key is None:  # something in the state does not pickle: no replay in this stretch
            self.next_at = float("inf")
            return 0, 0
        mark = Mark(sim.trace.steps, tuple(getattr(sim, name) for name in COUNTERS),
                    tuple(len(getattr(sim.trace, name)) for name in TRACE_LISTS), last_changes, vars_seen)
        earlier = self.places[place]
        if earlier is None or earlier[0] != key:
            self.places[place] = (key, mark)
            return 0, 0
        self.places.clear()
        self.next_at = float("inf")  # the rounds left run normally, up to the step limit
        return self._replay(earlier[1], mark)

    def _state(self, quiet, last_changes, vars_seen, round_states, polling, threshold) -> bytes | None:
        sim = self.sim
        trace = sim.trace
        base, steps, events, prints = sim.changes - sim.var_changes, trace.steps, len(trace.events), len(trace.prints)
        state = {name: value for name, value in sim.__dict__.items() if name not in FIXED and name not in COUNTERS}
        mark = sim.round
        if mark is not None:
            state["round"] = (mark.frame, mark.label, mark.depth, mark.now, mark.quiet_changes - (sim.changes - sim.wakes),
                              mark.delays, mark.events - events, mark.prints - prints, mark.steps - steps,
                              mark.marks - len(trace.cycle_marks))
        # (the changes when polling began count only while it polls: `_execute` compares them then)
        relative = (sim.poll_changes - base if sim.polling else None, sim.quiet_events - events, sim.quiet_step - steps,
                    sim.event_step - steps, quiet, last_changes - base, vars_seen - sim.var_changes, round_states,
                    polling, threshold)
        out = io.BytesIO()
        _StatePickler.know_ir()
        try:
            _StatePickler(out, protocol=pickle.HIGHEST_PROTOCOL).dump((state, relative))
        except (pickle.PicklingError, TypeError, AttributeError, RecursionError):
            return None
        return out.getvalue()

    def _replay(self, earlier: Mark, now: Mark) -> tuple[int, int]:
        sim = self.sim
        trace = sim.trace
        poll_at = COUNTERS.index("poll_steps")
        counted = (now.steps - earlier.steps) - (now.counters[poll_at] - earlier.counters[poll_at])
        if counted <= 0:  # the rounds do not count against the step limit: the poll detector's
            return 0, 0
        rounds = (sim.options.max_steps - (trace.steps - sim.poll_steps)) // counted - 1
        if rounds < 1:
            return 0, 0
        for name, start, end in zip(TRACE_LISTS, earlier.lengths, now.lengths):
            items = getattr(trace, name)
            piece = items[start:end]
            if name == "events":
                items.extend(Event(e.t, e.kind, e.line, dict(e.data)) for _ in range(rounds) for e in piece)
            else:
                items.extend(piece * rounds)
        for name, before, after in zip(COUNTERS, earlier.counters, now.counters):
            setattr(sim, name, getattr(sim, name) + rounds * (after - before))
        steps = rounds * (now.steps - earlier.steps)
        trace.steps += steps
        sim.skipped += steps  # (never run; the counter's own growth over a round is 0 here)
        if sim.round is not None:
            mark = sim.round
            events = now.lengths[TRACE_LISTS.index("events")] - earlier.lengths[TRACE_LISTS.index("events")]
            prints = now.lengths[TRACE_LISTS.index("prints")] - earlier.lengths[TRACE_LISTS.index("prints")]
            quiet = (now.counters[0] - earlier.counters[0]) - (now.counters[2] - earlier.counters[2])
            passes = now.lengths[TRACE_LISTS.index("cycle_marks")] - earlier.lengths[TRACE_LISTS.index("cycle_marks")]
            mark.events += rounds * events
            mark.prints += rounds * prints
            mark.marks += rounds * passes
            mark.steps += steps
            mark.quiet_changes += rounds * quiet
        cancel.checkpoint()  # the editor's run of a stale version still stops (lsp/cycles.py)
        return rounds * (now.last_changes - earlier.last_changes), rounds * (now.vars_seen - earlier.vars_seen)
