"""Values in force: which motion settings hold a known constant at each point of a program.

Several conversions need the settings in force where an operation runs, not only the operation
itself: an Arcus ramp time (`ACC=300`) is an acceleration only together with the speeds in force
(`(HSPD - LSPD) / 0.3 s`), and an MCode acceleration becomes an Arcus ramp time the same way. The
optimizer drops a setting already in force on every path, and lint finds a move before any speed
is set. All of them read this one forward data-flow analysis.

The state at a point maps `(param, axis)` to the constant in force; a key that is absent is not
known statically (never set, set from a variable, or different on two paths). A setting for every
axis (`axis == "*"`) is stored under `"*"` and read for any axis without a setting of its own.

Across routines the analysis is context-insensitive: a subroutine starts with what holds at every
one of its calls, a call removes whatever the subroutine (or anything it calls) may set, and an
event handler starts knowing nothing, since it can run at any time. Each block is visited a
bounded number of times (the lattice only loses keys), so the cost is linear in the program for
the graphs programs have.
"""

from __future__ import annotations

from collections import deque
from typing import Iterator

from mcc.compiler import ir

Key = tuple[ir.MotionParam, str]
State = dict[Key, ir.Const]

ALL = ir.ALL_AXES


# Settings a source dialect fixes for every axis, whatever the program does: X150 has no initial
# speed (its moves start from standstill, docs/dialects/x150.md), so a program written for it runs
# with an initial speed of 0 at every point.
FIXED: dict[str, State] = {
    "x150": {(ir.MotionParam.INITIAL_SPEED, ALL): ir.Const(0, ir.Unit.STEPS_PER_S)},
}


def with_fixed_initial_speed(module: ir.Module, lowest: float) -> ir.Module:
    """For a target whose initial speed cannot be 0: a program from a dialect that fixes it at 0
    (X150 starts every move from standstill) sets the target's lowest initial speed (`lowest`, in
    the IR's steps/s) at the start of each routine that runs first, so that the device does not
    start moves at whatever initial speed it has stored. A copy; other programs are returned as they
    are."""
    if (ir.MotionParam.INITIAL_SPEED, ALL) not in FIXED.get(module.dialect, {}):
        return module
    copy = ir.copy_module(module)
    for routine in copy.routines:
        if routine.kind in (ir.RoutineKind.MAIN, ir.RoutineKind.IMMEDIATE) and routine.blocks:
            speed = ir.Const(lowest, ir.Unit.STEPS_PER_S)
            routine.blocks[0].ops.insert(0, ir.SetMotion(ir.MotionParam.INITIAL_SPEED, ALL, speed))
    return copy


def lookup(state: State, param: ir.MotionParam, axis: str) -> ir.Const | None:
    """The constant in force for `param` on `axis`, or None when it is not known statically."""
    found = state.get((param, axis))
    if found is None and axis != ALL:
        found = state.get((param, ALL))
    return found


def meet(a: State | None, b: State) -> State:
    if a is None:
        return dict(b)
    return {k: v for k, v in a.items() if k in b and _same(b[k], v)}


def _same(a: ir.Const, b: ir.Const) -> bool:
    return a.value == b.value and a.unit == b.unit


def transfer(state: State, op: ir.Op, clobbers: dict[str, frozenset[Key]]) -> None:
    """Update `state` in place for one operation."""
    if isinstance(op, ir.SetMotion):
        if op.axis == ALL:
            for key in [k for k in state if k[0] is op.param]:
                del state[key]
        if isinstance(op.value, ir.Const):
            state[(op.param, op.axis)] = op.value
        else:
            state.pop((op.param, op.axis), None)
    elif isinstance(op, ir.Native):
        state.clear()  # a command only its own dialect knows may change any setting
    elif isinstance(op, ir.Call):
        for key in clobbers.get(op.routine, frozenset()):
            if key[1] == ALL:
                for other in [k for k in state if k[0] is key[0]]:
                    del state[other]
            state.pop(key, None)


class InForce:
    """The analysis of one module: entry states per block, replayed per operation on demand."""

    def __init__(self, module: ir.Module, defaults: State | None = None):
        self.module = module
        self.defaults = dict(defaults or {})
        self.fixed = FIXED.get(module.dialect, {})
        self.clobbers = _clobbers(module)
        self.entry: dict[str, State] = {}
        self._solve()

    def at_entry(self, label: str) -> State:
        return {**self.entry.get(label, {}), **self.fixed}

    def after(self, state: State, op: ir.Op) -> State:
        """The state in force after `op`, given `state` before it (a new dictionary)."""
        state = dict(state)
        transfer(state, op, self.clobbers)
        if self.fixed:
            state.update(self.fixed)
        return state

    def walk(self, routine: ir.Routine) -> Iterator[tuple[ir.Block, int, ir.Op, State]]:
        """Every operation of `routine` with the state in force just before it."""
        for block in routine.blocks:
            state = self.at_entry(block.label)
            for index, op in enumerate(block.ops):
                yield block, index, op, state
                state = self.after(state, op)

    def _solve(self) -> None:
        starts: dict[str, State | None] = {}
        for routine in self.module.routines:
            if routine.kind in (ir.RoutineKind.MAIN, ir.RoutineKind.IMMEDIATE, ir.RoutineKind.POWERUP):
                starts[routine.name] = dict(self.defaults)
            elif routine.kind is ir.RoutineKind.HANDLER:
                starts[routine.name] = {}
            else:
                starts[routine.name] = None  # met from its calls
        # Iterate: routine entries depend on call sites, call sites on routine entries.
        for _ in range(len(self.module.routines) + 2):
            calls: dict[str, State | None] = {}
            for routine in self.module.routines:
                start = starts.get(routine.name)
                if start is None:
                    start = {}
                self._solve_routine(routine, start, calls)
            changed = False
            for routine in self.module.routines:
                if routine.kind is ir.RoutineKind.SUBROUTINE:
                    new = calls.get(routine.name) or {}
                    if new != starts.get(routine.name):
                        starts[routine.name] = new
                        changed = True
            if not changed:
                break

    def _solve_routine(self, routine: ir.Routine, start: State, calls: dict[str, State | None]) -> None:
        if not routine.blocks:
            return
        blocks = {b.label: b for b in routine.blocks}
        entry: dict[str, State | None] = {b.label: None for b in routine.blocks}
        entry[routine.blocks[0].label] = dict(start)
        queue = deque([routine.blocks[0].label])
        queued = {routine.blocks[0].label}
        while queue:
            label = queue.popleft()
            queued.discard(label)
            block = blocks[label]
            state = dict(entry[label] or {})
            for op in block.ops:
                if isinstance(op, ir.Call):
                    calls[op.routine] = meet(calls.get(op.routine), state)
                transfer(state, op, self.clobbers)
            for succ in ir.successors(block.terminator):
                if succ not in blocks:
                    continue
                old = entry[succ]
                new = meet(old, state)
                if old is None or new != old:
                    entry[succ] = new
                    if succ not in queued:
                        queue.append(succ)
                        queued.add(succ)
        for label, state in entry.items():
            self.entry[label] = state or {}


def _clobbers(module: ir.Module) -> dict[str, frozenset[Key]]:
    """For each routine, the settings it or anything it calls may change (a fixpoint over calls)."""
    direct: dict[str, set[Key]] = {}
    callees: dict[str, set[str]] = {}
    for routine in module.routines:
        keys: set[Key] = set()
        called: set[str] = set()
        for block in routine.blocks:
            for op in block.ops:
                if isinstance(op, ir.SetMotion):
                    keys.add((op.param, op.axis))
                elif isinstance(op, ir.Native):
                    keys |= {(param, ALL) for param in ir.MotionParam}
                elif isinstance(op, ir.Call):
                    called.add(op.routine)
            if isinstance(block.terminator, ir.GotoRoutine):
                called.add(block.terminator.routine)
        direct[routine.name] = keys
        callees[routine.name] = called
    result = {name: set(keys) for name, keys in direct.items()}
    changed = True
    while changed:
        changed = False
        for name, called in callees.items():
            for callee in called:
                extra = result.get(callee, set()) - result[name]
                if extra:
                    result[name] |= extra
                    changed = True
    return {name: frozenset(keys) for name, keys in result.items()}
