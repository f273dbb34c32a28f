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

Counters (sim/round_counters.py: X150's hidden `%Lk`, which `L` without a count decrements for
ever) make every state new, so they are left out of the compared state and their values kept in the marks; two marks
that differ only by them are replayed when the rounds cannot tell the difference (`_counted`): each
moved counter moved the way all its steps go, no reset of it is reachable in a round
(`round_blocks`), none of the constants it is compared with lies within the values it takes, and
`_execute`'s `round_states` end as running every round leaves them (`_states`). The replay then
moves each counter on by `rounds * (after - before)`, stopping short of the first constant it
would meet (the rounds from there run, and it looks again after them).
"""

from __future__ import annotations

import io
import pickle
from dataclasses import dataclass

from mcc.compiler import cancel, ir
from mcc.sim.round_counters import counters_of, round_blocks, short_of
from mcc.sim.trace import Event

# The simulator's fields that a run never changes (the module and its indexes, the scenario, the
# options, the profile's arithmetic): left out of the state, so that the IR is not pickled each time.
FIXED = frozenset({
    "module", "scenario", "options", "routines", "block_of", "block_index", "product", "division", "motion_floor",
    "float_format", "float_pad", "active_high_default", "idle_level", "input_count", "output_count",
    "countdown_marks", "default_type", "cycle_headers", "travel", "nesting", "observer", "trace",
    "repeat_counters",
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
    values: tuple  # the counters' values (`Counter`), in the order of `Repeats.counters`
    hits: int  # the times going round found a state `_execute` had seen (`Repeats.hits`)
    states: frozenset | None  # `_execute`'s `round_states` when the module has counters
    frames: tuple  # the frames themselves (a frame called again is a new one)


INT32 = (-2**31, 2**31 - 1)


def _shifted(state: tuple, moved: dict[str, int], times: int) -> tuple:
    """A state of `round_states` with the moved counters `times` rounds further on."""
    label, items = state
    return label, tuple((name, value + times * moved[name]) if name in moved else (name, value)
                        for name, value in items)


def _states(earlier: Mark, now: Mark, moved: dict[str, int]) -> tuple[bool, list] | None:
    """How the rounds change `_execute`'s `round_states`, when every later round changes it as the
    round between the two marks did with the counters further on: (True, []) when the round
    left the same states with the counters moved on, (False, added) when it added the states
    `added` (in the order it added them) and every later round adds them, moved on, as new
    states; else None.

    `_execute` looks up the state (the block, every variable) where a loop goes round with
    variables changed and adds it when it is new, and empties the states at any change other
    than a variable's, and when they are full. When the round turned the states into themselves
    with the counters moved on, the next round, whose every state is the same with the counters
    moved on, finds in them what the first found and leaves them the same way again. Otherwise:
    the round found no state it had seen (`hits`) and emptied none (the earlier states are all
    still there), so it added the difference. One moved counter then tells every state apart:
    its values in the added states are all different, ahead of those of the states before, and
    closer together than it moves in a round; the states of the next rounds are the same states
    with it further on, so they are new too, and added in the order it reaches them."""
    if {_shifted(state, moved, 1) for state in earlier.states} == now.states:
        return True, []
    if now.hits != earlier.hits or not earlier.states <= now.states:
        return None
    added = now.states - earlier.states
    if not added:  # no state looked up: none in the next rounds either
        return False, []
    for name, delta in moved.items():
        sign = 1 if delta > 0 else -1
        values = [dict(items).get(name) for _, items in added]
        if None in values or len(set(values)) != len(values) or sign * (max(values) - min(values)) >= abs(delta):
            continue
        first = min(values) if sign > 0 else max(values)
        if all(sign * (first - value) > 0 for value in (dict(items).get(name) for _, items in earlier.states)
               if value is not None):
            return False, sorted(added, key=lambda state: sign * dict(state[1])[name])
    return None


def _add_states(round_states: set, added: list, moved: dict[str, int], rounds: int) -> None:
    """Make `round_states` what the `rounds` replayed rounds leave in it: each adds `added` with
    the moved counters further on, and `_execute` empties it when it is full before an addition."""
    from mcc.sim.interpreter import ROUND_STATES

    total = rounds * len(added)
    first = 1  # the first addition still there at the end
    free = ROUND_STATES - len(round_states)
    if total > free:
        round_states.clear()
        first = free + 1 + (total - free - 1) // ROUND_STATES * ROUND_STATES
    for n in range(first, total + 1):
        round_, index = divmod(n - 1, len(added))
        round_states.add(_shifted(added[index], moved, round_ + 1))


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
        if sim.repeat_counters is None:  # the module's, worked out once per run (a run has many stretches)
            sim.repeat_counters = counters_of(sim.module, sim._type)
        self.counters = sim.repeat_counters
        self.names = frozenset(self.counters)
        self.pickled = 0  # states pickled since the places were last emptied
        self.exact: dict[tuple, tuple[bytes, Mark]] = {}  # the states by place and counters
        # the times `_execute` found the state it went round in among its `round_states` (it
        # looks them up at a jump back where variables changed; found, it counts a quiet step)
        self.hits = 0
        self.seen: int | None = None  # `vars_seen` at the last call

    def at_jump_back(self, quiet: int, last_changes: int, vars_seen: int, round_states: set, polling: bool,
                     threshold: int) -> tuple[int, int]:
        """Called where a loop went round, with `_execute`'s locals as the next step sees them.
        Answers how far `last_changes` and `vars_seen` move (0, 0 when nothing was replayed)."""
        sim = self.sim
        if self.seen is not None and vars_seen != self.seen and quiet > 0:
            self.hits += 1
        self.seen = vars_seen
        frames = tuple((id(frame.block), frame.index) for frame in sim.stack)
        names = self.names
        # (a counter's value is left out: rounds that differ only by their counters repeat)
        place = (frames, tuple(item for item in sim.vars.items() if item[0] not in names) if names
                 else tuple(sim.vars.items()))
        if place not in self.places:
            if len(self.places) >= MARKS:  # a loop whose variables keep changing: look again later
                self._later()
            self.places[place] = None
            return 0, 0
        key = self._state(quiet, last_changes, vars_seen, round_states, polling, threshold)
        if key is None:  # something in the state does not pickle: no replay in this stretch
            self.next_at = float("inf")
            return 0, 0
        mark = Mark(sim.trace.steps, tuple(getattr(sim, name) for name in COUNTERS),
                    tuple(len(getattr(sim.trace, name)) for name in TRACE_LISTS), last_changes, vars_seen,
                    tuple(sim.vars.get(name) for name in self.counters), self.hits,
                    frozenset(round_states) if names else None, tuple(sim.stack) if names else ())
        # the last state at this point with the same counters (a loop that cycles through
        # them, as an outer loop around a counted inner one), then the last with any
        exact = (place, mark.values)
        same, last = self.exact.get(exact), self.places[place]
        for earlier in (same, last) if same is not last else (same,):
            if earlier is None or earlier[0] != key:
                continue
            moved = self._replay(earlier[1], mark, round_states)
            if moved is None:  # the counters forbid it: look on
                continue
            self.places.clear()
            self.exact.clear()
            self.pickled = 0
            if self.next_at <= sim.trace.steps:  # the rounds left run normally, up to the step limit
                self.next_at = float("inf")
            self.seen = vars_seen + moved[1]
            return moved
        self.places[place] = self.exact[exact] = (key, mark)
        self.pickled += 1
        if self.pickled >= MARKS:  # a place that comes back in another state each time
            self._later()
        return 0, 0

    def _later(self) -> None:
        """Forget the places and look again twice as far away: the cost of looking stays a small
        part of the run."""
        self.places.clear()
        self.exact.clear()
        self.pickled = 0
        self.gap *= 2
        self.next_at = self.sim.trace.steps + self.gap

    def _state(self, quiet, last_changes, vars_seen, round_states, polling, threshold) -> bytes | None:
        sim = self.sim
        trace = sim.trace
        base, steps, events, prints = sim.changes - sim.var_changes, trace.steps, len(trace.events), len(trace.prints)
        state = {name: value for name, value in sim.__dict__.items() if name not in FIXED and name not in COUNTERS}
        names = self.names
        if names:
            state["vars"] = {name: value for name, value in sim.vars.items() if name not in names}
            # (the states the loop went round in hold the counters: `_counted` compares them)
            round_states = None
        mark = sim.round
        if mark is not None:
            state["round"] = (mark.frame, mark.label, mark.depth, mark.now, mark.quiet_changes - (sim.changes - sim.wakes),
                              mark.delays, mark.events - events, mark.prints - prints, mark.steps - steps,
                              mark.marks - len(trace.cycle_marks))
        # (the changes when polling began count only while it polls: `_execute` compares them then)
        relative = (sim.poll_changes - base if sim.polling else None, sim.quiet_events - events, sim.quiet_step - steps,
                    # (the last event's step counts only once quiet began: `_note_repeats`)
                    sim.event_step - steps if sim.event_step >= sim.quiet_step else None, quiet, last_changes - base, vars_seen - sim.var_changes, round_states,
                    polling, threshold)
        out = io.BytesIO()
        _StatePickler.know_ir()
        try:
            _StatePickler(out, protocol=pickle.HIGHEST_PROTOCOL).dump((state, relative))
        except (pickle.PicklingError, TypeError, AttributeError, RecursionError):
            return None
        return out.getvalue()

    def _counted(self, earlier: Mark, now: Mark, rounds: int) -> tuple[int, dict[str, int], tuple | None]:
        """How many of `rounds` can be replayed given the counters, how far each counter that
        moved between the two marks moves in a round, and the states a round adds to
        `_execute`'s `round_states` (`_states`).

        Only steps of one sign move a counter in these rounds: none of its resets can run in them
        (`round_blocks`), and its steps go the way it moved. So over the rounds it moves one way,
        the values of each round between the values the round starts and ends with; while it
        meets none of the constants it is compared with, and stays an int32, every comparison
        has the outcome it had in the rounds that ran, and the rounds do the same thing, only
        with the counter further on (`_states` for `round_states`)."""
        ends = {name: (before, after) for name, before, after in zip(self.counters, earlier.values, now.values)
                if before != after}
        moved: dict[str, int] = {}
        if not ends:  # the counters are as they were: so must be the states `_execute` saw
            return (rounds if earlier.states == now.states else 0), moved, None
        for name, (before, after) in ends.items():
            if type(before) is not int or type(after) is not int:
                return 0, {}, None
            moved[name] = after - before
        signs = {name: 1 if delta > 0 else -1 for name, delta in moved.items()}
        # the frames that ran in the round: from the one below the lowest frame made anew (a
        # frame called again is a new object; one never popped is the same)
        same = [old is new for old, new in zip(earlier.frames, now.frames)] + [False]
        lowest = max(same.index(False) - 1, 0)
        # until a reset, a counter moves from its start one way, at most its largest step at each
        # of the round's operations
        ranges = {}
        for name, (before, _) in ends.items():
            reach = (now.steps - earlier.steps) * max((abs(step) for step in self.counters[name].steps), default=0)
            ranges[name] = (before, before + reach) if signs[name] > 0 else (before - reach, before)
        blocks = round_blocks(self.sim.module, [id(frame.block) for frame in now.frames[lowest:]], ranges)
        for name, (before, after) in ends.items():
            counter, delta = self.counters[name], moved[name]
            if any(step * signs[name] < 0 for step in counter.steps) or any(block in blocks for block in counter.resets):
                return 0, moved, None
            low, high = min(before, after), max(before, after)
            for bound in (*counter.compared, INT32[0] - 1, INT32[1] + 1):
                if low <= bound <= high:
                    return 0, moved, None
                rounds = min(rounds, short_of(bound, after, delta))
        states = _states(earlier, now, moved)
        return (rounds if states is not None else 0), moved, states

    def _replay(self, earlier: Mark, now: Mark, round_states: set) -> tuple[int, int] | None:
        """Replays the rounds between two marks of the same state (the counters aside); answers
        how far `last_changes` and `vars_seen` move, or None when the counters forbid it. Sets
        `next_at` when a counter stopped it short of a constant."""
        sim = self.sim
        trace = sim.trace
        poll_at = COUNTERS.index("poll_steps")
        counted = (now.steps - earlier.steps) - (now.counters[poll_at] - earlier.counters[poll_at])
        if counted <= 0:  # the rounds do not count against the step limit: the poll detector's
            return 0, 0
        rounds = (sim.options.max_steps - (trace.steps - sim.poll_steps)) // counted - 1
        if rounds < 1:
            return 0, 0
        fit = rounds
        rounds, moved, added = self._counted(earlier, now, rounds)
        if rounds < 1:
            return None
        self.next_at = float("inf")
        if rounds < fit:  # a counter would meet a constant it is compared with: look again after it
            self.next_at = trace.steps
        for name, delta in moved.items():
            sim.vars[name] += rounds * delta
        if added is not None and added[0]:  # the states the loop went round in, moved on
            shifted = {_shifted(state, moved, rounds) for state in round_states}
            round_states.clear()
            round_states.update(shifted)
        elif added is not None and added[1]:
            _add_states(round_states, added[1], moved, rounds)
        for name, start, end in zip(TRACE_LISTS, earlier.lengths, now.lengths):
            items = getattr(trace, name)
            piece = items[start:end]
            if name == "events":
                items.extend(Event(e.t, e.kind, e.line, dict(e.data)) for _ in range(rounds) for e in piece)
            else:
                items.extend(piece * rounds)
        # (an event before quiet began stays before it, which is all `_note_repeats` asks)
        before_quiet = sim.event_step < sim.quiet_step
        for name, before, after in zip(COUNTERS, earlier.counters, now.counters):
            if name != "event_step" or not before_quiet:
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
