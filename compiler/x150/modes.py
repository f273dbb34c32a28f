"""X150's modal moves resolved by data flow: what each `G` does, as a neutral operation.

An X150 `G` moves by the distance register D in the way the modes in force say (docs/dialects/x150.md,
"Moves"): MN (normal, the factory default) with MPI (incremental, the factory default, L2608) moves
by D, with MPA to D; MC (continuous, L2498) runs at V in the direction of D's sign until stopped; MQ
moves like MN but lets the next commands run during the move (L2631). `D` sets the register, `H`
reverses its sign and `H+`/`H-` set it (L1828, L1864).

The lowering writes placeholders in source order: each mode command as a Native (MPA MPI MN MC MQ),
each `D`/`H`/`H+`/`H-` as an assignment to a hidden per-device variable `%D<device>`, each `G` as a
`Move(MODAL, %D<device>)`. `resolve` then follows the modes and the register forward through every
routine's graph (a sequence starts with what holds at every one of its calls, an immediate stretch
with what the stretch before it left, and what nothing in the file runs with the factory defaults:
MN, MPI and a positive D)
and rewrites each G:

- MN (or MQ) with a known position mode: `Move(ABSOLUTE|RELATIVE, D)`, D a constant when the
  register is known there, else the variable `%D<device>`; after an MN move a `WaitMotion` (the next
  command runs when the move has ended, unlike MQ);
- MC with a known sign of D: `Slew(direction=±1)` (at the max speed in force);
- anything not known statically (two paths with different modes, MC with an unknown direction): the
  `G` stays Native and X140 says why, so no backend but X150's own writes it.

The mode commands themselves disappear (their effect is in the moves: an MQ move is a `Move` without
the `WaitMotion`, which the backend writes in MQ); assignments to
`%D` that nothing reads any more disappear too.
"""

from __future__ import annotations

from mcc.compiler import ir
from mcc.compiler.cfg import dataflow
from mcc.compiler.cfg.graph import BlockIndex, predecessors
from mcc.compiler.cancel import checkpoint
from mcc.compiler.diagnostics import Diagnostics

DIALECT = "x150"
DISTANCE = "%D"
POSITION_MODES = {"MPA": ir.MoveMode.ABSOLUTE, "MPI": ir.MoveMode.RELATIVE}
MOVE_MODES = ("MN", "MC", "MQ")
MODE_COMMANDS = frozenset((*POSITION_MODES, *MOVE_MODES))
# The factory defaults (L2608, L2520; D4000, L810): MPI, MN, and a positive distance register, so a
# G in MC before any D runs forward. Assumed where the file shows nothing else (see resolve).
DEFAULTS = {("pos", ir.ALL_AXES): "MPI", ("move", ir.ALL_AXES): "MN", ("sign", ir.ALL_AXES): 1}

NOTHING: frozenset[str] = frozenset()
State = dict  # ("pos"|"move"|"D", axis) -> "MPA"/"MPI", "MN"/"MC"/"MQ", or an ir.Const


def distance_var(axis: str) -> str:
    return DISTANCE + axis


def is_distance(name: str) -> bool:
    return name.startswith(DISTANCE)


UNKNOWN = "unknown"  # a device's setting not known statically: hides what every device ("*") has


def set_key(state: State, kind: str, axis: str, value) -> None:
    """A setting for every device ("*") replaces the per-device ones; a device's setting that is
    not known statically is recorded as UNKNOWN, so the all-devices value (a factory default)
    does not show through it."""
    if axis == ir.ALL_AXES:
        for key in [k for k in state if k[0] == kind]:
            del state[key]
    if value is None:
        if axis == ir.ALL_AXES:
            state.pop((kind, axis), None)
        else:
            state[(kind, axis)] = UNKNOWN
    else:
        state[(kind, axis)] = value


def get_key(state: State, kind: str, axis: str):
    found = state.get((kind, axis))
    if found is UNKNOWN:
        return None
    return found if found is not None else state.get((kind, ir.ALL_AXES))


def lookup(state: State, kind: str, axis: str, devices: tuple[str, ...]):
    """What `kind` is for a G on `axis`. An unaddressed G ("*") is run by every device, each in its
    own modes and with its own D: the value all of `devices` have, None when they differ (issue 23:
    `1MPA` then an unaddressed `D0 G` on a single device moves to 0, not by 0)."""
    if axis != ir.ALL_AXES or not devices:
        return get_key(state, kind, axis)
    first = get_key(state, kind, devices[0])
    return first if all(same(get_key(state, kind, d), first) for d in devices[1:]) else None


def meet(a: State | None, b: State) -> State:
    if a is None:
        return dict(b)
    # `is` first: the states share most values (a value is the same as itself: no NaN is ever a
    # constant of a program, its numbers are read from decimal text)
    return {k: v for k, v in a.items() if k in b and ((other := b[k]) is v or same(other, v))}


def same(a, b) -> bool:
    if isinstance(a, ir.Const) and isinstance(b, ir.Const):
        return a.value == b.value
    return a == b


def register_value(op: ir.Assign, state: State):
    """The constant D holds after an assignment to %D (None: not known)."""
    axis = op.target.name[len(DISTANCE):]
    value = op.value
    if isinstance(value, ir.Const):
        return ir.Const(value.value, ir.Unit.STEPS, value.span)
    old = get_key(state, "D", axis)
    if not isinstance(old, ir.Const):
        return None
    if isinstance(value, ir.UnOp) and value.op == "-":
        inner = value.operand
        if isinstance(inner, ir.Var):
            return ir.Const(-old.value, ir.Unit.STEPS)
        if isinstance(inner, ir.Func) and inner.name == "abs":
            return ir.Const(-abs(old.value), ir.Unit.STEPS)
    if isinstance(value, ir.Func) and value.name == "abs":
        return ir.Const(abs(old.value), ir.Unit.STEPS)
    return None


def register_sign(op: ir.Assign, state: State, value) -> int | None:
    """The sign of D after an assignment (H- makes it negative whatever D held, L1864)."""
    if isinstance(value, ir.Const):  # D without a sign (D0 too) is positive (L814)
        return -1 if value.value < 0 else 1
    expr = op.value
    if isinstance(expr, ir.Func) and expr.name == "abs":
        return 1
    if isinstance(expr, ir.UnOp) and isinstance(expr.operand, ir.Func):
        return -1
    old = get_key(state, "sign", op.target.name[len(DISTANCE):])
    if isinstance(expr, ir.UnOp) and old is not None:
        return -old
    return None


def transfer(state: State, op, touched: dict[str, bool], exits: dict[str, State | None]) -> State:
    kind = type(op)  # the IR's operation classes have no subclasses
    if kind is ir.Native:
        if op.dialect == DIALECT:
            if op.mnemonic in POSITION_MODES:
                set_key(state, "pos", op.axis, op.mnemonic)
            elif op.mnemonic in MOVE_MODES:
                set_key(state, "move", op.axis, op.mnemonic)
    elif kind is ir.Assign and is_distance(op.target.name):
        axis = op.target.name[len(DISTANCE):]
        value = register_value(op, state)
        set_key(state, "sign", axis, register_sign(op, state, value))
        set_key(state, "D", axis, value)
        set_key(state, "reg", axis, op.target.name)  # which hidden register holds the device's D
    elif kind is ir.Call and touched.get(op.routine, True):
        end = exits.get(op.routine)
        state.clear()
        if end:
            state.update(end)
    return state


class Resolver:
    def __init__(self, module: ir.Module, diags: Diagnostics, devices: tuple[str, ...] = ()):
        self.module = module
        self.diags = diags
        self.devices = devices  # the devices an unaddressed G moves (the profile's and the file's)
        self.touched = self.touching()
        self.entries: dict[str, State | None] = {}
        self.exits: dict[str, State | None] = {}
        self.before: dict[int, State] = {}  # id(op) -> the state just before it
        # id(routine) -> (start, exits of what it calls, end, its call sites' states): the walk of a
        # routine is a function of these, so a later round whose inputs did not change reuses it
        self.memo: dict[int, tuple] = {}
        self.relevant: dict[int, list] = {}  # id(block) -> its ops that read or change the state
        self.call_ops: dict[int, list] = {}  # id(routine) -> its calls
        self.plans: dict[int, tuple] = {}  # id(routine) -> what its walks look at (`plan`)
        self.analysed: set[str] = set()  # routines analysed at least once (their exit state is known)
        # routines whose last walk stopped at a call still waiting for its callee: their exit is not
        # known yet either, so a call of one waits too (else the code after it went on with nothing
        # known and met that into its callees' entries: `1XR3` then `2XR3`, where sequence 3 of
        # device 1 runs sequence 3 of device 2 with `1"2XR3"`, made 2XD3's G X142)
        self.incomplete: set[str] = set()
        self.waited = False  # the walk in progress stopped at a call that waits
        self.patient_done = False  # True: a call of an incomplete routine no longer waits
        self.names = {routine.name for routine in module.routines}  # `module.routine` is a linear search

    def touching(self) -> dict[str, bool]:
        """Routines that may change a mode or D, themselves or through what they call."""
        direct: dict[str, bool] = {}
        calls: dict[str, set[str]] = {}
        for routine in self.module.routines:
            direct[routine.name] = False
            calls[routine.name] = set()
            for block in routine.blocks:
                for op in block.ops:
                    kind = type(op)  # the IR's operation classes have no subclasses
                    if (kind is ir.Native and op.mnemonic in MODE_COMMANDS) or \
                            (kind is ir.Assign and op.target.name.startswith(DISTANCE)):
                        direct[routine.name] = True
                    elif kind is ir.Call:
                        calls[routine.name].add(op.routine)
        result = dict(direct)
        for name in self.module.externals:
            result[name] = True
        changed = True
        while changed:
            changed = False
            for name, called in calls.items():
                if not result[name] and any(result.get(c, True) for c in called):
                    result[name] = True
                    changed = True
        return result

    def solve(self) -> None:
        routines = self.module.routines
        for _ in range(3 * len(routines) + 5):
            sites: dict[str, State | None] = {}
            carried: State = dict(DEFAULTS)
            changed = False
            for routine in routines:
                if routine.kind is ir.RoutineKind.IMMEDIATE:
                    start = carried
                elif routine.kind is ir.RoutineKind.SUBROUTINE:
                    start = self.entries.get(routine.name)
                    if start is None:  # no call reaches it yet: analysed once one does (optimistic)
                        continue
                else:
                    start = dict(DEFAULTS)  # run by the host, at power-up or by an event: assumed defaults
                end = self.walk(routine, start, sites)
                self.analysed.add(routine.name)
                if routine.kind is ir.RoutineKind.IMMEDIATE and end is not None:
                    carried = end
                if not states_equal(self.exits.get(routine.name), end):
                    self.exits[routine.name] = end
                    changed = True
            for routine in routines:
                if routine.kind is ir.RoutineKind.SUBROUTINE:
                    new = sites.get(routine.name)
                    if new is None and routine.name in self.entries:
                        new = {}  # its calls became unreachable: nothing known
                    if new is not None and not states_equal(self.entries.get(routine.name), new):
                        self.entries[routine.name] = new
                        changed = True
            if not changed:
                if self.incomplete and not self.patient_done:
                    # calls that still wait wait on each other (recursion): go on past them with
                    # nothing known, as before a routine's exit could be awaited
                    self.patient_done = True
                    continue
                break

    def walk(self, routine: ir.Routine, start: State, sites: dict[str, State | None]) -> State | None:
        """`routine` walked from `start`, its call sites' states met into `sites` (in the order the
        walk reaches them); the walk of an earlier round when its inputs are exactly the same."""
        calls = self.calls(routine)
        called = [self.exits.get(op.routine) for op in calls]
        known = [op.routine in self.analysed and (self.patient_done or op.routine not in self.incomplete)
                 for op in calls]  # a call to an unanalysed routine waits
        memo = self.memo.get(id(routine))
        if memo is not None and identical(memo[0], start) and len(memo[1]) == len(called) \
                and all(identical(a, b) for a, b in zip(memo[1], called)) and memo[4] == known:
            end, reached, waited = memo[2], memo[3], memo[5]
        else:
            before = self.before
            for op in self.plan(routine)[1]:  # a new walk: the states it no longer reaches are not kept
                before.pop(id(op), None)
            reached = []
            self.waited = False
            end = self.routine(routine, start, reached)
            waited = self.waited
            self.memo[id(routine)] = (dict(start), called, end, reached, known, waited)
        if waited and end is None:  # no path has reached the routine's end yet
            self.incomplete.add(routine.name)
        else:
            self.incomplete.discard(routine.name)
        for name, state in reached:  # (the first state met is kept as it is: no state is changed once made)
            earlier = sites.get(name)
            sites[name] = state if earlier is None else meet(earlier, state)
        return end

    def calls(self, routine: ir.Routine) -> list:
        """The routine's calls, found once (the walks do not change the operations)."""
        found = self.call_ops.get(id(routine))
        if found is None:
            found = [op for block in routine.blocks for op in self.ops_of(block) if isinstance(op, ir.Call)]
            self.call_ops[id(routine)] = found
        return found

    def ops_of(self, block: ir.Block) -> list:
        """The operations of `block` that `transfer` or the rewriting look at (the others leave
        the state as it is)."""
        found = self.relevant.get(id(block))
        if found is None:
            found = []
            for op in block.ops:
                kind = type(op)  # the IR's operation classes have no subclasses
                if kind is ir.Native:
                    if op.dialect == DIALECT and op.mnemonic in MODE_COMMANDS:
                        found.append(op)
                elif kind is ir.Assign:
                    if op.target.name.startswith(DISTANCE):
                        found.append(op)
                elif kind is ir.Call or (kind is ir.Move and op.mode is ir.MoveMode.MODAL):
                    found.append(op)
            self.relevant[id(block)] = found
        return found

    def plan(self, routine: ir.Routine) -> tuple[dict[str, tuple], list]:
        """What a walk of the routine looks at, found once (the walks do not change the blocks):
        each block's label -> (its `ops_of`, the routine its GotoRoutine names or None, whether
        the routine ends there (FallOff, Return, no terminator), the labels after it that are in
        the routine); and the routine's modal moves (the operations `before` keeps states for)."""
        found = self.plans.get(id(routine))
        if found is None:
            labels = {block.label for block in routine.blocks}
            steps: dict[str, tuple] = {}
            moves = []
            for block in routine.blocks:
                ops = self.ops_of(block)
                moves += [op for op in ops if type(op) is ir.Move]
                term = block.terminator
                steps[block.label] = (ops, term.routine if isinstance(term, ir.GotoRoutine) else None,
                                      isinstance(term, (ir.FallOff, ir.Return)) or term is None,
                                      tuple(succ for succ in ir.successors(term) if succ in labels))
            found = self.plans[id(routine)] = (steps, moves)
        return found

    def routine(self, routine: ir.Routine, start: State, reached: list) -> State | None:
        if not routine.blocks:
            return None
        steps = self.plan(routine)[0]
        first = routine.blocks[0].label
        entry: dict[str, State | None] = {first: dict(start)}
        work = [first]
        end: State | None = None
        visits: dict[str, int] = {}
        before = self.before
        touched = self.touched
        names = self.names
        analysed = self.analysed
        while work:
            label = work.pop()
            visits[label] = visits.get(label, 0) + 1
            ops, goto, exits, after = steps[label]
            state = entry[label] or {}
            # Copy on write: `state` is shared (the block's entry, or kept for a G or a call site,
            # which only read it) until an operation changes it, and copied only then.
            shared = True
            waiting = False
            for op in ops:  # a modal Move, a Call, a mode command or a %D assignment
                kind = type(op)
                if kind is ir.Move:  # only a G needs its state; a move changes none
                    before[id(op)] = state
                    shared = True
                    continue
                if kind is ir.Call:
                    reached.append((op.routine, state))
                    shared = True
                    touches = touched.get(op.routine, True)
                    if touches and op.routine in names and (op.routine not in analysed or (
                            not self.patient_done and op.routine in self.incomplete)):
                        waiting = True  # what it leaves is not known yet: the next round goes on from here
                        self.waited = True
                        break
                    if not touches:
                        continue  # `transfer` leaves the state as it is
                if shared:
                    state = dict(state)
                    shared = False
                state = transfer(state, op, touched, self.exits)
            if waiting:
                continue
            if goto is not None:
                reached.append((goto, state))
            # A state reached for the first time is kept as it is, not copied (`meet(None, state)`):
            # no state is changed once made (the walk copies one before an operation changes it).
            if exits:
                end = state if end is None else meet(end, state)
            for succ in after:
                old = entry.get(succ)
                if old is None:
                    entry[succ] = state
                    if visits.get(succ, 0) < 64:
                        work.append(succ)
                    continue
                new = meet(old, state)
                if not states_equal(old, new):
                    entry[succ] = new
                    if visits.get(succ, 0) < 64:
                        work.append(succ)
        return end

    # -- rewriting ---------------------------------------------------------------------------------
    def rewrite(self) -> None:
        modal = ir.MoveMode.MODAL
        kept_go = False
        with_modes: list[ir.Block] = []  # the blocks holding a mode command (MPA MPI MN MC MQ)
        liveness: dict[int, list] = {}  # id(block) -> its `liveness_ops` (no mode command among them)
        for routine in self.module.routines:
            checkpoint()
            for block in routine.blocks:
                relevant = self.ops_of(block)
                if any(isinstance(op, ir.Move) and op.mode is modal for op in relevant):
                    out: list = []
                    for op in block.ops:
                        if isinstance(op, ir.Move) and op.mode is modal:
                            out += self.rewrite_op(op, block.ops, out)
                        else:
                            out.append(op)
                    block.ops = out
                # the block's register operations for the liveness, a G kept as text among them
                registers = liveness[id(block)] = liveness_ops(block.ops)
                kept_go = kept_go or any(type(op) is ir.Native for op in registers)
                if any(isinstance(op, ir.Native) for op in relevant):
                    with_modes.append(block)
        if not kept_go:  # the modes are in the moves now; a G kept as text still needs them
            for block in with_modes:
                block.ops = [op for op in block.ops if not (isinstance(op, ir.Native) and op.dialect == DIALECT
                                                            and op.mnemonic in MODE_COMMANDS)]
        checkpoint()
        self.drop_unread_distances(liveness)

    def rewrite_op(self, op, ops: list, done: list) -> list:
        if not (isinstance(op, ir.Move) and op.mode is ir.MoveMode.MODAL):
            return [op]
        state = self.before.get(id(op), {})
        axis = op.targets[0][0]
        devices = self.devices
        move = lookup(state, "move", axis, devices)
        register = lookup(state, "D", axis, devices)
        go = ir.Native(DIALECT, "G", (), axis=axis, span=op.span)
        if move == "MC":
            sign = lookup(state, "sign", axis, devices)
            if sign is not None:
                return [ir.Slew(axis, None, sign, op.span)]
            self.report(op.span, "G in MC runs in the direction of D's sign, which is not known here")
            return [go]
        if move not in ("MN", "MQ"):
            self.report(op.span, "G moves in the move mode in force (MN, MC or MQ), which differs on the paths "
                                 "that reach it")
            return [go]
        pos = lookup(state, "pos", axis, devices)
        if pos not in POSITION_MODES:
            self.report(op.span, "G moves by D in the position mode in force (MPA or MPI), which differs on the "
                                 "paths that reach it")
            return [go]
        span = op.span
        if isinstance(register, ir.Const):
            source = self.last_distance(done, axis)
            target = ir.Const(register.value, ir.Unit.STEPS, register.span)
            if source is not None and source.span is not None and span is not None and source.span.file == span.file \
                    and source.span.start < span.start:
                span = source.span.to(span)
        else:
            name = lookup(state, "reg", axis, devices) or distance_var(axis)
            target = ir.Var(name, span)
            self.declare(name)
        moved = [ir.Move(POSITION_MODES[pos], ((axis, target),), op.options, span)]
        if move == "MN":
            moved.append(ir.WaitMotion(axis, op.span))
        return moved

    @staticmethod
    def last_distance(done: list, axis: str):
        """The `D` that set the register in the same block before this G (for the source map)."""
        for op in reversed(done):
            if isinstance(op, ir.Assign) and op.target.name == distance_var(axis):
                return op
        return None

    def declare(self, name: str) -> None:
        if name not in self.module.variables:
            self.module.variables[name] = ir.Variable(name, ir.VarType.INT32, None, "global")

    def drop_unread_distances(self, relevant: dict[int, list] | None = None) -> None:
        """Assignments to a %D that no move, native G or later H can read (backward liveness; a call,
        a transfer and the end of a routine read every %D something in the module reads) are dropped,
        and so is a %D variable nothing reads. `relevant`: each block's `liveness_ops` when the
        caller has them (found in one pass over the module); everything below looks at these only."""
        if relevant is None:
            relevant = {id(block): liveness_ops(block.ops) for routine in self.module.routines
                        for block in routine.blocks}
        op_reads = self.op_reads
        # Until nothing more goes: an assignment dropped (an `H` whose D is set again before any G)
        # may be the only reader of an earlier one (the `D4000` before that `H`), which the output,
        # compiled again, would drop; dropping it now makes compile(compile(p)) == compile(p).
        for _ in range(16):
            before = sum(map(len, relevant.values()))
            if self.module.externals:
                read = {n for n in self.module.variables if is_distance(n)}
            else:
                read = {name for ops in relevant.values() for op in ops if type(op) is not ir.Call
                        for name in op_reads(op)}
            for routine in self.module.routines:
                self.drop_dead_in(routine, read, relevant)
            if sum(map(len, relevant.values())) == before:
                break
        used: set[str] = set()
        for ops in relevant.values():
            for op in ops:
                if type(op) is not ir.Call:
                    used |= op_reads(op)
                    if type(op) is ir.Assign:  # to a %D (liveness_ops)
                        used.add(op.target.name)
        for name in [n for n in self.module.variables if is_distance(n) and n not in used]:
            del self.module.variables[name]

    def op_reads(self, op) -> frozenset[str] | set[str]:
        """The registers an operation reads: only moves, a G kept as text and H/H+/H- (the lowering
        puts %D nowhere else). Not to be changed by the caller (most operations share NOTHING)."""
        if isinstance(op, ir.Native):
            if op.mnemonic != "G":
                return NOTHING
            devices = self.devices if op.axis == ir.ALL_AXES else ()
            return {distance_var(op.axis), distance_var(ir.ALL_AXES), *map(distance_var, devices)}
        if isinstance(op, ir.Move):
            return {e.name for _, e in op.targets if isinstance(e, ir.Var) and is_distance(e.name)}
        if isinstance(op, ir.Assign) and is_distance(op.target.name) and not isinstance(op.value, ir.Const):
            return {node.name for node in ir.walk_expr(op.value) if isinstance(node, ir.Var) and is_distance(node.name)}
        return NOTHING

    def drop_dead_in(self, routine: ir.Routine, read: set[str], relevant: dict[int, list]) -> None:
        """`relevant`: each block's `liveness_ops`, kept up to date when assignments are dropped."""
        if not any(type(op) is ir.Assign for b in routine.blocks for op in relevant[id(b)]):
            return
        live_in: dict[str, set[str] | frozenset[str]] = dict.fromkeys((b.label for b in routine.blocks), NOTHING)
        op_reads = self.op_reads

        def live_out(block) -> set[str] | frozenset[str]:
            """Not to be changed by the caller (it may be `read` itself)."""
            term = block.terminator
            if isinstance(term, (ir.FallOff, ir.Return, ir.GotoRoutine, ir.End)) or term is None:
                return read if not isinstance(term, ir.End) else NOTHING
            out: set[str] = set()
            for succ in ir.successors(term):
                out |= live_in[succ] if succ in live_in else read
            return out

        def through(block, live: set[str]) -> None:
            """The block without the assignments to a %D that nothing reads after them."""
            dropped = []
            for op in reversed(relevant[id(block)]):
                kind = type(op)
                if kind is ir.Assign:  # to a %D (liveness_ops)
                    if op.target.name not in live:
                        dropped.append(op)
                        continue
                    live = (live - {op.target.name}) | op_reads(op)
                elif kind is ir.Call:
                    live = live | read
                else:
                    live = live | op_reads(op)
            if dropped:
                gone = {id(op) for op in dropped}
                block.ops = [op for op in block.ops if id(op) not in gone]
                relevant[id(block)] = [op for op in relevant[id(block)] if id(op) not in gone]

        def summary(block) -> tuple[set[str], set[str]]:
            """The block's effect on the live registers, `(live - kill) | gen`: its operations
            composed once, so that each round of the fixed point costs a set operation per block."""
            kill: set[str] = set()
            gen: set[str] = set()
            for op in reversed(relevant[id(block)]):
                kind = type(op)
                if kind is ir.Assign:  # to a %D (liveness_ops)
                    gen.discard(op.target.name)
                    kill.add(op.target.name)
                    gen |= op_reads(op)
                elif kind is ir.Call:
                    gen |= read
                else:
                    gen |= op_reads(op)
            return kill, gen

        nothing = (NOTHING, NOTHING)  # the summary of a block without register operations
        summaries = [summary(block) if relevant[id(block)] else nothing for block in routine.blocks]
        # Backward liveness with the analysis library's solver: each block's state is what is live
        # after it, `beyond` (what its exits out of the routine read) joined with what is live at
        # the start of the blocks after it; a block's transfer is its summary. Every block starts
        # (a block no path from the entry reaches keeps its registers too), last block first.
        index = BlockIndex.of_routine(routine)
        beyond: list = []
        for block, targets in zip(routine.blocks, index.succ):
            term = block.terminator
            if isinstance(term, (ir.FallOff, ir.Return, ir.GotoRoutine, ir.End)) or term is None:
                beyond.append(NOTHING if isinstance(term, ir.End) else read)
            else:
                beyond.append(read if len(targets) < len(ir.successors(term)) else NOTHING)
        preds = predecessors(range(len(index.succ)), index.succ, len(index.succ))

        def transfer(node: int, live: set[str] | frozenset[str]) -> set[str] | frozenset[str]:
            kill, gen = summaries[node]
            return (live - kill) | gen

        starts = {node: beyond[node] for node in reversed(range(len(index.succ)))}
        live_after = dataflow.solve(None, preds, starts, transfer, lambda old, new: old | new)
        for node, label in enumerate(index.labels):
            live_in[label] = transfer(node, live_after[node])
        for node, block in enumerate(routine.blocks):
            if summaries[node][0]:  # a block that assigns no %D keeps its operations
                through(block, live_out(block))

    def report(self, span, why: str) -> None:
        if span is not None:
            self.diags.add("X142", span, f"{why}: mcc keeps this G as X150 text, so it compiles to X150 only; "
                                         "set the mode (MN/MC, MPA/MPI) and D on every path before G")


def liveness_ops(ops: list) -> list:
    """The operations of a block that the register liveness looks at: assignments to a %D, calls
    (which read every register), moves, and a G kept as text; every other operation reads no
    register and assigns none (`Resolver.op_reads`)."""
    out = []
    for op in ops:
        kind = type(op)  # the IR's operation classes have no subclasses
        if kind is ir.Assign:
            if op.target.name.startswith(DISTANCE):
                out.append(op)
        elif kind is ir.Call or kind is ir.Move or (kind is ir.Native and op.mnemonic == "G"):
            out.append(op)
    return out


def identical(a: State | None, b: State | None) -> bool:
    """The same state to the last detail (the spans and the number types of the constants too):
    what a reused walk needs, where `states_equal` compares meanings."""
    if a is None or b is None:
        return a is b
    if a.keys() != b.keys():
        return False
    for key, value in a.items():
        other = b[key]
        if value is other:
            continue
        if type(value) is not type(other) or value != other:
            return False
        if isinstance(value, ir.Const) and type(value.value) is not type(other.value):
            return False
    return True


def states_equal(a: State | None, b: State | None) -> bool:
    if a is None or b is None:
        return a is b
    if a is b:
        return True
    return a.keys() == b.keys() and all(a[k] is b[k] or same(a[k], b[k]) for k in a)


def resolve(module: ir.Module, diags: Diagnostics, devices: tuple[str, ...] = ()) -> None:
    """`devices`: the devices of the profile and the file, which an unaddressed G moves."""
    resolver = Resolver(module, diags, devices)
    resolver.solve()
    checkpoint()  # the editor server abandons a stale analysis here (compiler/cancel.py)
    resolver.rewrite()
