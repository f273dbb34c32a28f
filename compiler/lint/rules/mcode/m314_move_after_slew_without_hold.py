r"""# M314 move-after-slew-without-hold

A move follows `SL` without an `H` in between.

- kind: lint
- default severity: warning
- dialects: mcode
- fix available: no
- manual: L5396-L5406

## What it means

`SL` runs the axis at a velocity until the next `SL`. "If 'SL 0' is issued after a MA/MR, motion
has to come to a stop before issuing another motion command" (L5404): a move started while the
axis is still slewing or still decelerating from `SL 0` is refused or runs from an unknown
position. Put `H` between the `SL` and the next move.

## Bad

```
PG 1
LB G1
  SL 20000
  H 500
  SL 0
  MA 0
  H
  E
PG
```

## Good

```
PG 1
LB G1
  SL 20000
  H 500
  SL 0
  H
  MA 0
  H
  E
PG
```
"""

from __future__ import annotations

from mcc.compiler import ir
from mcc.compiler.lint import flow
from mcc.compiler.lint.rules import Context, rule
from mcc.compiler.lint.rules.mcode.helpers import line_of


# Flags a program polls to wait for the end of a move instead of H (L4207, L4427).
MOTION_FLAGS = ("moving", "moving_to_position")  # MV, MP


def reads_any(item, meanings: tuple[str, ...]) -> bool:
    """Whether an operation or terminator reads one of the named device readings."""
    found = flow.op_reads(item) if not isinstance(item, (ir.Branch, ir.Jump, ir.Return, ir.End, ir.FallOff)) \
        else flow.term_reads(item)
    return any(isinstance(n, ir.Status) and n.meaning in meanings for n in found)


class Motion:
    """Data flow of 'a move may still be running': the state is the set of lines of such moves.

    A call is summarised by running the callee with an empty state (what it leaves running) and
    whether it waits on every path (then it clears the caller's moves).
    """

    def __init__(self, module: ir.Module, starts: tuple[type, ...], clears_on_flag: bool = True):
        self.module = module
        self.starts = starts
        self.clears_on_flag = clears_on_flag
        self.summaries: dict[str, tuple[bool, frozenset]] = {}
        self.routines = flow.routine_index(module)
        self.calls = flow.call_graph(module)

    def transfer(self, state: frozenset, item) -> frozenset:
        if isinstance(item, self.starts):
            return state | {line_of(item.span)}
        if isinstance(item, ir.WaitMotion):
            return frozenset()
        if isinstance(item, ir.Call):
            clears, leaves = self.summary(item.routine)
            return (frozenset() if clears else state) | leaves
        if self.clears_on_flag and item is not None and reads_any(item, MOTION_FLAGS):
            return frozenset()
        return state

    def summary(self, name: str) -> tuple[bool, frozenset]:
        # a recursive call assumes nothing; callees are summarised first, without Python recursion
        return flow.summarize(name, self.summaries, (False, frozenset()), self.calls, self.compute)

    def compute(self, name: str) -> tuple[bool, frozenset]:
        routine = self.routines.get(name)
        if routine is None:
            return (False, frozenset())
        marker = frozenset({-1})  # a pseudo move standing for "whatever ran before the call"
        states = flow.forward(routine, marker, self.transfer, frozenset.union)
        exits = [b for b in routine.blocks if isinstance(b.terminator, ir.Return) and b.label in states]
        at_exit = frozenset()
        for block in exits:
            state = states[block.label]
            for op in block.ops:
                state = self.transfer(state, op)
            at_exit |= state
        return (-1 not in at_exit, frozenset(at_exit - marker))

    def run(self, routine: ir.Routine):
        """(item, state before it) for every operation and terminator reachable in the routine."""
        states = flow.forward(routine, frozenset(), self.transfer, frozenset.union)
        for block in routine.blocks:
            if block.label in states:
                yield from flow.replay(block, states[block.label], self.transfer)


@rule
def move_after_slew_without_hold(ctx: Context) -> None:
    if not any(isinstance(op, ir.Slew) for _, _, op in flow.ops(ctx.module)):
        return  # no SL: nothing may still be running (and no walk of every routine)
    motion = Motion(ctx.module, (ir.Slew,))

    def transfer(state: frozenset, item) -> frozenset:
        return frozenset() if isinstance(item, (ir.Move, ir.Home)) else motion.transfer(state, item)

    for routine in ctx.module.routines:
        if routine.kind is ir.RoutineKind.IMMEDIATE:
            continue  # H is program only: outside a program there is nothing to add
        states = flow.forward(routine, frozenset(), transfer, frozenset.union)
        for block in routine.blocks:
            if block.label not in states:
                continue
            for item, state in flow.replay(block, states[block.label], transfer):
                if state and isinstance(item, (ir.Move, ir.Home)):
                    lines = ", ".join(str(n) for n in sorted(state) if n > 0)
                    ctx.report(item.span, f"this move starts while the SL at line {lines} may still be running: "
                                          "add `H` before it so the axis has stopped (L5404)")
