"""A routine's graph: its block index (local successors), predecessors and the depth-first walk.

Every analysis starts with the same two things, the successors of each block inside the routine
and an order to visit the blocks in; they are built here once, as dictionaries keyed by label
(looking a label up in the routine's block list per edge would make every walk quadratic).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Hashable, Iterable, Mapping, Sequence, TypeVar

from mcc.compiler import ir

N = TypeVar("N", bound=Hashable)


def local_successors(routine: ir.Routine) -> dict[str, list[str]]:
    """Block label -> the labels its terminator may go to inside the routine, in the terminator's
    order (a jump to another routine's block is left out: each routine is analysed on its own).
    The first block of a label wins when two share one (a malformed routine)."""
    labels = {block.label for block in routine.blocks}
    succ: dict[str, list[str]] = {}
    for block in routine.blocks:
        if block.label not in succ:
            succ[block.label] = [label for label in ir.successors(block.terminator) if label in labels]
    return succ


def predecessors(nodes: Iterable[N], succ: Mapping[N, Sequence[N]]) -> dict[N, list[N]]:
    """Node -> the nodes among `nodes` with an edge to it, in the order of `nodes` (an edge given
    twice counts twice). Only the successors of `nodes` are read, so passing the reachable nodes
    gives the reachable predecessors."""
    nodes = list(nodes)
    preds: dict[N, list[N]] = {node: [] for node in nodes}
    for node in nodes:
        for nxt in succ.get(node, ()):
            preds.setdefault(nxt, []).append(node)
    return preds


@dataclass
class DepthFirst:
    """One depth-first walk from an entry, successors taken in order.

    `preorder` is the discovery order and `number` each node's place in it; `last[n]` is the
    highest preorder number in n's subtree of the walk, so m descends from n exactly when
    `number[n] <= number[m] <= last[n]` (Havlak's loop finder needs that test). `retreating` are
    the edges to a node still on the walk's stack: in a reducible graph exactly the back edges."""

    preorder: list = field(default_factory=list)
    number: dict = field(default_factory=dict)
    last: dict = field(default_factory=dict)
    postorder: list = field(default_factory=list)
    retreating: list = field(default_factory=list)

    @property
    def reverse_postorder(self) -> list:
        """Every node before its successors except along retreating edges: the order in which
        forward analyses converge fastest."""
        return self.postorder[::-1]


def depth_first(entry: N, succ: Mapping[N, Sequence[N]]) -> DepthFirst:
    """The depth-first walk of the nodes reachable from `entry` (an explicit stack: a chain of
    thousands of blocks needs no Python recursion)."""
    walk = DepthFirst()
    number, last, preorder, postorder, retreating = walk.number, walk.last, walk.preorder, walk.postorder, \
        walk.retreating
    number[entry] = 0
    preorder.append(entry)
    on_stack = {entry}
    stack = [(entry, iter(succ.get(entry, ())))]
    while stack:
        node, it = stack[-1]
        for nxt in it:
            if nxt in on_stack:
                retreating.append((node, nxt))
            if nxt not in number:
                number[nxt] = len(preorder)
                preorder.append(nxt)
                on_stack.add(nxt)
                stack.append((nxt, iter(succ.get(nxt, ()))))
                break
        else:
            stack.pop()
            on_stack.discard(node)
            last[node] = len(preorder) - 1
            postorder.append(node)
    return walk


def reverse_postorder(entry: N, succ: Mapping[N, Sequence[N]]) -> list:
    """The nodes reachable from `entry` in reverse postorder (see `DepthFirst`)."""
    return depth_first(entry, succ).reverse_postorder


def all_paths_reach(nodes: Iterable[N], succ: Mapping[N, Sequence[N]], sinks: Iterable[N]) -> set:
    """The nodes from which every path reaches one of `sinks` (the sinks included): a node is in
    when it is a sink, or it has successors and all of them are in. The least such set, so a cycle
    that no path leaves for a sink is not in it, nor a node without successors that is no sink.

    Linear: each node counts its successors not yet known to be in, and a node joins when its count
    reaches zero, reached backwards from the sinks (a fixpoint that scanned every node again until
    nothing changed took one pass per nesting level)."""
    nodes = list(nodes)
    sink_set = set(sinks)
    waiting: dict = {}
    preds: dict = {}
    for node in nodes:
        distinct = set(succ.get(node, ()))
        waiting[node] = len(distinct)
        for nxt in distinct:
            preds.setdefault(nxt, []).append(node)
    result = {node for node in nodes if node in sink_set}
    work = list(result)
    while work:
        node = work.pop()
        for pred in preds.get(node, ()):
            if pred in result:
                continue
            waiting[pred] -= 1
            if waiting[pred] == 0:
                result.add(pred)
                work.append(pred)
    return result
