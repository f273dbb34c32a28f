"""An abstract interpretation of a module over intervals: where each axis may be, and what each
variable that feeds a move may hold, at every operation (issue 27).

The state maps a variable's name, an axis's position (`POS + axis`) and whether an axis has been
homed (`HOMED + axis`, 0 or 1) to an `Interval`; a name it lacks is unknown (any value). Inputs
and every device reading but the position are unknown. At a loop header the analysis first tries
to extrapolate: when the loop's count is bounded (one counter changed by a constant each pass and
compared with a bound at the loop's exit), a value that changes by `d` each pass reaches at most
`count * d` beyond its value on entry; otherwise, or when that guess does not hold, it widens the
value to infinity. Two narrowing passes then recover what the loop's exit test bounds. A call
applies the callee's summary (computed callee first): the positions it leaves (absolute, or moved
by a delta) and the variables it writes.

Each block is visited a bounded number of times, so the cost is linear in the program's size
(bench/bench_lint.py, "envelope").
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from mcc.compiler import ir
from mcc.compiler.envelope.axes import AxisEnvelope
from mcc.compiler.lint import flow

INF = math.inf
POS = "@pos:"
HOMED = "@homed:"
ANCHOR = "@anchor:"
PEAK = "@peak:"  # summaries: how far the callee's moves go from where it was called, before it anchors
SET = "@set:"  # a motion setting in force on an axis: "@set:max_speed:X"  # summaries: 1 once the callee set the position absolutely
WIDEN_AFTER = 2  # visits of a loop header before its growing values are extrapolated or widened
NARROWING = 2


@dataclass(frozen=True, slots=True)
class Interval:
    lo: float
    hi: float

    def join(self, other: "Interval") -> "Interval":
        return Interval(min(self.lo, other.lo), max(self.hi, other.hi))

    def meet(self, other: "Interval") -> "Interval":
        return Interval(max(self.lo, other.lo), min(self.hi, other.hi))

    def widen(self, new: "Interval") -> "Interval":
        return Interval(self.lo if new.lo >= self.lo else -INF, self.hi if new.hi <= self.hi else INF)

    @property
    def empty(self) -> bool:
        return self.lo > self.hi

    def text(self) -> str:
        return f"{self.lo:g}" if self.lo == self.hi else f"{self.lo:g} .. {self.hi:g}"


TOP = Interval(-INF, INF)
State = dict[str, Interval]


def point(value: float) -> Interval:
    return Interval(value, value)


def _mul(a: float, b: float) -> float:
    return 0.0 if a == 0 or b == 0 else a * b


def arith(op: str, a: Interval, b: Interval) -> Interval:
    if op == "+":
        return Interval(a.lo + b.lo, a.hi + b.hi)
    if op == "-":
        return Interval(a.lo - b.hi, a.hi - b.lo)
    if op == "*":
        products = [_mul(x, y) for x in (a.lo, a.hi) for y in (b.lo, b.hi)]
        return Interval(min(products), max(products))
    if op == "/" and (b.lo > 0 or b.hi < 0):
        quotients = [x / y for x in (a.lo, a.hi) for y in (b.lo, b.hi) if not (math.isinf(x) and math.isinf(y))]
        return Interval(min(quotients), max(quotients)) if len(quotients) == 4 else TOP
    if op == "%" and b.lo == b.hi and b.lo != 0:
        m = abs(b.lo) - 1
        return Interval(0 if a.lo >= 0 else -m, m if a.hi > 0 else 0)
    return TOP


@dataclass
class Check:
    """A move's target on one axis, as the analysis knows it where the move runs."""

    op: object
    axis: str
    target: Interval
    relative: bool
    loops: tuple[str, ...]  # notes: the loops (header line, count) the move runs in
    homed: Interval
    before: Interval = TOP  # where the axis may be when the move starts
    anchored: Interval = TOP  # 1 on the paths where an absolute move, homing or position set came first
    branches: tuple[int, ...] = ()  # lines of the routine's branches before the move


@dataclass
class Summary:
    positions: dict[str, tuple[str, Interval]]  # axis -> ("absolute" | "relative", interval)
    writes: dict[str, Interval]
    homes: frozenset[str]
    peaks: dict[str, Interval] = field(default_factory=dict)  # axis -> the targets of its relative moves, from the call


@dataclass
class Result:
    checks: list[Check] = field(default_factory=list)
    unbounded: dict[int, tuple[object, str, str]] = field(default_factory=dict)  # id(move) -> (move, axis, loop note)
    settings: list[tuple[object, Interval]] = field(default_factory=list)  # (SetMotion, value)
    assigns: dict[str, list[tuple[object, Interval]]] = field(default_factory=dict)  # name -> (Assign, value)
    # what a motion runs at, beside the settings themselves: (operation, axis, quantity, value) with
    # quantity "speed" (a slew's velocity, a homing's speed) or "ramp" (the acceleration a ramp time
    # gives with the speeds in force: (max - initial) / time)
    motion: list[tuple[object, str, str, Interval]] = field(default_factory=list)


def loop_count(loop: flow.Loop, blocks_in: set[str], state: State, entry: State, types) -> int | None:
    """How many passes a loop makes at most, when one counter decides it; None when unbounded."""
    exits = [b.terminator for b in loop_blocks(loop) if isinstance(b.terminator, ir.Branch)
             and ((b.terminator.then in blocks_in) != (b.terminator.otherwise in blocks_in))]
    if len(exits) != 1 or not isinstance(exits[0].cond, ir.Compare):
        return None
    branch = exits[0]
    # a WHILE tests before the first pass (its header holds nothing but the test), a BR loop after it
    tested_first = branch is loop.header.terminator and not loop.header.ops
    cond = branch.cond
    op = cond.op if branch.then in blocks_in else NEGATE[cond.op]
    if isinstance(cond.left, ir.Var):
        name, bound = cond.left.name, cond.right
    elif isinstance(cond.right, ir.Var):
        name, bound, op = cond.right.name, cond.left, FLIP[op]
    else:
        return None
    steps = [op2 for b in loop_blocks(loop) for op2 in b.ops if isinstance(op2, ir.Assign) and op2.target.name == name]
    if len(steps) != 1:
        return None
    value = steps[0].value
    if not (isinstance(value, ir.BinOp) and value.op in "+-" and isinstance(value.left, ir.Var)
            and value.left.name == name and isinstance(value.right, ir.Const) and value.right.value != 0):
        return None
    k = value.right.value if value.op == "+" else -value.right.value
    start = entry.get(name, TOP)
    limit = evaluate(bound, state)
    if any(math.isinf(v) for v in (start.lo, start.hi, limit.lo, limit.hi)):
        return None
    if k > 0 and op in ("<", "<="):
        span = limit.hi - start.lo
        count = math.ceil(span / k) if op == "<" else math.floor(span / k) + 1
    elif k < 0 and op in (">", ">="):
        span = start.hi - limit.lo
        count = math.ceil(span / -k) if op == ">" else math.floor(span / -k) + 1
    elif op == "!=" and start.lo == start.hi and limit.lo == limit.hi and (limit.lo - start.lo) / k >= 0 \
            and (limit.lo - start.lo) % k == 0:
        count = int((limit.lo - start.lo) / k)
        if count == 0 and not tested_first:
            return None  # X150 L0: the counter passes the bound before the first test and never meets it
    else:
        return None
    return max(1, int(count))


NEGATE = {"<": ">=", "<=": ">", ">": "<=", ">=": "<", "=": "!=", "!=": "="}
FLIP = {"<": ">", "<=": ">=", ">": "<", ">=": "<=", "=": "=", "!=": "!="}


def loop_blocks(loop: flow.Loop) -> list[ir.Block]:
    out, work = [], [loop]
    while work:
        current = work.pop()
        out += current.blocks
        work += current.inner
    return out


def evaluate(expr, state: State) -> Interval:
    if isinstance(expr, ir.Const):
        return point(float(expr.value)) if isinstance(expr.value, (int, float)) else TOP
    if isinstance(expr, ir.Var):
        return state.get(expr.name, TOP)
    if isinstance(expr, ir.Status):
        return state.get(POS + expr.axis, TOP) if expr.meaning == "position" else TOP
    if isinstance(expr, ir.BinOp):
        return arith(expr.op, evaluate(expr.left, state), evaluate(expr.right, state))
    if isinstance(expr, ir.UnOp) and expr.op == "-":
        inner = evaluate(expr.operand, state)
        return Interval(-inner.hi, -inner.lo)
    if isinstance(expr, ir.Func) and expr.name == "abs" and expr.args:
        inner = evaluate(expr.args[0], state)
        if inner.lo >= 0:
            return inner
        return Interval(0 if inner.hi >= 0 else -inner.hi, max(-inner.lo, inner.hi))
    return TOP


def refine(cond, state: State, truth: bool) -> State | None:
    """`state` on the edge where `cond` is `truth`; None when that edge cannot be taken."""
    if isinstance(cond, ir.Not):
        return refine(cond.cond, state, not truth)
    if isinstance(cond, ir.Logic):
        if (cond.op == "and") == truth:
            first = refine(cond.left, state, truth)
            return None if first is None else refine(cond.right, first, truth)
        return state
    if not isinstance(cond, ir.Compare):
        return state
    op = cond.op if truth else NEGATE.get(cond.op)
    if op is None:
        return state
    out = state
    for side, other, sop in ((cond.left, cond.right, op), (cond.right, cond.left, FLIP[op])):
        key = side.name if isinstance(side, ir.Var) else POS + side.axis \
            if isinstance(side, ir.Status) and side.meaning == "position" else None
        if key is None:
            continue
        bound = evaluate(other, out)
        current = out.get(key, TOP)
        limit = {"<": Interval(-INF, bound.hi), "<=": Interval(-INF, bound.hi), ">": Interval(bound.lo, INF),
                 ">=": Interval(bound.lo, INF), "=": bound, "!=": TOP}[sop]
        new = current.meet(limit)
        if new.empty:
            return None
        if new != current:
            out = dict(out)
            out[key] = new
    return out


def join_states(a: State, b: State) -> State:
    return {k: a[k].join(b[k]) for k in a.keys() & b.keys()}


class Analyzer:
    """The analysis of one module against the envelopes of its axes."""

    def __init__(self, module: ir.Module, envelopes: dict[str, AxisEnvelope], axes: tuple[str, ...] = ()):
        self.module = module
        self.envelopes = envelopes
        self.routines = flow.routine_index(module)
        self.calls = flow.call_graph(module)
        self.summaries: dict[str, Summary] = {}
        self.axes = tuple(sorted(envelopes))
        self.branch_lines: list[int] = []
        # "*" (every axis) means the product's axes that have an envelope
        self.every = tuple(a for a in self.axes if a in axes) if axes else self.axes
        self.int_vars = {name for name, v in module.variables.items() if v.type is ir.VarType.INT32}
        self.int_vars |= {name for name, t in module.registers.items() if t is ir.VarType.INT32}

    def axes_of(self, axis: str) -> tuple[str, ...]:
        """The configured axes an axis name of the IR stands for ("*": every one)."""
        if axis in (ir.ALL_AXES, ""):
            return self.every
        return (axis,) if axis in self.envelopes else ()

    def start_state(self) -> State:
        """Inputs unknown; each axis somewhere in its travel, not yet homed."""
        state: State = {}
        for axis, env in self.envelopes.items():
            state[POS + axis] = Interval(env.min if env.min is not None else -INF, env.max if env.max is not None else INF)
            state[HOMED + axis] = point(0)
            state[ANCHOR + axis] = point(0)
        return state

    def run(self) -> Result:
        result = Result()
        for routine in self.module.routines:
            self.solve(routine, self.start_state(), result)
        return result

    # the summary of a routine, for its callers -----------------------------------------------
    def summary(self, name: str) -> Summary:
        empty = Summary({}, {}, frozenset())
        return flow.summarize(name, self.summaries, empty, self.calls, self.compute)

    def compute(self, name: str) -> Summary:
        routine = self.routines.get(name)
        if routine is None:
            return Summary({a: ("absolute", TOP) for a in self.axes}, {}, frozenset())
        entry: State = {}
        for axis in self.axes:
            entry[POS + axis] = point(0)
            entry[ANCHOR + axis] = point(0)
            entry[HOMED + axis] = point(0)
        exit_state = self.solve(routine, entry, None)
        writes = {op.target.name for _, _, op in flow.ops(ir.Module(self.module.dialect, "", routines=[routine]),
                                                           ir.Assign)}
        if exit_state is None:
            return Summary({}, {w: TOP for w in writes}, frozenset())
        positions = {}
        for axis in self.axes:
            anchor = exit_state.get(ANCHOR + axis, TOP)
            pos = exit_state.get(POS + axis, TOP)
            positions[axis] = ("absolute", pos) if anchor == point(1) else ("relative", pos) \
                if anchor == point(0) else ("absolute", TOP)
        homes = frozenset(a for a in self.axes if exit_state.get(HOMED + a) == point(1))
        peaks = {a: exit_state[PEAK + a] for a in self.axes if PEAK + a in exit_state}
        return Summary(positions, {w: exit_state.get(w, TOP) for w in writes}, homes, peaks)

    # the fixed point of one routine --------------------------------------------------------------
    def solve(self, routine: ir.Routine, entry: State, result: Result | None) -> State | None:
        start = routine.entry
        if start is None:
            return None
        shape = flow.shape_of(routine, start)
        succ, order, blocks = shape.succ, shape.order, shape.blocks
        forest = flow.loop_forest(routine)
        caller_branches = self.branch_lines  # a callee's summary is computed in the middle of its caller
        self.branch_lines = sorted({b.terminator.span.line for b in routine.blocks
                                    if isinstance(b.terminator, ir.Branch) and b.terminator.span is not None})
        loops = {loop.header.label: loop for loop in forest}
        members = {label: {b.label for b in loop_blocks(loop)} for label, loop in loops.items()}
        incoming: dict[str, dict[str, State]] = {label: {} for label in order}
        states: dict[str, State] = {start.label: entry}
        visits: dict[str, int] = {}
        extrapolated: dict[tuple[str, str], tuple[Interval | None, Interval]] = {}
        counts: dict[str, int | None] = {}

        def head_state(label: str, narrowing: bool) -> State | None:
            ins = list(incoming[label].values())
            if label == start.label:
                ins.append(entry)
            if not ins:
                return None
            new = ins[0]
            for other in ins[1:]:
                new = join_states(new, other)
            old = states.get(label)
            if old is None:
                return new
            if narrowing:
                return {k: old[k].meet(v) if k in old else v for k, v in new.items()}
            if label not in loops or visits.get(label, 0) < WIDEN_AFTER:
                return join_states(old, new) if label in loops else new
            inside = members[label]
            outside = [s for p, s in incoming[label].items() if p not in inside]
            if label == start.label:
                outside.append(entry)
            enter = outside[0] if outside else {}
            for other in outside[1:]:
                enter = join_states(enter, other)
            count = loop_count(loops[label], inside, old, enter, self.int_vars)
            counts[label] = count
            out: State = {}
            for key, value in new.items():
                before = old.get(key)
                if before is None:
                    continue
                grown = value.join(before)
                if grown == before:
                    out[key] = before
                    continue
                base = enter.get(key)
                known = extrapolated.get((label, key))
                if count is not None and known is not None and known[0] == base:
                    out[key] = known[1]  # the count bounds it: pass j starts at entry + (j-1) * d
                elif count is not None and base is not None and known is None:
                    d_lo, d_hi = value.lo - before.lo, value.hi - before.hi
                    passes = count - 1
                    guess = base.join(Interval(base.lo + passes * min(0.0, d_lo), base.hi + passes * max(0.0, d_hi)))
                    extrapolated[(label, key)] = (base, guess.join(before))
                    out[key] = guess.join(before)
                else:
                    out[key] = before.widen(grown)
            return out

        def run_block(label: str, state: State, report: Result | None) -> None:
            block = blocks[label]
            loops_here = tuple(f"line {loops[h].header.span.line if loops[h].header.span else '?'}: a loop "
                               + (f"of at most {counts[h]} passes" if counts.get(h) else "whose count mcc cannot bound")
                               for h in members if label in members[h])
            for op in block.ops:
                state = self.transfer(state, op, report, loops_here)
            term = block.terminator
            for nxt in succ[label]:
                out = state
                if isinstance(term, ir.Branch) and term.then != term.otherwise:
                    out = refine(term.cond, state, nxt.label == term.then)
                if out is None:
                    incoming[nxt.label].pop(label, None)
                    continue
                incoming[nxt.label][label] = out

        # widening iterations in order until nothing changes, then narrowing passes
        changed = True
        rounds = 0
        while changed and rounds < 50:
            changed = False
            rounds += 1
            for label in order:
                new = head_state(label, narrowing=False)
                if new is None:
                    continue
                visits[label] = visits.get(label, 0) + 1
                if states.get(label) != new or rounds == 1:
                    changed = changed or states.get(label) != new
                    states[label] = new
                    run_block(label, new, None)
        for _ in range(NARROWING):
            for label in order:
                new = head_state(label, narrowing=True)
                if new is not None:
                    states[label] = new
                    run_block(label, new, None)
        if result is not None:
            for label, loop in loops.items():
                if label in states and counts.get(label, loop_count(loop, members[label], states[label],
                                                                    states[label], self.int_vars)) is None:
                    self.note_unbounded(result, loop)
        exit_state: State | None = None
        for label in order:
            if label not in states:
                continue
            run_block(label, states[label], result)
            block = blocks[label]
            if isinstance(block.terminator, (ir.Return, ir.End, ir.FallOff)):
                state = states[label]
                for op in block.ops:
                    state = self.transfer(state, op, None, ())
                exit_state = state if exit_state is None else join_states(exit_state, state)
        self.branch_lines = caller_branches
        return exit_state

    def note_ramp(self, state: State, op, axis: str, report: Result) -> None:
        """The acceleration a ramp time in force gives a move: (max speed - initial speed) / time."""
        time = state.get(SET + "accel_time:" + axis)
        if time is None or time.lo <= 0 or math.isinf(time.hi):
            return
        top = state.get(SET + "max_speed:" + axis, TOP)
        start = state.get(SET + "initial_speed:" + axis, point(0.0))
        if math.isinf(top.hi) or math.isinf(start.lo):
            return
        report.motion.append((op, axis, "ramp", Interval(max(0.0, (top.lo - start.hi) / time.hi),
                                                         max(0.0, (top.hi - start.lo) / time.lo))))

    def note_unbounded(self, result: Result, loop: flow.Loop) -> None:
        """The relative moves of a loop whose count is unbounded, on each axis the loop does not
        re-anchor (no absolute move, homing or position set) and whose distances do not cancel."""
        line = loop.header.span.line if loop.header.span else 0
        ops = [op for block in loop_blocks(loop) for op in block.ops]
        for axis in self.axes:
            anchored = any(isinstance(op, ir.Move) and op.mode is ir.MoveMode.ABSOLUTE
                           and any(axis in self.axes_of(a) for a, _ in op.targets)
                           or isinstance(op, (ir.Home, ir.SetPosition)) and axis in self.axes_of(op.axis)
                           for op in ops)
            moves = [(op, expr) for op in ops if isinstance(op, ir.Move) and op.mode is ir.MoveMode.RELATIVE
                     for a, expr in op.targets if axis in self.axes_of(a)]
            if anchored or not moves:
                continue
            distances = [evaluate(expr, {}) for _, expr in moves]
            if all(d.lo == d.hi for d in distances) and sum(d.lo for d in distances) == 0:
                continue
            for op, _ in moves:
                result.unbounded.setdefault(id(op), (op, axis, f"line {line}: the loop"))

    # one operation ----------------------------------------------------------------------------------
    def transfer(self, state: State, op, report: Result | None, loops: tuple[str, ...]) -> State:
        if isinstance(op, ir.Assign):
            value = evaluate(op.value, state)
            if op.target.name in self.int_vars and not math.isinf(value.lo) and not math.isinf(value.hi):
                value = Interval(float(math.trunc(value.lo)), float(math.trunc(value.hi)))
            if report is not None:
                report.assigns.setdefault(op.target.name, []).append((op, value))
            return {**state, op.target.name: value}
        if isinstance(op, ir.Move):
            out = dict(state)
            for axis_name, expr in op.targets:
                value = evaluate(expr, state)
                for axis in self.axes_of(axis_name):
                    relative = op.mode is ir.MoveMode.RELATIVE
                    target = arith("+", state.get(POS + axis, TOP), value) if relative else value
                    if report is not None:
                        self.note_ramp(state, op, axis, report)
                        line = op.span.line if op.span else 0
                        report.checks.append(Check(op, axis, target, relative, loops, state.get(HOMED + axis, TOP),
                                                   before=state.get(POS + axis, TOP),
                                                   branches=tuple(b for b in self.branch_lines if b < line)[-3:],
                                                   anchored=state.get(ANCHOR + axis, TOP)))
                    env = self.envelopes[axis]
                    travel = Interval(env.min if env.min is not None else -INF, env.max if env.max is not None else INF)
                    inside = target.meet(travel)
                    if inside.empty:  # the limit switch stops it at the end it ran into
                        inside = point(travel.hi if target.lo > travel.hi else travel.lo)
                    out[POS + axis] = inside
                    if relative and state.get(ANCHOR + axis) == point(0):
                        peak = state.get(PEAK + axis)
                        out[PEAK + axis] = target if peak is None else peak.join(target)
                    if not relative:
                        out[ANCHOR + axis] = point(1)
            return out
        if isinstance(op, ir.SetPosition):
            value = evaluate(op.value, state)
            return {**state, **{POS + a: value for a in self.axes_of(op.axis)},
                    **{ANCHOR + a: point(1) for a in self.axes_of(op.axis)}}
        if isinstance(op, ir.Home):
            out = dict(state)
            for axis in self.axes_of(op.axis):
                home = self.envelopes[axis].home or 0.0
                out[POS + axis] = point(home) if op.zero != "none" else TOP
                out[HOMED + axis] = point(1)
                out[ANCHOR + axis] = point(1)
            return out
        if isinstance(op, (ir.Slew, ir.Home)) and report is not None:
            speed = op.velocity if isinstance(op, ir.Slew) else op.speed
            if speed is not None:
                value = evaluate(speed, state)
                magnitude = Interval(0.0 if value.lo <= 0 <= value.hi else min(abs(value.lo), abs(value.hi)),
                                     max(abs(value.lo), abs(value.hi)))
                for axis in self.axes_of(op.axis):
                    report.motion.append((op, axis, "speed", magnitude))
        if isinstance(op, (ir.Arc, ir.Slew)):
            out = dict(state)
            for axis_name in (op.axes if isinstance(op, ir.Arc) else (op.axis,)):
                for axis in self.axes_of(axis_name):
                    env = self.envelopes[axis]
                    out[POS + axis] = Interval(env.min if env.min is not None else -INF,
                                               env.max if env.max is not None else INF)
                    out[ANCHOR + axis] = TOP
            return out
        if isinstance(op, ir.SetMotion):
            value = evaluate(op.value, state)
            if report is not None:
                report.settings.append((op, value))
            return {**state, **{SET + op.param.value + ":" + a: value for a in self.axes_of(op.axis)}}
        if isinstance(op, ir.Call):
            summary = self.summary(op.routine)
            out = dict(state)
            if report is not None:  # the callee's relative moves, from where this call starts them
                for axis, peak in summary.peaks.items():
                    report.checks.append(Check(op, axis, arith("+", state.get(POS + axis, TOP), peak), True, loops,
                                               state.get(HOMED + axis, TOP), before=state.get(POS + axis, TOP),
                                               anchored=state.get(ANCHOR + axis, TOP)))
            for name, value in summary.writes.items():
                out[name] = value if op.cond is None else value.join(state.get(name, TOP))
            for axis, (kind, value) in summary.positions.items():
                before = state.get(POS + axis, TOP)
                after = value if kind == "absolute" else arith("+", before, value)
                out[POS + axis] = after if op.cond is None else after.join(before)
                if kind == "absolute" and value != TOP:
                    out[ANCHOR + axis] = point(1)
            for axis in summary.homes:
                if op.cond is None:
                    out[HOMED + axis] = point(1)
            return out
        return state
