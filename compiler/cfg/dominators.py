"""Dominators: which nodes every path from the entry passes through.

The structurer places an IF's end at a branch's merge child in the dominator tree and finds loops
by their back edges (an edge to a node that dominates its source); reducibility is tested with it.
Nodes are numbers 0..size-1 (compiler/cfg/graph.py, `BlockIndex`).
"""

from __future__ import annotations

from typing import Sequence


def immediate_dominators(order: Sequence[int], preds: Sequence[Sequence[int]], size: int) -> list[int]:
    """Each node's immediate dominator (the entry, `order[0]`, its own; -1 for a node not in
    `order`), for `order` a reverse postorder of the nodes reachable from the entry.

    Cooper, Harvey and Kennedy, "A Simple, Fast Dominance Algorithm" (2001): iterate over the
    reverse postorder, intersecting the dominator-tree paths of the processed predecessors by
    walking up by reverse-postorder rank. Simpler than Lengauer-Tarjan and as fast for graphs of
    programs (two or three passes); predecessors outside `order` (unreachable) are ignored."""
    idom = [-1] * size
    if not order:
        return idom
    index = [-1] * size
    for i, node in enumerate(order):
        index[node] = i
    idom[order[0]] = order[0]
    changed = True
    while changed:
        changed = False
        for node in order[1:]:
            new = -1
            for p in preds[node]:
                if idom[p] < 0:
                    continue
                if new < 0:
                    new = p
                    continue
                a, b = p, new
                while a != b:
                    while index[a] > index[b]:
                        a = idom[a]
                    while index[b] > index[a]:
                        b = idom[b]
                new = a
            if new >= 0 and idom[node] != new:
                idom[node] = new
                changed = True
    return idom


class DominatorTree:
    """The dominator tree of the nodes of `order` (a reverse postorder from the entry, over nodes
    0..size-1): each node's children, in `order`, and pre/post numbers that answer `dominates` in
    constant time (walking up the tree per question would make long programs quadratic)."""

    def __init__(self, order: Sequence[int], preds: Sequence[Sequence[int]], size: int):
        self.idom = immediate_dominators(order, preds, size)
        self.children: list[list[int]] = [[] for _ in range(size)]
        for node in order:
            parent = self.idom[node]
            if parent != node:
                self.children[parent].append(node)
        self.pre = [-1] * size
        self.post = [-1] * size
        if order:
            self._number(order[0])

    def _number(self, root: int) -> None:
        counter = 0
        pre, post, children = self.pre, self.post, self.children
        pre[root] = counter
        stack = [(root, iter(children[root]))]
        while stack:
            node, it = stack[-1]
            child = next(it, None)
            if child is None:
                stack.pop()
                counter += 1
                post[node] = counter
            else:
                counter += 1
                pre[child] = counter
                stack.append((child, iter(children[child])))

    def dominates(self, a: int, b: int) -> bool:
        """a dominates b (every node dominates itself); False for a node not reached."""
        pre = self.pre
        if pre[a] < 0 or pre[b] < 0:
            return False
        return pre[a] <= pre[b] and self.post[b] <= self.post[a]
