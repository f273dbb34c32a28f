"""Procedural abstraction (-Os): a sequence of operations repeated in several places becomes one
subroutine called from each place.

What it does: machine-made programs (a drawing converted to moves, a teach-in recording) repeat
the same runs of moves, outputs and delays. Each run of at least three operations that occurs at
least twice, and whose call sites and one copy cost fewer target lines than the copies, is moved
into a new subroutine; each occurrence becomes a call. The cost is counted in the target's own
measure where it is cheap to get: Arcus assembly lines from the profile's `[arcus.cost]` table (a
two-axis move costs two lines, a GOSUB one, SUB and ENDSUB one each); one line per operation for
the other targets. Runs are found by growing repeated windows one operation at a time (a window
seen once is never grown), best benefit first, over at most three rounds (a later round can
outline runs that contain the earlier rounds' calls' neighbours, never the calls).

Why it is safe: a call runs the subroutine's operations in order and returns to the next
operation, so each place runs the same operations in the same order. Runs never contain a call
(so the new subroutine calls nothing and adds one level of nesting at most, checked against the
target's limit), a native command, or anything of an immediate stream or event handler (MCode
runs CL only in programs; handlers are left as written). The pass stops when the target's
subroutine numbers (Arcus SUB 1-30: SUB 31 is the error handler; X150 sequences 1-64) or its
call nesting are used up.

Where the new subroutine goes (MCode): a device holds only what is sent between `PG <address>` and
`PG`; a line after the closing `PG` runs at once in immediate mode (lexium-mcode.txt L510-L512), and
a program's subroutines belong inside its region (`PG 1 [MAIN PROG] [SUBROUTINES]`, L4794). So on
an MCode target a run is outlined only from the places of one program region, and the new
subroutine is placed after that region's last routine, before its closing `PG` (the backend writes
routines in module order and closes a region at the next `PG <address>` or immediate line). A region
whose last routine runs off its end (no E or RT) is not outlined: that routine would run on into the
new subroutine.

Needs: the call graph (computed here) and the target profile's limits.
"""

from __future__ import annotations

from dataclasses import dataclass

from mcc.compiler import dialects, ir
from mcc.compiler.opt.common import key

NAME = "outline"
NEEDS = ()
MIN_RUN, MAX_RUN = 3, 24
ROUNDS = 3
ELIGIBLE = (ir.RoutineKind.MAIN, ir.RoutineKind.SUBROUTINE, ir.RoutineKind.POWERUP)
# host controls stay where they are: X150 never saves C or # in a sequence, and a pause moved into a
# subroutine could no longer be shown to follow the end of a move (ir.settled_ops)
NOT_OUTLINED = (ir.Call, ir.Native, ir.SetHandler, ir.Save, ir.Pause, ir.Resume, ir.Step)


def run(module: ir.Module, context) -> int:
    capacity = free_subroutines(module, context.profile)
    if capacity <= 0 or not nesting_allows(module, context.profile):
        return 0
    cost = target_cost(context.profile, module.dialect)
    target = context.profile.dialect if context.profile is not None else module.dialect
    saved = 0
    for _ in range(ROUNDS):
        made, gained = one_round(module, capacity, cost, dialects.get(target).program_regions)
        capacity -= made
        saved += gained
        if not made or capacity <= 0:
            break
    return saved


def free_subroutines(module: ir.Module, profile) -> int:
    """How many new subroutines the target can number (its `dialects.RoutineNumbers`).

    A numbering target (Arcus SUB n, X150 sequences) gives routines without a number of their own
    the free numbers of its range in ascending order from its first one, so the new ones (appended
    last) get the highest free numbers; a reserved number (Arcus SUB 31 runs on an error) is never
    given. Where every routine takes a number (X150: the main program is a sequence too), a module
    that calls routines stored on the device outlines nothing, since the writer does not know their
    numbers and could give one of them to a new routine. A naming target (MCode labels) takes a
    fixed number of new ones."""
    target = profile.dialect if profile is not None else module.dialect
    numbers = dialects.get(target).routine_numbers
    counted = [r for r in module.routines if r.kind is not ir.RoutineKind.IMMEDIATE] if numbers.every_routine \
        else [r for r in module.routines if r.kind is ir.RoutineKind.SUBROUTINE]
    if not numbers.range_key:
        return numbers.named - len(counted)
    if numbers.every_routine and module.externals:
        return 0
    low, high = (int(n) for n in (profile.get(numbers.range_key, list(numbers.default)) if profile
                                  else numbers.default))
    first = int(profile.get(numbers.first_key, numbers.first or low)) if profile and numbers.first_key \
        else (numbers.first or low)
    taken: set[int] = set()
    pending = 0
    for routine in counted:
        if routine.number is not None and low <= routine.number <= high and routine.number not in taken:
            taken.add(routine.number)
        else:
            pending += 1
    free = [n for n in range(max(low, first), high + 1) if n not in taken and n not in numbers.reserved]
    return len(free) - pending


def nesting_allows(module: ir.Module, profile) -> bool:
    limit = int(profile.get("limits.nesting", 0)) if profile is not None else 0
    return not limit or call_depth(module) + 1 <= limit


def call_depth(module: ir.Module) -> int:
    """The deepest chain of calls in the module (a cycle counts once)."""
    calls = {r.name: {op.routine for b in r.blocks for op in b.ops if isinstance(op, ir.Call)}
             for r in module.routines}
    depth: dict[str, int] = {}
    for start in calls:
        stack = [(start, iter(sorted(calls[start])))]
        on_path = {start}
        while stack:
            name, children = stack[-1]
            child = next(children, None)
            if child is None:
                stack.pop()
                on_path.discard(name)
                depth[name] = 1 + max((depth.get(c, 0) for c in calls[name] if c not in on_path), default=0)
            elif child in calls and child not in depth and child not in on_path:
                on_path.add(child)
                stack.append((child, iter(sorted(calls[child]))))
    return max(depth.values(), default=0)


@dataclass(frozen=True)
class Cost:
    """What operations, calls and a subroutine's frame cost on the target, in its own lines."""

    statements: dict[str, int]
    default: int = 1
    per_axis: bool = False  # Arcus: a move costs one line per axis it names

    def of(self, op) -> int:
        if not self.per_axis:
            return 1
        if isinstance(op, ir.Move):
            return sum(self.get(axis) for axis, _ in op.targets)
        if isinstance(op, ir.Arc):
            return self.get("ARC" if op.angle is not None else "CIR")
        if isinstance(op, ir.Assign):
            operators = sum(1 for n in ir.walk_expr(op.value) if isinstance(n, (ir.BinOp, ir.UnOp)))
            return self.get("V") if operators == 0 else operators * self.get("V_OP")
        return self.get(ARCUS_KEYS.get(type(op), ""))

    def get(self, name: str) -> int:
        return max(1, int(self.statements.get(name, self.default)))

    @property
    def call(self) -> int:
        return self.get("GOSUB") if self.per_axis else 1

    @property
    def frame(self) -> int:
        """A new subroutine's own lines: SUB and ENDSUB on Arcus; a label and a return elsewhere."""
        return self.get("SUB") + self.get("ENDSUB") if self.per_axis else 2


ARCUS_KEYS = {ir.Delay: "DELAY", ir.SetOutput: "DO", ir.WaitMotion: "WAIT", ir.Home: "HOME", ir.Stop: "STOP",
              ir.SetPosition: "P"}


def target_cost(profile, dialect: str) -> Cost:
    """The target's price of a statement: its profile's cost table (Arcus assembly lines per
    statement, per axis of a move), else one line a statement."""
    key = dialects.get(profile.dialect if profile is not None else dialect).cost_key
    if key and profile is not None:
        table = profile.get(key, {}) or {}
        statements = {str(k).upper(): int(v) for k, v in (table.get("statements") or {}).items()}
        return Cost(statements, int(table.get("default", 1)), per_axis=True)
    if key:
        return Cost({}, 1, per_axis=True)
    return Cost({})


def benefit(count: int, run_cost: int, cost: Cost, has_move: bool) -> int:
    """Lines saved by outlining `count` copies of a run costing `run_cost`: the copies, less the
    calls, one copy and the subroutine's frame (and a move-mode line a backend may write at the
    subroutine's start, where the mode in force is not known)."""
    return count * run_cost - (count * cost.call + run_cost + cost.frame + (1 if has_move else 0))


def program_regions(module: ir.Module) -> dict[str, int | None]:
    """The MCode program region each routine is written in, as the backend lays them out
    (backends/mcode.py Writer.run): a routine with a PG address opens a region, an immediate
    stream closes it, a routine without an address continues the open one. None: outside any
    region (never outlined into or from). Another dialect's program is written as one region (its
    immediate lines are moved around it, Writer.program_order)."""
    if not dialects.get(module.dialect).program_regions:
        return {r.name: (None if r.kind is ir.RoutineKind.IMMEDIATE else 0) for r in module.routines}
    origin_given = any(r.origin is not None for r in module.routines)
    regions: dict[str, int | None] = {}
    region, is_open = -1, False
    for routine in module.routines:
        if routine.kind is ir.RoutineKind.IMMEDIATE:
            regions[routine.name] = None
            is_open = False
            continue
        if routine.origin is not None or not is_open and not origin_given:
            region, is_open = region + 1, True
        regions[routine.name] = region if is_open else None
    # an MCode routine that runs off its end runs on into the next line (M323): a region whose last
    # routine can do so has no place for a new subroutine, which would run after it
    last: dict[int, ir.Routine] = {}
    for routine in module.routines:
        if regions[routine.name] is not None:
            last[regions[routine.name]] = routine
    for region, routine in last.items():
        if any(isinstance(b.terminator, ir.FallOff) or b.terminator is None for b in routine.blocks):
            for name, where in regions.items():
                if where == region:
                    regions[name] = None
    return regions


def one_region(places: list[tuple[int, int]], owner: list[int | None]) -> list[tuple[int, int]]:
    """The places of the region holding most of them (the first such region on a tie)."""
    counts: dict[int, int] = {}
    for bi, _ in places:
        if owner[bi] is not None:
            counts[owner[bi]] = counts.get(owner[bi], 0) + 1
    if not counts:
        return []
    best = max(counts, key=lambda r: (counts[r], -r))
    return [(bi, start) for bi, start in places if owner[bi] == best]


def place_routine(module: ir.Module, routine: ir.Routine, region: int | None,
                  regions: dict[str, int | None] | None) -> None:
    """Append the new subroutine; on MCode, right after the last routine of its callers' region."""
    if regions is None:
        module.routines.append(routine)
        return
    last = max(i for i, r in enumerate(module.routines) if regions.get(r.name) == region)
    module.routines.insert(last + 1, routine)
    regions[routine.name] = region


def one_round(module: ir.Module, capacity: int, cost: Cost, in_regions: bool = False) -> tuple[int, int]:
    routines = [r for r in module.routines if r.kind in ELIGIBLE]
    blocks = [b for r in routines for b in r.blocks]
    regions = program_regions(module) if in_regions else None
    owner = [regions[r.name] if regions is not None else 0 for r in routines for _ in r.blocks]
    ids: dict = {}
    prices: list[int] = []
    moves: set[int] = set()
    coded = [[_code(op, ids, prices, moves, cost) for op in b.ops] for b in blocks]
    candidates = find(coded, prices, moves, cost)
    taken: list[set[int]] = [set() for _ in blocks]
    chosen: list[tuple[int, int, int, str]] = []  # (block, start, length, routine), applied at the end
    made = saved = 0
    for _, length, places, run_cost, has_move in candidates:
        if made >= capacity:
            break
        free = [(bi, start) for bi, start in places if not taken[bi].intersection(range(start, start + length))]
        free = one_region(non_overlapping(free, length), owner)
        gain = benefit(len(free), run_cost, cost, has_move)
        if len(free) < 2 or gain <= 0:
            continue
        name = new_name(module)
        first_bi, first_start = free[0]
        body = list(blocks[first_bi].ops[first_start:first_start + length])
        routine = ir.Routine(name, ir.RoutineKind.SUBROUTINE,
                             [ir.Block(name, body, ir.Return(body[-1].span))], span=body[0].span)
        place_routine(module, routine, owner[first_bi], regions)
        for bi, start in free:
            taken[bi].update(range(start, start + length))
            chosen.append((bi, start, length, name))
        made += 1
        saved += gain
    replace(blocks, chosen)
    return made, saved


def _code(op, ids: dict, prices: list[int], moves: set[int], cost: Cost) -> int:
    """A number per distinct operation (equal numbers: equal operations); -1 and below: never
    part of a run."""
    if isinstance(op, NOT_OUTLINED):
        return -1
    code = ids.get(k := key(op))
    if code is None:
        code = ids[k] = len(prices)
        prices.append(cost.of(op))
        if isinstance(op, (ir.Move, ir.Arc)):
            moves.add(code)
    return code


def find(coded: list[list[int]], prices: list[int], moves: set[int], cost: Cost) -> list[tuple]:
    """Repeated runs, best first: (benefit, length, [(block index, start), ...], run cost, has a move).

    Windows of MIN_RUN operations are grouped by content; only a group seen at two places or more
    is grown by one operation, so the work stays near the program's length when little repeats."""
    groups: dict[tuple, list[tuple[int, int]]] = {}
    for bi, codes in enumerate(coded):
        for start in range(0, len(codes) - MIN_RUN + 1):
            window = tuple(codes[start:start + MIN_RUN])
            if min(window) >= 0:
                groups.setdefault(window, []).append((bi, start))
    found = []
    length = MIN_RUN
    while groups and length <= MAX_RUN:
        grown: dict[tuple, list[tuple[int, int]]] = {}
        for window, where in groups.items():
            if len(where) < 2:
                continue
            run_cost = sum(prices[c] for c in window)
            has_move = any(c in moves for c in window)
            places = non_overlapping(where, length)
            gain = benefit(len(places), run_cost, cost, has_move)
            if len(places) >= 2 and gain > 0:
                found.append((gain, length, places, run_cost, has_move))
            for bi, start in where:
                end = start + length
                if end < len(coded[bi]) and coded[bi][end] >= 0:
                    grown.setdefault(window + (coded[bi][end],), []).append((bi, start))
        groups = grown
        length += 1
    found.sort(key=lambda c: (-c[0], -c[1], c[2]))
    return found


def non_overlapping(places: list[tuple[int, int]], length: int) -> list[tuple[int, int]]:
    kept: list[tuple[int, int]] = []
    last_end: dict[int, int] = {}
    for bi, start in sorted(places):
        if start >= last_end.get(bi, -1):
            kept.append((bi, start))
            last_end[bi] = start + length
    return kept


def replace(blocks: list[ir.Block], chosen: list[tuple[int, int, int, str]]) -> None:
    """Each chosen run becomes a call; later runs first, so earlier indices stay valid (the runs
    chosen in one round never overlap)."""
    for bi, start, length, name in sorted(chosen, key=lambda c: (c[0], c[1]), reverse=True):
        ops = blocks[bi].ops
        ops[start:start + length] = [ir.Call(name, None, ops[start].span)]


def new_name(module: ir.Module) -> str:
    taken = {r.name for r in module.routines} | {b.label for _, b in module.blocks()}
    n = 1
    while f"%sub{n}" in taken:
        n += 1
    return f"%sub{n}"
