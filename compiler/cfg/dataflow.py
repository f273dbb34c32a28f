"""One worklist solver for data-flow problems over a graph, forward or backward.

Every analysis that asks "what holds at the start of each block, on every path (or on some path)"
is the same loop: start from the entry's state, push each block's result along its edges, merge
(`join`) where paths meet, and revisit a block whenever what reaches it changed, until nothing does.
Only the state, the transfer and the join differ, so they are the parameters and the loop is here.

The worklist is a priority queue on the rank of each node in an order the caller chooses: for a
forward problem a reverse postorder (a block waits until its forward predecessors are done, so a
loop nest settles in a few passes instead of one pass per queued change); for a backward problem,
pass the predecessors as `succ` and a reverse postorder of the reversed graph (or the postorder of
the forward one). The result is the least fixed point the transfer and join reach from the starts;
for a monotone framework over a finite lattice it does not depend on the order, only the number of
visits does. Without an ordering the worklist is first in, first out, in the order nodes are
reached. That needs no depth-first walk first, which pays for a problem solved again and again
over a long routine whose lattice is a plain union (compiler/arcus/modes.py: the move modes, in
every round of an interprocedural fixpoint); and it is the order of an analysis whose join is not
a lattice's (compiler/in_force.py drops a setting for every axis where one axis's own was lost), so
that its fixed point, which may depend on the order of visits, stays what it was.
"""

from __future__ import annotations

import heapq
from collections import deque
from dataclasses import dataclass
from typing import Callable, Mapping, Sequence, TypeVar

from mcc.compiler.cfg.graph import Succ

S = TypeVar("S")


@dataclass(frozen=True)
class Ordering:
    """Nodes (numbers 0..size-1) in the order the worklist prefers them, with each node's rank in
    it (-1: not in the order)."""

    nodes: Sequence[int]
    rank: Sequence[int]

    @classmethod
    def of(cls, nodes: Sequence[int], size: int) -> "Ordering":
        rank = [-1] * size
        for i, node in enumerate(nodes):
            rank[node] = i
        return cls(nodes, rank)


def solve(ordering: Ordering | None, succ: Succ, starts: Mapping[int, S],
          transfer: Callable[[int, S], S], join: Callable[[S, S], S],
          edge: Callable[[S, int, int], S] | None = None) -> dict[int, S]:
    """The state at the start of each node reached from `starts` (node -> its initial state), to a
    fixed point.

    `transfer(node, state)` is the state after the node (the state it gets must not be changed in
    place: it is kept as the node's result); `edge(state, node, successor)` may refine it along
    one edge (the branch's condition holds on its taken edge); `join(old, new)` merges what
    reaches a node by several paths. States are compared with `!=`, so they must be values
    (frozensets, dictionaries of constants) and the lattice of finite height. Every node reached
    must be in `ordering` (None: first in, first out)."""
    states: dict[int, S] = dict(starts)
    get = states.get
    queued = set(starts)
    discard, add = queued.discard, queued.add
    if ordering is None:  # first in, first out
        fifo = deque(starts)
        put, take = fifo.append, fifo.popleft
    else:  # the lowest rank first: a node after the nodes before it in the ordering
        rank, nodes = ordering.rank, ordering.nodes
        heap = [rank[node] for node in starts]
        heapq.heapify(heap)

        def put(node: int) -> None:
            heapq.heappush(heap, rank[node])

        def take() -> int:
            return nodes[heapq.heappop(heap)]
    while queued:
        node = take()
        discard(node)
        state = transfer(node, states[node])
        for nxt in succ[node]:
            out = edge(state, node, nxt) if edge is not None else state
            old = get(nxt)
            if old is not None:
                out = join(old, out)
                if out == old:
                    continue
            states[nxt] = out
            if nxt not in queued:
                add(nxt)
                put(nxt)
    return states
