"""Loops: back edges, natural loops, reducibility and the loop-nesting forest.

A loop is found from its header, the node an edge jumps back to. Two definitions are in use and
both are here: the natural loop of a back edge u -> h (h dominates u; the structurer, which works
on reducible graphs only), and Havlak's loop-nesting forest (lint, which must also say something
about an irreducible graph: a header there is the target of a retreating edge of the depth-first
walk). On a reducible graph the two find the same loops. Nodes are numbers 0..n-1
(compiler/cfg/graph.py, `BlockIndex`).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Sequence

from mcc.compiler.cfg.dominators import DominatorTree
from mcc.compiler.cfg.graph import DepthFirst, Succ


def back_edges(order: Sequence[int], succ: Succ, tree: DominatorTree) -> set[tuple[int, int]]:
    """The edges u -> v of the nodes of `order` whose target dominates their source."""
    dominates = tree.dominates
    return {(u, v) for u in order for v in succ[u] if dominates(v, u)}


def latches(order: Sequence[int], succ: Succ, back: set[tuple[int, int]]) -> dict[int, list[int]]:
    """Each loop header's back-edge sources, in `order`, found in one pass over the edges (scanning
    every back edge for each header was quadratic in the number of loops, issue 26)."""
    found: dict[int, list[int]] = {}
    for u in order:
        for v in succ[u]:
            if (u, v) in back:
                found.setdefault(v, []).append(u)
    return found


def natural_loop(header: int, sources: Sequence[int], preds: Succ) -> set[int]:
    """The header and every node that reaches one of `sources` (the header's latches) without
    passing through the header: the body of the natural loop."""
    body = {header}
    work = list(sources)
    while work:
        node = work.pop()
        if node in body:
            continue
        body.add(node)
        work.extend(preds[node])
    return body


def reducible(walk: DepthFirst, tree: DominatorTree) -> bool:
    """Every retreating edge of the depth-first walk is a back edge (its target dominates its
    source): no loop is entered at two places."""
    return all(tree.dominates(target, source) for source, target in walk.retreating)


@dataclass
class Loop:
    """One loop of the loop-nesting forest: its header, the nodes directly inside it (not in an
    inner loop; the header first, then in preorder) and the loops nested in it."""

    header: int
    nodes: list[int] = field(default_factory=list)
    inner: list["Loop"] = field(default_factory=list)


def loop_forest(walk: DepthFirst, succ: Succ) -> list[Loop]:
    """The loops of the graph `walk` was taken of, innermost first: a header is a node a node of its
    depth-first subtree jumps back to; its body is every node of that subtree that reaches such a
    jump without passing through the header.

    Havlak's algorithm ("Nesting of reducible and irreducible loops", 1997, without the
    irreducible-entry bookkeeping): headers are taken in reverse preorder, and the body walk jumps
    over an inner loop already found (union-find), so each node is visited about once and a nest
    of 500 loops costs what 500 loops in a row cost. Edges into a loop from outside the header's
    depth-first subtree (an irreducible entry) are not followed."""
    order, number, last = walk.preorder, walk.number, walk.last
    preds: list[list[int]] = [[] for _ in succ]
    for node in order:
        for nxt in succ[node]:
            preds[nxt].append(node)
    parent = list(range(len(succ)))  # union-find: a node -> the header that absorbed it

    def find(node: int) -> int:
        root = node
        while parent[root] != root:
            root = parent[root]
        while parent[node] != root:
            parent[node], node = root, parent[node]
        return root

    loops: dict[int, Loop] = {}
    found: list[Loop] = []
    for header in reversed(order):
        low, high = number[header], last[header]
        back = [p for p in preds[header] if low <= number[p] <= high]
        if not back:
            continue
        loop = Loop(header, [header])
        members: set[int] = set()
        work = [find(p) for p in back]
        while work:
            node = work.pop()
            if node == header or node in members:
                continue
            members.add(node)
            for pred in preds[node]:
                if low <= number[pred] <= high:
                    work.append(find(pred))
        for node in sorted(members, key=number.__getitem__):
            parent[node] = header
            if node in loops:
                loop.inner.append(loops[node])
            else:
                loop.nodes.append(node)
        loops[header] = loop
        found.append(loop)
    return found
