"""Control-flow helpers over the shared IR, for rules of every dialect.

The IR gives each routine a list of blocks with one terminator each. Rules ask the same few
questions — which blocks can run, which are inside a loop, what state reaches an operation — so
they are answered here once. Edges that leave a routine (a cross-routine `Jump`) are not followed:
each routine is analysed from its own entry, and calls are summarised by the rules that care.
"""

from __future__ import annotations

import threading
from collections import deque
from contextlib import contextmanager
from dataclasses import dataclass, field
from typing import Callable, Hashable, Iterable, Iterator, TypeVar

from mcc.compiler import ir
from mcc.compiler.cfg import dataflow, graph, loops
from mcc.compiler.cfg.components import strongly_connected
from mcc.compiler.cfg.dataflow import Ordering
from mcc.compiler.cfg.graph import BlockIndex

State = TypeVar("State", bound=Hashable)


def block_index(module: ir.Module) -> dict[str, tuple[ir.Routine, ir.Block]]:
    """Block label -> (routine, block), for the whole module."""
    index: dict[str, tuple[ir.Routine, ir.Block]] = {}
    for routine, block in module.blocks():
        index.setdefault(block.label, (routine, block))
    return index


def routine_index(module: ir.Module) -> dict[str, ir.Routine]:
    """Routine name -> routine (the first of that name), built once instead of a search per call."""
    index: dict[str, ir.Routine] = {}
    for routine in module.routines:
        index.setdefault(routine.name, routine)
    return index


def successor_map(routine: ir.Routine) -> dict[str, list[ir.Block]]:
    """Block label -> successor blocks inside the routine, for every block: built once per analysis
    (looking each label up in the routine's block list would make every walk quadratic)."""
    index: dict[str, ir.Block] = {}
    for block in routine.blocks:
        index.setdefault(block.label, block)
    return {block.label: [index[label] for label in ir.successors(block.terminator) if label in index]
            for block in routine.blocks}


def local_successors(routine: ir.Routine, block: ir.Block) -> list[ir.Block]:
    """Successor blocks inside the same routine (one lookup; use `successor_map` in a walk)."""
    out = []
    for label in ir.successors(block.terminator):
        target = routine.block(label)
        if target is not None:
            out.append(target)
    return out


def reachable(routine: ir.Routine, start: ir.Block | None = None,
              succ: dict[str, list[ir.Block]] | None = None) -> list[ir.Block]:
    """Blocks reachable from `start` (default: the entry) inside the routine, in routine order."""
    first = start or routine.entry
    if first is None:
        return []
    succ = succ if succ is not None else successor_map(routine)
    seen = {first.label}
    queue = deque([first])
    while queue:
        for nxt in succ.get(queue.popleft().label, ()):
            if nxt.label not in seen:
                seen.add(nxt.label)
                queue.append(nxt)
    return [b for b in routine.blocks if b.label in seen]


def entry_points(routine: ir.Routine, used: Callable[[str], bool]) -> set[str]:
    """Named blocks of `routine` that nothing in the file reaches: not its entry, no block of the
    routine jumps or runs on into them, and no BR, CL, EX or trip names them (`used`). A host may start
    such a label with `EX` (real MDrive programs put entry points after a subroutine's RT), so it is
    an entry point of its own, not a part of the routine it follows (issue 24)."""
    succ = successor_map(routine)
    reached = {b.label for targets in succ.values() for b in targets}
    return {b.label for b in routine.blocks
            if b.named and b is not routine.entry and b.label not in reached and not used(b.label)}


def components(labels: Iterable[str], succ: Callable[[str], Iterable[str]]) -> list[list[str]]:
    """The strongly connected components of a graph, callees before callers (the analysis
    library's Tarjan, `mcc.compiler.cfg.components`)."""
    return strongly_connected(labels, succ)


def in_loops(routine: ir.Routine) -> set[str]:
    """Labels of blocks that can reach themselves again (the body of some loop): the members of a
    strongly connected component with a cycle, found in one linear pass."""
    succ = successor_map(routine)
    looping: set[str] = set()
    for component in components(succ, lambda label: (b.label for b in succ.get(label, ()))):
        if len(component) > 1 or any(b.label == component[0] for b in succ.get(component[0], ())):
            looping.update(component)
    return looping


def is_fallthrough(jump: ir.Jump, target: ir.Block | None) -> bool:
    """A `Jump` the lowering added because one label's code runs on into the next label.

    MCode lowering gives such a jump the span of the `LB` line it falls into (the target block's
    own span); a written `BR` has the span of the `BR` statement.
    """
    return target is not None and jump.span is not None and jump.span == target.span


def foreign_jumps(module: ir.Module, routine: ir.Routine,
                  index: dict[str, tuple[ir.Routine, ir.Block]] | None = None) \
        -> Iterator[tuple[ir.Block, str, ir.Routine, bool]]:
    """Edges from `routine` to blocks of another routine: (block, target label, target routine, fallthrough).

    Pass `index` (`block_index(module)`) when asking for many routines: building it is linear."""
    index = index if index is not None else block_index(module)
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


def stream_entries(module: ir.Module, transfer: Callable[[State, object], State],
                   join: Callable[[State, State], State], subroutines: bool) -> dict[str, State]:
    """Entry facts per routine. The controller keeps its settings between commands: each stretch of
    commands sent outside a program starts with what the stretches before it left, and a program
    starts with what the whole stream left (it runs after the download). `subroutines`: a
    subroutine starts with that too (else it has no entry here, and the caller decides)."""
    carried: State = frozenset()
    entries: dict[str, State] = {}
    for routine in module.routines:
        if routine.kind is ir.RoutineKind.IMMEDIATE:
            entries[routine.name] = carried
            end = exit_state(routine, forward(routine, carried, transfer, join), transfer, join)
            carried = carried if end is None else end
    for routine in module.routines:
        if subroutines or routine.kind is not ir.RoutineKind.SUBROUTINE:
            entries.setdefault(routine.name, carried)
    return entries


@dataclass(frozen=True)
class Shape:
    """A routine's graph as the forward walks need it: successors, the blocks by label, and the
    reachable labels in reverse postorder from the entry with their ranks; `index` and `ordering`
    are the same graph over block numbers, as the analysis library (`mcc.compiler.cfg`) takes it."""

    succ: dict[str, list[ir.Block]]
    blocks: dict[str, ir.Block]
    order: list[str]
    rank: dict[str, int]
    index: BlockIndex
    ordering: Ordering
    numbered: list[ir.Block]  # node number -> its block


_shared = threading.local()  # the shapes shared within `shared_shapes` (per thread: the editor's worker)


@contextmanager
def shared_shapes() -> Iterator[None]:
    """Within it, each routine's shape is computed once and shared by every walk. For analyses of
    a module that does not change meanwhile (the lint rules of one file, engine.run_rules), never
    for passes that rewrite it."""
    outer = getattr(_shared, "shapes", None)
    if outer is None:
        _shared.shapes = {}
    try:
        yield
    finally:
        if outer is None:
            _shared.shapes = None


def shape_of(routine: ir.Routine, start: ir.Block) -> Shape:
    """The routine's shape (`start` is its entry block), shared within `shared_shapes`."""
    cache = getattr(_shared, "shapes", None)
    if cache is not None:
        found = cache.get(id(routine))
        if found is not None and found[0] is routine:
            return found[1]
    index = BlockIndex.of_routine(routine)
    labels = index.labels
    numbered = routine.blocks
    succ = {block.label: [numbered[n] for n in targets] for block, targets in zip(routine.blocks, index.succ)}
    rpo = graph.reverse_postorder(index.number[start.label], index.succ)
    order = [labels[n] for n in rpo]
    shape = Shape(succ, {block.label: block for block in reversed(routine.blocks)}, order,
                  {label: i for i, label in enumerate(order)}, index, Ordering.of(rpo, len(labels)), numbered)
    if cache is not None:
        cache[id(routine)] = (routine, shape)  # the routine kept: its id is not reused meanwhile
    return shape


def forward(routine: ir.Routine, entry: State, transfer: Callable[[State, object], State],
            join: Callable[[State, State], State],
            edge: Callable[[State, ir.Block, ir.Block], State] | None = None) -> dict[str, State]:
    """A forward data-flow analysis to a fixed point: the state at the start of each reachable block.

    `transfer(state, item)` is applied to each operation and then to the terminator; `edge` may
    refine the state along one edge (e.g. after a branch that polled a flag); `join` merges states
    where paths meet. States must be hashable and the lattice finite (sets of facts are). The
    analysis library's solver (`mcc.compiler.cfg.dataflow`) over the routine's blocks, in reverse
    postorder.
    """
    start = routine.entry
    if start is None:
        return {}
    shape = shape_of(routine, start)
    numbered, labels = shape.numbered, shape.index.labels

    def through(node: int, state: State) -> State:
        block = numbered[node]
        for op in block.ops:
            state = transfer(state, op)
        return transfer(state, block.terminator)

    along = None if edge is None else (lambda state, u, v: edge(state, numbered[u], numbered[v]))
    states = dataflow.solve(shape.ordering, shape.index.succ, {shape.index.number[start.label]: entry},
                            through, join, along)
    return {labels[node]: state for node, state in states.items()}


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


@dataclass
class Loop:
    """One loop of a routine's loop-nesting forest: its header, the blocks directly inside it (not
    in an inner loop; the header first) and the loops nested in it."""

    header: ir.Block
    blocks: list[ir.Block] = field(default_factory=list)
    inner: list["Loop"] = field(default_factory=list)


def loop_forest(routine: ir.Routine) -> list[Loop]:
    """The routine's loops, innermost first: a header is a block a later block (one the depth-first
    walk reaches from it) jumps back to; its body is every block that reaches such a jump without
    passing through the header — the blocks of a WHILE, an MCode `BR` loop or an X150 `L..N`.

    The analysis library's Havlak loop-nesting forest (`mcc.compiler.cfg.loops`): each block is
    visited about once, so a nest of 500 loops costs what 500 loops in a row cost. Edges into a
    loop from outside the header's depth-first subtree (an irreducible entry) are not followed.
    """
    if routine.entry is None:
        return []
    index = BlockIndex.of_routine(routine)
    numbered = routine.blocks
    made: dict[int, Loop] = {}
    found: list[Loop] = []
    for loop in loops.loop_forest(graph.depth_first(0, index.succ), index.succ):
        made[loop.header] = Loop(numbered[loop.header], [numbered[n] for n in loop.nodes],
                                 [made[inner.header] for inner in loop.inner])
        found.append(made[loop.header])
    return found


def natural_loops(routine: ir.Routine) -> list[tuple[ir.Block, list[ir.Block]]]:
    """(header, body) of each loop of `loop_forest`, the body with its inner loops' blocks, in
    routine order. The bodies of a deep nest add up to more than the routine: rules that only need
    a property of each loop should compute it over `loop_forest` bottom-up instead."""
    position = {block.label: i for i, block in enumerate(routine.blocks)}
    out = []
    for loop in sorted(loop_forest(routine), key=lambda item: position[item.header.label]):
        body: list[ir.Block] = []
        work = [loop]
        while work:
            current = work.pop()
            body += current.blocks
            work += current.inner
        out.append((loop.header, sorted(body, key=lambda b: position[b.label])))
    return out


def call_graph(module: ir.Module) -> dict[str, list[str]]:
    """Routine name -> names of the routines it calls, in the order of its blocks."""
    graph: dict[str, list[str]] = {routine.name: [] for routine in module.routines}
    for routine, _, op in ops(module, ir.Call):
        graph[routine.name].append(op.routine)
    return graph


def summarize(name: str, summaries: dict, assume, graph: dict[str, list[str]], compute: Callable[[str], object]):
    """`summaries[name]`, computing the summaries of `name` and of the routines it calls, callees
    first, without Python recursion: a routine's summary may read its callees' summaries, which are
    ready (or `assume`d while a recursive call is still being summarised, as in a recursive walk)."""
    if name in summaries:
        return summaries[name]
    summaries[name] = assume
    post: list[str] = []
    stack = [(name, iter(graph.get(name, ())))]
    while stack:
        current, it = stack[-1]
        for callee in it:
            if callee not in summaries:
                summaries[callee] = assume
                stack.append((callee, iter(graph.get(callee, ()))))
                break
        else:
            stack.pop()
            post.append(current)
    for current in post:
        summaries[current] = compute(current)
    return summaries[name]


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
        self.routines = routine_index(module)
        self.calls = call_graph(module)

    def transfer(self, state: frozenset, item) -> frozenset:
        if isinstance(item, ir.Call):
            return state | self.summary(item.routine)
        facts = self.gen(item) if item is not None else ()
        return state | frozenset(facts) if facts else state

    def summary(self, name: str) -> frozenset:
        # a recursive call assumes nothing
        return summarize(name, self.summaries, frozenset(), self.calls, self.compute)

    def compute(self, name: str) -> frozenset:
        routine = self.routines.get(name)
        if routine is None:
            return frozenset()
        states = forward(routine, frozenset(), self.transfer, frozenset.intersection)
        succ = successor_map(routine)
        exits = []
        for block in routine.blocks:
            if block.label in states and not succ[block.label]:
                state = states[block.label]
                for item in [*block.ops, block.terminator]:
                    state = self.transfer(state, item)
                exits.append(state)
        return frozenset.intersection(*exits) if exits else frozenset()

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
            routine = self.routines.get(name)
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
                            if item.routine not in queue:
                                queue.append(item.routine)
        return result


def exit_state(routine: ir.Routine, states: dict, transfer, join):
    """The state after the routine's last blocks (those without a successor in the routine), from
    the states at block entries that `forward` computed; None when no last block is reached."""
    result = None
    succ = successor_map(routine)
    for block in routine.blocks:
        if block.label in states and not succ[block.label]:
            state = states[block.label]
            for item in [*block.ops, block.terminator]:
                state = transfer(state, item)
            result = state if result is None else join(result, state)
    return result
