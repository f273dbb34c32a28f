"""Procedural abstraction (-Os): a sequence of operations repeated in several places becomes one
subroutine called from each place.

What it does: machine-made programs (a drawing converted to moves, a teach-in recording) repeat
the same runs of moves, outputs and delays. Each run of at least three operations that occurs at
least twice, and whose call sites and one copy cost fewer operations than the copies, is moved
into a new subroutine; each occurrence becomes a call.

Why it is safe: a call runs the subroutine's operations in order and returns to the next
operation, so each place runs the same operations in the same order. Runs never contain a call
(so the new subroutine calls nothing and adds one level of nesting at most, checked against the
target's limit), a native command, or anything of an immediate stream or event handler (MCode
runs CL only in programs; handlers are left as written). The pass stops when the target's
subroutine numbers (Arcus SUB 0-31, X150 sequences 1-64) or its call nesting are used up.

Needs: the call graph (computed here) and the target profile's limits.
"""

from __future__ import annotations

from mcc.compiler import ir
from mcc.compiler.opt.common import key

NAME = "outline"
NEEDS = ()
MIN_RUN, MAX_RUN = 3, 24
ROUNDS = 3
ELIGIBLE = (ir.RoutineKind.MAIN, ir.RoutineKind.SUBROUTINE, ir.RoutineKind.POWERUP)
NOT_OUTLINED = (ir.Call, ir.Native, ir.SetHandler, ir.Save)


def run(module: ir.Module, context) -> int:
    capacity = free_subroutines(module, context.profile)
    if capacity <= 0 or not nesting_allows(module, context.profile):
        return 0
    saved = 0
    for _ in range(ROUNDS):
        made, gained = one_round(module, capacity)
        capacity -= made
        saved += gained
        if not made or capacity <= 0:
            break
    return saved


def free_subroutines(module: ir.Module, profile) -> int:
    used = sum(1 for r in module.routines if r.kind is ir.RoutineKind.SUBROUTINE)
    target = profile.dialect if profile is not None else module.dialect
    if target == "arcus":
        low, high = profile.get("arcus.subroutines", [0, 31]) if profile else (0, 31)
        return (high - low + 1) - 1 - used  # SUB 31 is kept for the error handler
    if target == "x150":
        low, high = profile.get("limits.sequences", [1, 64]) if profile else (1, 64)
        return (high - low + 1) - used
    return 32 - used  # MCode: labels share the 192-name table; keep the outlining modest


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


def one_round(module: ir.Module, capacity: int) -> tuple[int, int]:
    blocks = [b for r in module.routines if r.kind in ELIGIBLE for b in r.blocks]
    ids: dict = {}
    coded = [[_code(op, ids) for op in b.ops] for b in blocks]
    candidates = find(coded)
    taken: list[set[int]] = [set() for _ in blocks]
    chosen: list[tuple[int, int, int, str]] = []  # (block, start, length, routine), applied at the end
    made = saved = 0
    for benefit, length, places in candidates:
        if made >= capacity:
            break
        free = [(bi, start) for bi, start in places if not taken[bi] & set(range(start, start + length))]
        free = non_overlapping(free, length)
        if len(free) < 2 or len(free) * length - (len(free) + length + 2) <= 0:
            continue
        name = new_name(module)
        first_bi, first_start = free[0]
        body = list(blocks[first_bi].ops[first_start:first_start + length])
        routine = ir.Routine(name, ir.RoutineKind.SUBROUTINE,
                             [ir.Block(name, body, ir.Return(body[-1].span))], span=body[0].span)
        module.routines.append(routine)
        for bi, start in free:
            taken[bi] |= set(range(start, start + length))
            chosen.append((bi, start, length, name))
        made += 1
        saved += len(free) * length - (len(free) + length)
    replace(blocks, chosen)
    return made, saved


def _code(op, ids: dict) -> int:
    if isinstance(op, NOT_OUTLINED):
        return -1 - len(ids)  # unique: never part of a repeated run
    return ids.setdefault(key(op), len(ids))


def find(coded: list[list[int]]) -> list[tuple[int, int, list[tuple[int, int]]]]:
    """Repeated runs, best first: (benefit, length, [(block index, start), ...])."""
    found = []
    for length in range(MIN_RUN, MAX_RUN + 1):
        places: dict[tuple, list[tuple[int, int]]] = {}
        any_window = False
        for bi, codes in enumerate(coded):
            for start in range(0, len(codes) - length + 1):
                window = tuple(codes[start:start + length])
                if min(window) < 0:
                    continue
                any_window = True
                places.setdefault(window, []).append((bi, start))
        if not any_window:
            break
        for where in places.values():
            where = non_overlapping(where, length)
            if len(where) >= 2:
                benefit = len(where) * length - (len(where) + length + 2)
                if benefit > 0:
                    found.append((benefit, length, where))
    found.sort(key=lambda c: (-c[0], -c[1]))
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
    """Each chosen run becomes a call; later runs first, so earlier indices stay valid."""
    for bi, start, length, name in sorted(chosen, key=lambda c: (c[0], c[1]), reverse=True):
        ops = blocks[bi].ops
        ops[start:start + length] = [ir.Call(name, None, ops[start].span)]


def new_name(module: ir.Module) -> str:
    taken = {r.name for r in module.routines} | {b.label for _, b in module.blocks()}
    n = 1
    while f"%sub{n}" in taken:
        n += 1
    return f"%sub{n}"
