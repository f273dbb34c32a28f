"""Which variables of a module only count rounds, and which blocks a round can reach: the static
side of replaying rounds that differ only by such a counter (sim/repeats.py, whose docstring has
the argument). A counter is an int32 variable whose every assignment is a constant (a reset) or
itself plus or minus a whole constant (a step), and whose every reading is a comparison with a
constant, as the hidden `%Lk` of X150's `L` loop."""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

from mcc.compiler import ir
from mcc.sim import values


@dataclass
class Counter:
    """An int32 variable that only counts: every assignment is a constant (a reset) or itself plus
    or minus a whole constant (a step), and every reading is a comparison with a constant. Its
    value reaches nothing but those comparisons and itself, so rounds that differ only by it do
    the same thing while no comparison changes its outcome."""

    steps: set[int]  # the constants its steps add
    resets: list[int]  # the ids of the blocks that assign it a constant
    compared: list  # the constants it is compared with


def _step(name: str, value) -> int | None:
    """The whole constant `value` adds to variable `name` (`V + k`, `k + V`, `V - k`), else None."""
    if not isinstance(value, ir.BinOp) or value.op not in ("+", "-"):
        return None
    left, right = value.left, value.right
    if value.op == "+" and isinstance(left, ir.Const):
        left, right = right, left
    if isinstance(left, ir.Var) and left.name == name and isinstance(right, ir.Const) \
            and type(right.value) is int:
        return right.value if value.op == "+" else -right.value
    return None


def _readings(node, found: dict, spoiled: set) -> None:
    """Every variable `node` reads: a bare variable compared with a constant adds the constant to
    `found`; any other reading spoils it (a print, arithmetic, an argument)."""
    stack = [node]
    while stack:
        node = stack.pop()
        if isinstance(node, ir.Compare):
            pair = (node.left, node.right) if isinstance(node.left, ir.Var) else (node.right, node.left)
            if isinstance(pair[0], ir.Var) and isinstance(pair[1], ir.Const):
                found.setdefault(pair[0].name, []).append(pair[1].value)
                continue
        if isinstance(node, ir.Var):
            spoiled.add(node.name)
        elif isinstance(node, (list, tuple)):
            stack.extend(node)
        elif dataclasses.is_dataclass(node) and not isinstance(node, (ir.Block, ir.Routine, type)):
            stack.extend(getattr(node, f.name) for f in dataclasses.fields(node) if f.name != "span")


def counters_of(module: ir.Module, type_of) -> dict[str, Counter]:
    """The module's counters (`Counter`), by name; `type_of` gives a variable's type as the run
    stores it. Every field of every operation and terminator is looked at, not only the
    expressions the IR says an operation reads, so that no reading is missed."""
    steps: dict[str, set[int]] = {}
    resets: dict[str, list[int]] = {}
    compared: dict[str, list] = {}
    spoiled: set[str] = set()
    for routine in module.routines:
        for block in routine.blocks:
            for op in block.ops:
                if isinstance(op, ir.Assign):
                    name = op.target.name
                    step = _step(name, op.value)
                    if step is not None:
                        steps.setdefault(name, set()).add(step)
                        continue
                    if isinstance(op.value, ir.Const):
                        resets.setdefault(name, []).append(id(block))
                        continue
                    spoiled.add(name)
                    _readings(op.value, compared, spoiled)
                else:
                    _readings(op, compared, spoiled)
            _readings(block.terminator, compared, spoiled)
    names = (set(steps) | set(resets)) - spoiled
    return {name: Counter(steps.get(name, set()), resets.get(name, []), compared.get(name, []))
            for name in sorted(names) if type_of(name) is ir.VarType.INT32}


def _settled(cond, ranges: dict[str, tuple[int, int]]) -> bool | None:
    """The outcome of `cond` when it compares a counter of `ranges` with a constant outside the
    range of values the counter can take (then every one of them gives that outcome); else None."""
    if not isinstance(cond, ir.Compare):
        return None
    left, right = cond.left, cond.right
    var, const = (left, right) if isinstance(left, ir.Var) else (right, left)
    if not isinstance(var, ir.Var) or not isinstance(const, ir.Const) or var.name not in ranges:
        return None
    (low, high), bound = ranges[var.name], const.value
    try:
        if low <= bound <= high:
            return None
        return values.compare(cond.op, *((low, bound) if var is left else (bound, low)))
    except (TypeError, ArithmeticError, values.ArithmeticFault):
        return None


def round_blocks(module: ir.Module, starts: list[int], ranges: dict[str, tuple[int, int]]) -> set[int]:
    """The blocks (by id) that a round can run in before it first resets one of the counters of
    `ranges`, which until then stay within their ranges: a superset.

    The round starts in the blocks `starts` of the frames that run in it (the lowest frame that
    runs is never popped; those above it finish and are called again). A branch on a comparison
    of a counter with a constant outside its range goes one way only. Routines called from the
    blocks reached run whole, and any handler's routine may interrupt."""
    block_of = {b.label: b for r in module.routines for b in r.blocks}
    entries = {r.name: id(r.entry) for r in module.routines if r.entry is not None}
    succ: dict[int, list[int]] = {}
    calls: dict[int, list[int]] = {}
    handlers: list[int] = []
    for routine in module.routines:
        for block in routine.blocks:
            term = block.terminator
            targets: list[str] = []
            if isinstance(term, ir.Jump):
                targets = [term.target]
            elif isinstance(term, ir.Branch):
                outcome = _settled(term.cond, ranges)
                targets = [term.then, term.otherwise] if outcome is None else [term.then if outcome else term.otherwise]
            succ[id(block)] = [id(block_of[t]) for t in targets if t in block_of]
            if isinstance(term, ir.GotoRoutine) and term.routine in entries:
                succ[id(block)].append(entries[term.routine])
            calls[id(block)] = [entries[op.routine] for op in block.ops
                                if isinstance(op, ir.Call) and op.routine in entries]
            handlers += [entries[op.routine] for op in block.ops
                         if isinstance(op, ir.SetHandler) and op.routine in entries]
    blocks: set[int] = set()
    todo = [*starts, *handlers]
    while todo:
        block = todo.pop()
        if block not in blocks:
            blocks.add(block)
            todo += succ.get(block, ())
            todo += calls.get(block, ())
    return blocks


def short_of(bound, value: int, delta: int) -> int | float:
    """How many rounds moving `value` by `delta` leave it short of `bound` (infinity when it moves
    away from it or the bound is no number that it could meet)."""
    try:
        if delta > 0 and bound > value:
            return int((bound - value - 1) // delta)
        if delta < 0 and bound < value:
            return int((value - bound - 1) // -delta)
    except (TypeError, ValueError, OverflowError, ArithmeticError):  # an infinite or NaN bound
        pass
    return float("inf")
