"""Dominators: which nodes every path from the entry passes through.

The structurer places an IF's end at a branch's merge child in the dominator tree and finds loops
by their back edges (an edge to a node that dominates its source); reducibility is tested with it.
"""

from __future__ import annotations

from typing import Hashable, Mapping, Sequence, TypeVar

N = TypeVar("N", bound=Hashable)


def immediate_dominators(order: Sequence[N], preds: Mapping[N, Sequence[N]]) -> dict[N, N]:
    """Node -> its immediate dominator (the entry, `order[0]`, maps to itself), for the nodes of
    `order`, a reverse postorder of the nodes reachable from the entry.

    Cooper, Harvey and Kennedy, "A Simple, Fast Dominance Algorithm" (2001): iterate over the
    reverse postorder, intersecting the dominator-tree paths of the processed predecessors by
    walking up by postorder rank. Simpler than Lengauer-Tarjan and as fast for graphs of programs
    (two or three passes); predecessors outside `order` (unreachable) are ignored."""
    if not order:
        return {}
    entry = order[0]
    index = {node: i for i, node in enumerate(order)}
    idom: dict[N, N] = {entry: entry}
    changed = True
    while changed:
        changed = False
        for node in order[1:]:
            new = None
            for p in preds.get(node, ()):
                if p not in idom:
                    continue
                if new is None:
                    new = p
                    continue
                a, b = p, new
                while a != b:
                    while index[a] > index[b]:
                        a = idom[a]
                    while index[b] > index[a]:
                        b = idom[b]
                new = a
            if new is not None and idom.get(node) != new:
                idom[node] = new
                changed = True
    return idom


class DominatorTree:
    """The dominator tree of the nodes of `order` (a reverse postorder from the entry): each
    node's children, in `order`, and pre/post numbers that answer `dominates` in constant time
    (walking up the tree per question would make long programs quadratic)."""

    def __init__(self, order: Sequence[N], preds: Mapping[N, Sequence[N]]):
        self.idom = immediate_dominators(order, preds)
        self.children: dict[N, list[N]] = {node: [] for node in order}
        for node in order:
            parent = self.idom.get(node)
            if parent is not None and parent != node:
                self.children[parent].append(node)
        self.pre: dict[N, int] = {}
        self.post: dict[N, int] = {}
        if order:
            self._number(order[0])

    def _number(self, root: N) -> None:
        counter = 0
        self.pre[root] = counter
        stack = [(root, iter(self.children.get(root, ())))]
        while stack:
            node, it = stack[-1]
            child = next(it, None)
            if child is None:
                stack.pop()
                counter += 1
                self.post[node] = counter
            else:
                counter += 1
                self.pre[child] = counter
                stack.append((child, iter(self.children[child])))

    def dominates(self, a: N, b: N) -> bool:
        """a dominates b (every node dominates itself); False for a node not reached."""
        pre = self.pre
        if a not in pre or b not in pre:
            return False
        return pre[a] <= pre[b] and self.post[b] <= self.post[a]
