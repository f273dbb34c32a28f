"""Control-flow helpers over the shared IR, for rules of every dialect.

The IR gives each routine a list of blocks with one terminator each. Rules ask the same few
questions — which blocks can run, which are inside a loop, what state reaches an operation — so
they are answered here once. Edges that leave a routine (a cross-routine `Jump`) are not followed:
each routine is analysed from its own entry, and calls are summarised by the rules that care.
"""

from __future__ import annotations

from collections import deque
from typing import Callable, Hashable, Iterable, Iterator, TypeVar

from mcc.compiler import ir

State = TypeVar("State", bound=Hashable)


def block_index(module: ir.Module) -> dict[str, tuple[ir.Routine, ir.Block]]:
    """Block label -> (routine, block), for the whole module."""
    return {block.label: (routine, block) for routine, block in module.blocks()}


def local_successors(routine: ir.Routine, block: ir.Block) -> list[ir.Block]:
    """Successor blocks inside the same routine."""
    out = []
    for label in ir.successors(block.terminator):
        target = routine.block(label)
        if target is not None:
            out.append(target)
    return out


def reachable(routine: ir.Routine, start: ir.Block | None = None) -> list[ir.Block]:
    """Blocks reachable from `start` (default: the entry) inside the routine, in routine order."""
    first = start or routine.entry
    if first is None:
        return []
    seen = {first.label}
    queue = deque([first])
    while queue:
        for succ in local_successors(routine, queue.popleft()):
            if succ.label not in seen:
                seen.add(succ.label)
                queue.append(succ)
    return [b for b in routine.blocks if b.label in seen]


def in_loops(routine: ir.Routine) -> set[str]:
    """Labels of blocks that can reach themselves again (the body of some loop)."""
    looping = set()
    for block in routine.blocks:
        for succ in local_successors(routine, block):
            if block.label in {b.label for b in reachable(routine, succ)}:
                looping.add(block.label)
                break
    return looping


def is_fallthrough(jump: ir.Jump, target: ir.Block | None) -> bool:
    """A `Jump` the lowering added because one label's code runs on into the next label.

    MCode lowering gives such a jump the span of the `LB` line it falls into (the target block's
    own span); a written `BR` has the span of the `BR` statement.
    """
    return target is not None and jump.span is not None and jump.span == target.span


def foreign_jumps(module: ir.Module, routine: ir.Routine) -> Iterator[tuple[ir.Block, str, ir.Routine, bool]]:
    """Edges from `routine` to blocks of another routine: (block, target label, target routine, fallthrough)."""
    index = block_index(module)
    for block in routine.blocks:
        for label in ir.successors(block.terminator):
            found = index.get(label)
            if found is None or found[0] is routine:
                continue
            fall = isinstance(block.terminator, ir.Jump) and is_fallthrough(block.terminator, found[1])
            yield block, label, found[0], fall


def reads(node) -> Iterator:
    """Every sub-expression of an expression or condition."""
    yield from ir.walk_expr(node)


def op_reads(op) -> Iterator:
    for expr in ir.op_exprs(op):
        yield from ir.walk_expr(expr)


def term_reads(term) -> Iterator:
    for expr in ir.term_exprs(term):
        yield from ir.walk_expr(expr)


def forward(routine: ir.Routine, entry: State, transfer: Callable[[State, object], State],
            join: Callable[[State, State], State],
            edge: Callable[[State, ir.Block, ir.Block], State] | None = None) -> dict[str, State]:
    """A forward data-flow analysis to a fixed point: the state at the start of each reachable block.

    `transfer(state, item)` is applied to each operation and then to the terminator; `edge` may
    refine the state along one edge (e.g. after a branch that polled a flag); `join` merges states
    where paths meet. States must be hashable and the lattice finite (sets of facts are).
    """
    start = routine.entry
    if start is None:
        return {}
    states: dict[str, State] = {start.label: entry}
    queue = deque([start])
    while queue:
        block = queue.popleft()
        state = states[block.label]
        for op in block.ops:
            state = transfer(state, op)
        state = transfer(state, block.terminator)
        for succ in local_successors(routine, block):
            out = edge(state, block, succ) if edge is not None else state
            old = states.get(succ.label)
            new = out if old is None else join(old, out)
            if old is None or new != old:
                states[succ.label] = new
                queue.append(succ)
    return states


def replay(block: ir.Block, state: State, transfer: Callable[[State, object], State]) -> Iterator[tuple[object, State]]:
    """Each operation (then the terminator) of a block with the state just before it."""
    for item in [*block.ops, block.terminator]:
        yield item, state
        state = transfer(state, item)


def ops(module: ir.Module, kinds: type | tuple[type, ...] | None = None) -> Iterable[tuple[ir.Routine, ir.Block, object]]:
    """Every operation of the module (optionally only of some types), in module order."""
    for routine, block in module.blocks():
        for op in block.ops:
            if kinds is None or isinstance(op, kinds):
                yield routine, block, op


def natural_loops(routine: ir.Routine) -> list[tuple[ir.Block, list[ir.Block]]]:
    """(header, body) of each loop: a block some later block jumps back to.

    The body is every block from which the header can be reached again without passing through the
    header itself — the blocks of a WHILE, an MCode `BR` loop or an X150 `L..N`.
    """
    preds: dict[str, list[ir.Block]] = {b.label: [] for b in routine.blocks}
    for block in routine.blocks:
        for succ in local_successors(routine, block):
            preds[succ.label].append(block)
    found = []
    for header in routine.blocks:
        inside = {b.label for b in reachable(routine, header)}
        back = [p for p in preds[header.label] if p.label in inside]
        body: set[str] = set()
        stack = list(back)
        while stack:
            block = stack.pop()
            if block.label in body or block is header:
                continue
            body.add(block.label)
            stack += preds[block.label]
        if back:
            found.append((header, [b for b in routine.blocks if b.label in body or b is header]))
    return found


class MustFacts:
    """Facts that hold on every path: settings made, variables written. Facts are only added.

    `gen(item)` gives the facts an operation or terminator establishes. A call adds what the callee
    establishes on every path to its end; a subroutine starts with what holds at every call site
    (one it is never called from is not analysed: a host may run it in any state).
    """

    def __init__(self, module: ir.Module, gen: Callable[[object], Iterable[Hashable]]):
        self.module = module
        self.gen = gen
        self.summaries: dict[str, frozenset] = {}

    def transfer(self, state: frozenset, item) -> frozenset:
        if isinstance(item, ir.Call):
            return state | self.summary(item.routine)
        facts = self.gen(item) if item is not None else ()
        return state | frozenset(facts) if facts else state

    def summary(self, name: str) -> frozenset:
        if name in self.summaries:
            return self.summaries[name]
        self.summaries[name] = frozenset()  # recursion: assume nothing
        routine = self.module.routine(name)
        if routine is None:
            return frozenset()
        states = forward(routine, frozenset(), self.transfer, frozenset.intersection)
        exits = []
        for block in routine.blocks:
            if block.label in states and not local_successors(routine, block):
                state = states[block.label]
                for item in [*block.ops, block.terminator]:
                    state = self.transfer(state, item)
                exits.append(state)
        self.summaries[name] = frozenset.intersection(*exits) if exits else frozenset()
        return self.summaries[name]

    def states(self, start: dict[str, frozenset] | None = None) -> dict[str, dict[str, frozenset]]:
        """Routine name -> block label -> facts at the block's start, for every analysed routine.

        `start` gives the entry facts of routines that are not subroutines (default: none).
        """
        start = start or {}
        entries: dict[str, frozenset] = {r.name: start.get(r.name, frozenset()) for r in self.module.routines
                                         if r.kind is not ir.RoutineKind.SUBROUTINE}
        result: dict[str, dict[str, frozenset]] = {}
        queue = deque(entries)
        while queue:
            name = queue.popleft()
            routine = self.module.routine(name)
            if routine is None:
                continue
            states = forward(routine, entries[name], self.transfer, frozenset.intersection)
            result[name] = states
            for block in routine.blocks:
                if block.label not in states:
                    continue
                for item, state in replay(block, states[block.label], self.transfer):
                    if isinstance(item, ir.Call):
                        old = entries.get(item.routine)
                        new = state if old is None else old & state
                        if old is None or new != old:
                            entries[item.routine] = new
                            queue.append(item.routine)
        return result
