r"""# A306 recursive-subroutine

A subroutine calls itself, directly or through other subroutines.

- kind: lint
- default severity: error
- dialects: arcus
- fix available: no
- manual: L2176-L2192, L2619-L2631

## What it means

`GOSUB` takes a fixed number (L2186), so a subroutine that reaches itself again calls itself on
every pass; the manual documents no call stack depth, and the standalone language has no
parameters or local variables that would let the recursion end differently (L2176-L2192,
L2619-L2631). Use a `WHILE` loop instead.

## Bad

```
GOSUB 1
END
SUB 1
V1=V1+1
IF V1<10
GOSUB 1
ENDIF
ENDSUB
```

## Good

```
GOSUB 1
END
SUB 1
WHILE V1<10
V1=V1+1
ENDWHILE
ENDSUB
```
"""

from __future__ import annotations

from mcc.compiler import ir
from mcc.compiler.lint import flow
from mcc.compiler.lint.rules import Context, rule


def calls(module: ir.Module) -> dict[str, list[ir.Call]]:
    graph: dict[str, list[ir.Call]] = {r.name: [] for r in module.routines}
    for routine, _, op in flow.ops(module, ir.Call):
        graph[routine.name].append(op)
    return graph


@rule
def recursive_subroutine(ctx: Context) -> None:
    graph = calls(ctx.module)
    targets = {name: [call.routine for call in found] for name, found in graph.items()}
    component = {}
    for members in flow.components(targets, lambda name: (t for t in targets.get(name, ()) if t in targets)):
        for name in members:
            component[name] = members[0]
    for routine in ctx.module.routines:
        for call in graph.get(routine.name, ()):
            if call.routine not in component or component[call.routine] != component.get(routine.name):
                continue
            cycle = " -> ".join(call_path(targets, call.routine, routine.name, component) + [call.routine])
            ctx.report(call.span, f"GOSUB makes {call.routine} call itself ({cycle}): subroutines cannot be "
                                  "recursive; use a WHILE loop")


def call_path(targets: dict[str, list[str]], start: str, goal: str, component: dict[str, str]) -> list[str]:
    """The shortest chain of calls from `start` to `goal` inside their cycle (breadth first)."""
    before: dict[str, str | None] = {start: None}
    queue = [start]
    for name in queue:
        if name == goal:
            break
        for callee in targets.get(name, ()):
            if callee not in before and component.get(callee) == component[start]:
                before[callee] = name
                queue.append(callee)
    path: list[str] = []
    name: str | None = goal if goal in before else start
    while name is not None:
        path.append(name)
        name = before[name]
    return path[::-1]
