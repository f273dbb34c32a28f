"""The analysis library (compiler/cfg) against the definitions it implements, by brute force on
random graphs: dominators by removing a node and asking what is still reached, natural loops by
walking back from the latches, reducibility by the T1/T2 reductions, the data-flow solver against
the path semantics of two problems whose answers are known (strict dominators, and the nodes on
some path to a target)."""

from __future__ import annotations

from hypothesis import given, settings
from hypothesis import strategies as st

from mcc.compiler import ir
from mcc.compiler.cfg import dataflow, loops
from mcc.compiler.cfg.dominators import DominatorTree
from mcc.compiler.cfg.graph import BlockIndex, all_paths_reach, depth_first, predecessors

# node i -> its successors (none, one, two; repeats allowed, as a branch with equal arms)
graphs = st.integers(1, 12).flatmap(
    lambda n: st.lists(st.lists(st.integers(0, n - 1), max_size=2), min_size=n, max_size=n)
).map(lambda edges: [list(targets) for targets in edges])


def reached(succ: list, entry: int, without: int | None = None) -> set:
    if entry == without:
        return set()
    seen = {entry}
    work = [entry]
    while work:
        for nxt in succ[work.pop()]:
            if nxt != without and nxt not in seen:
                seen.add(nxt)
                work.append(nxt)
    return seen


def analysed(succ: list):
    walk = depth_first(0, succ)
    order = walk.reverse_postorder
    return walk, order, DominatorTree(order, predecessors(order, succ, len(succ)), len(succ))


@settings(max_examples=300, deadline=None)
@given(graphs)
def test_the_walk_orders_every_reached_node_before_its_successors(succ) -> None:
    """Reverse postorder: the reached nodes, the entry first, each edge forward except the
    retreating ones (to an ancestor in the walk, which `number`/`last` recognise)."""
    walk, order, _ = analysed(succ)
    assert set(order) == reached(succ, 0) and order[0] == 0 and len(order) == len(set(order))
    rank = {node: i for i, node in enumerate(order)}
    for u in order:
        for v in succ[u]:
            ancestor = walk.number[v] <= walk.number[u] <= walk.last[v]
            assert ((u, v) in walk.retreating) == ancestor
            assert ancestor or rank[u] < rank[v]


@settings(max_examples=300, deadline=None)
@given(graphs)
def test_dominators_are_the_nodes_every_path_passes(succ) -> None:
    """a dominates b exactly when b is not reached once a is taken out (or a is b); the immediate
    dominator is the strict dominator that every other strict dominator dominates."""
    _, order, tree = analysed(succ)
    for a in order:
        cut = reached(succ, 0, without=a)
        for b in order:
            assert tree.dominates(a, b) == (a == b or b not in cut), (a, b)
    for b in order[1:]:
        strict = {a for a in order if a != b and tree.dominates(a, b)}
        assert tree.idom[b] in strict and all(tree.dominates(a, tree.idom[b]) for a in strict)
    assert tree.idom[0] == 0


def reducible_by_reduction(succ: list) -> bool:
    """Hecht and Ullman's T1/T2: drop self-loops, merge a node with one predecessor into it;
    the graph is reducible when one node is left."""
    live = reached(succ, 0)
    edges = {u: {v for v in succ[u] if v in live} for u in live}
    changed = True
    while changed:
        changed = False
        for u in edges:
            edges[u].discard(u)  # T1
        for v in list(edges):
            preds = [u for u in edges if v in edges[u]]
            if v != 0 and len(preds) == 1:  # T2
                u = preds[0]
                edges[u] |= edges.pop(v)
                edges[u].discard(v)
                changed = True
                break
    return len(edges) == 1


def body_by_definition(succ: list, header: int, sources: list) -> set:
    """The header and every node that reaches a latch with a path avoiding the header."""
    preds = [[u for u in range(len(succ)) if n in succ[u]] for n in range(len(succ))]
    body = {header}
    work = list(sources)
    while work:
        node = work.pop()
        if node not in body:
            body.add(node)
            work += [p for p in preds[node] if p in reached(succ, 0)]
    return body


@settings(max_examples=300, deadline=None)
@given(graphs)
def test_loops_back_edges_and_reducibility(succ) -> None:
    """Back edges go to a dominator; the graph is reducible as T1/T2 say; on a reducible graph
    the loop-nesting forest's loops are the natural loops of the back edges."""
    walk, order, tree = analysed(succ)
    back = loops.back_edges(order, succ, tree)
    assert back == {(u, v) for u in order for v in succ[u] if tree.dominates(v, u)}
    assert loops.reducible(walk, tree) == reducible_by_reduction(succ)
    latches = loops.latches(order, succ, back)
    preds = predecessors(order, succ, len(succ))
    for header, sources in latches.items():
        assert loops.natural_loop(header, sources, preds) == body_by_definition(succ, header, sources)
    if loops.reducible(walk, tree):
        forest = loops.loop_forest(walk, succ)
        assert {loop.header for loop in forest} == set(latches)
        for loop in forest:
            body, work = set(), [loop]
            while work:
                current = work.pop()
                body |= set(current.nodes)
                work += current.inner
            assert body == loops.natural_loop(loop.header, latches[loop.header], preds)
            assert loop.nodes[0] == loop.header


@settings(max_examples=300, deadline=None)
@given(graphs, st.sets(st.integers(0, 11)))
def test_all_paths_reach_is_the_least_fixpoint(succ, sinks) -> None:
    """A node is in when it is a sink, or has successors all in (computed by scanning until
    nothing changes, the slow way it replaced)."""
    sinks = {s for s in sinks if s < len(succ)}
    expected = set(sinks)
    changed = True
    while changed:
        changed = False
        for node in range(len(succ)):
            if node not in expected and succ[node] and all(s in expected for s in succ[node]):
                expected.add(node)
                changed = True
    preds = predecessors(range(len(succ)), succ, len(succ))
    assert all_paths_reach(range(len(succ)), succ, preds, sinks) == expected


@settings(max_examples=300, deadline=None)
@given(graphs)
def test_solver_forward_must_analysis_gives_the_strict_dominators(succ) -> None:
    """Forward, join = intersection, each node adding itself: at a node's start, the nodes on
    every path to it from the entry, i.e. its strict dominators."""
    _, order, tree = analysed(succ)
    states = dataflow.solve(dataflow.Ordering.of(order, len(succ)), succ, {0: frozenset()},
                            lambda node, state: state | {node}, frozenset.intersection)
    assert set(states) == set(order)
    for node in order:
        assert states[node] == {a for a in order if a != node and tree.dominates(a, node)}
    fifo = dataflow.solve(None, succ, {0: frozenset()}, lambda node, state: state | {node}, frozenset.intersection)
    assert fifo == states  # a monotone problem: the same fixed point in first-in, first-out order


@settings(max_examples=300, deadline=None)
@given(graphs, st.integers(0, 11))
def test_solver_backward_may_analysis_gives_the_nodes_on_some_path(succ, target) -> None:
    """Backward from `target` (predecessors as edges, postorder of the reversed graph's walk),
    join = union: at a node, the nodes some path from it (one step or more) to the target passes."""
    target = target % len(succ)
    preds = [[u for u in range(len(succ)) for v in succ[u] if v == n] for n in range(len(succ))]
    ordering = dataflow.Ordering.of(depth_first(target, preds).reverse_postorder, len(succ))
    states = dataflow.solve(ordering, preds, {target: frozenset()},
                            lambda node, state: state | {node}, frozenset.union)
    for node in range(len(succ)):
        after = set().union(*(reached(succ, s) for s in succ[node]))  # reached in one step or more
        expected = {m for m in after if target in reached(succ, m)}
        if node == target or target in after:
            assert states[node] == expected, node
        else:
            assert node not in states


def test_solver_refines_along_an_edge() -> None:
    """`edge` changes what one edge carries: here only the left arm of node 0's branch learns 'x'."""
    succ = [[1, 2], [3], [3], []]
    states = dataflow.solve(dataflow.Ordering.of([0, 1, 2, 3], 4), succ, {0: frozenset()},
                            lambda node, state: state,
                            frozenset.intersection,
                            edge=lambda state, u, v: state | {"x"} if (u, v) == (0, 1) else state)
    assert states == {0: frozenset(), 1: frozenset({"x"}), 2: frozenset(), 3: frozenset()}


def test_the_block_index_keeps_the_routine_inside() -> None:
    """Blocks are numbered in routine order, and a jump to another routine's block is not an edge
    of this routine's graph; a branch whose arms are the same block gives that edge twice."""
    blocks = [ir.Block("a", [], ir.Branch(ir.Truth(ir.Var("c")), "b", "elsewhere")),
              ir.Block("b", [], ir.Branch(ir.Truth(ir.Var("c")), "a", "a")), ir.Block("c", [], ir.Return())]
    index = BlockIndex.of_routine(ir.Routine("main", ir.RoutineKind.MAIN, blocks))
    assert index.labels == ["a", "b", "c"] and index.number == {"a": 0, "b": 1, "c": 2}
    assert index.succ == [[1], [0, 0], []]


def test_a_deep_chain_needs_no_recursion() -> None:
    """20,000 nodes in a row with a loop around them: every walk uses explicit stacks."""
    n = 20000
    succ = [[i + 1] for i in range(n - 1)] + [[0]]
    walk, order, tree = analysed(succ)
    assert order == list(range(n)) and tree.dominates(0, n - 1)
    assert [loop.header for loop in loops.loop_forest(walk, succ)] == [0]
