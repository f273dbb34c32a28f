"""The control-flow helpers of compiler/lint/flow.py against their definitions, on random graphs.

The helpers are written for linear time (one pass, explicit stacks); these tests compare them with
the slow, obvious definitions they replace, and check that deep graphs need no Python recursion.
"""

from __future__ import annotations

from hypothesis import given, settings
from hypothesis import strategies as st

from mcc.compiler import ir
from mcc.compiler.lint import flow


def routine_of(edges: list[list[int]]) -> ir.Routine:
    """Block i jumps to edges[i] (none: the end; one: a jump; two: a branch)."""
    blocks = []
    for i, targets in enumerate(edges):
        names = [f"b{t}" for t in targets]
        if not names:
            term = ir.Return()
        elif len(names) == 1:
            term = ir.Jump(names[0])
        else:
            term = ir.Branch(ir.Truth(ir.Var("c")), names[0], names[1])
        blocks.append(ir.Block(f"b{i}", [], term))
    return ir.Routine("main", ir.RoutineKind.MAIN, blocks)


graphs = st.integers(1, 12).flatmap(
    lambda n: st.lists(st.lists(st.integers(0, n - 1), max_size=2), min_size=n, max_size=n))


def reaches(routine: ir.Routine, start: str) -> set[str]:
    seen: set[str] = set()
    work = [start]
    while work:
        label = work.pop()
        for succ in ir.successors(routine.block(label).terminator):
            if succ not in seen:
                seen.add(succ)
                work.append(succ)
    return seen


@settings(max_examples=200, deadline=None)
@given(graphs)
def test_in_loops_is_every_block_that_reaches_itself(edges) -> None:
    routine = routine_of(edges)
    expected = {b.label for b in routine.blocks if b.label in reaches(routine, b.label)}
    assert flow.in_loops(routine) == expected


@settings(max_examples=200, deadline=None)
@given(graphs)
def test_reachable_is_the_closure_from_the_entry(edges) -> None:
    routine = routine_of(edges)
    expected = reaches(routine, "b0") | {"b0"}
    assert {b.label for b in flow.reachable(routine)} == expected


@settings(max_examples=200, deadline=None)
@given(graphs)
def test_every_loop_body_cycles_through_its_header(edges) -> None:
    routine = routine_of(edges)
    live = {b.label for b in flow.reachable(routine)}
    for header, body in flow.natural_loops(routine):
        labels = {b.label for b in body}
        assert header.label in labels and labels <= live
        for block in body:  # each block of the body gets back to the header
            assert header.label in reaches(routine, block.label)


def nested_whiles(depth: int) -> ir.Routine:
    """WHILE inside WHILE, `depth` deep. Block i < depth is the test of loop i (into loop i+1, or
    out to block depth+1+i); block depth is the innermost body; block depth+1+i follows loop i and
    jumps back to the test of loop i-1 (the program ends after loop 0)."""
    edges = [[i + 1, depth + 1 + i] for i in range(depth)]
    edges.append([depth - 1])
    edges += [[i - 1] if i else [] for i in range(depth)]
    return routine_of(edges)


def test_a_deep_nest_of_loops_needs_no_recursion() -> None:
    routine = nested_whiles(3000)  # far past Python's recursion limit
    forest = flow.loop_forest(routine)
    assert len(forest) == 3000
    assert sum(len(loop.inner) for loop in forest) == 2999  # each loop but the outermost is inside one
    assert len(flow.in_loops(routine)) >= 3000
    states = flow.forward(routine, frozenset(), lambda s, item: s, frozenset.union)
    assert len(states) == len(routine.blocks)


def test_components_of_a_long_call_chain() -> None:
    chain = {f"r{i}": [f"r{i + 1}"] for i in range(5000)}
    chain["r5000"] = ["r0"]  # one big cycle
    found = flow.components(chain, lambda name: chain.get(name, ()))
    assert len(found) == 1 and len(found[0]) == 5001


def test_summaries_of_a_deep_call_chain_need_no_recursion() -> None:
    routines = [ir.Routine(f"r{i}", ir.RoutineKind.SUBROUTINE,
                           [ir.Block(f"r{i}.0", [ir.Call(f"r{i + 1}")] if i < 3000 else
                                     [ir.Assign(ir.Var("v"), ir.Const(1))], ir.Return())])
                for i in range(3001)]
    module = ir.Module("arcus", "test", routines=routines)
    facts = flow.MustFacts(module, lambda item: ("v",) if isinstance(item, ir.Assign) else ())
    assert facts.summary("r0") == frozenset({"v"})  # what the innermost call does reaches the outermost
