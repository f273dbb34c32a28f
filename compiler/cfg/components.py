"""Strongly connected components: the blocks that can reach themselves again (a loop's body), the
routines that call themselves through others (recursion).

Over any graph with hashable nodes (labels, routine names): the call graph is keyed by name and
small, and rules ask it by name, so this one is not numbered like the rest of the library.
"""

from __future__ import annotations

from typing import Callable, Hashable, Iterable, TypeVar

N = TypeVar("N", bound=Hashable)


def strongly_connected(nodes: Iterable[N], succ: Callable[[N], Iterable[N]]) -> list[list[N]]:
    """The strongly connected components of the graph, each after every component it reaches
    (callees before callers): Tarjan's algorithm with an explicit stack, so a long chain of blocks
    or calls needs no Python recursion. Nodes reached through `succ` from `nodes` are included."""
    number: dict[N, int] = {}
    low: dict[N, int] = {}
    stack: list[N] = []
    on_stack: set[N] = set()
    found: list[list[N]] = []
    for root in nodes:
        if root in number:
            continue
        number[root] = low[root] = len(number)
        stack.append(root)
        on_stack.add(root)
        work = [(root, iter(succ(root)))]
        while work:
            node, it = work[-1]
            for nxt in it:
                if nxt not in number:
                    number[nxt] = low[nxt] = len(number)
                    stack.append(nxt)
                    on_stack.add(nxt)
                    work.append((nxt, iter(succ(nxt))))
                    break
                if nxt in on_stack:
                    low[node] = min(low[node], number[nxt])
            else:
                work.pop()
                if work:
                    parent = work[-1][0]
                    low[parent] = min(low[parent], low[node])
                if low[node] == number[node]:
                    component = []
                    while True:
                        member = stack.pop()
                        on_stack.discard(member)
                        component.append(member)
                        if member == node:
                            break
                    found.append(component)
    return found
