"""The shared rule `position-read-while-moving`: a position (or encoder) reading of an axis while a
move on it may still run.

Each dialect that has it gives it a code, a page and its messages in a module of its own
package (`speak`); the function's docstring names the fields, options and hooks it reads.
"""

from __future__ import annotations

from mcc.compiler import ir
from mcc.compiler.lint import flow
from mcc.compiler.lint.rules import Context
from mcc.compiler.lint.rules.shared.helpers import MOTION_FLAGS, motion_axes, reads, same_axis, walk
from mcc.compiler.lint.rules.shared.voice import Voice


NAME = "position-read-while-moving"
# Readings of where an axis is (position counter, encoder).
POSITION_READINGS = ("position", "encoder")
FINITE_MOTION = (ir.Move, ir.Home, ir.Arc)  # motion that ends by itself


class Motion:
    """'A move may still be running': the state is a set of (axis, line of the move).

    `WaitMotion` on an axis ends its moves, and so does reading whether it still moves (polling a
    motion flag). A call is summarised once: the axes the callee waits for on every path to its
    return, and the moves it leaves running.
    """

    def __init__(self, module: ir.Module):
        self.routines = flow.routine_index(module)
        self.calls = flow.call_graph(module)
        self.summaries: dict[str, tuple[frozenset, frozenset]] = {}
        axes = {axis for _, _, op in flow.ops(module) for axis in motion_axes(op)}
        axes |= {op.axis for _, _, op in flow.ops(module, ir.WaitMotion)}
        self.axes = frozenset(axes)

    def transfer(self, state: frozenset, item) -> frozenset:
        if isinstance(item, FINITE_MOTION):
            return state | {(axis, item.span.line if item.span else 0) for axis in motion_axes(item)}
        if isinstance(item, ir.WaitMotion):
            return frozenset(m for m in state if not same_axis(m[0], item.axis))
        if isinstance(item, ir.Call):
            waited, leaves = self.summary(item.routine)
            if waited:
                state = frozenset(m for m in state if m[0] not in waited)
            return state | leaves
        polled = [n.axis for n in reads(item) if isinstance(n, ir.Status) and n.meaning in MOTION_FLAGS]
        if polled and state:
            return frozenset(m for m in state if not any(same_axis(m[0], axis) for axis in polled))
        return state

    def summary(self, name: str) -> tuple[frozenset, frozenset]:
        # a recursive call assumes nothing; callees are summarised first, without Python recursion
        return flow.summarize(name, self.summaries, (frozenset(), frozenset()), self.calls, self.compute)

    def compute(self, name: str) -> tuple[frozenset, frozenset]:
        routine = self.routines.get(name)
        if routine is None:
            return (frozenset(), frozenset())
        marker = frozenset((axis, -1) for axis in self.axes)  # "whatever ran before the call"
        states = flow.forward(routine, marker, self.transfer, frozenset.union)
        at_exit: frozenset = frozenset()
        for block in routine.blocks:
            if block.label in states and isinstance(block.terminator, ir.Return):
                state = states[block.label]
                for op in block.ops:
                    state = self.transfer(state, op)
                at_exit |= state
        waited = frozenset(axis for axis in self.axes if (axis, -1) not in at_exit)
        return waited, frozenset(m for m in at_exit if m[1] != -1)


def reads_a_position(module: ir.Module) -> bool:
    """Whether an operation or terminator of the module reads a position (or encoder) register:
    without one the rule has nothing to find, and skips its walk of every routine (the editor
    server runs the rules on every keystroke)."""
    for _, block in module.blocks():
        for item in (*block.ops, block.terminator):
            if any(isinstance(node, ir.Status) and node.meaning in POSITION_READINGS for node in reads(item)):
                return True
    return False


def position_read_while_moving(ctx: Context, voice: Voice) -> None:
    """Fields: reading (the dialect's word for the register read), axis, lines (every move that may
    still run, ", "), line (the last of them). Option `anchor`: "reading" points at the register,
    "operation" at the statement (one finding per statement)."""
    options = voice.options.get("position-read-while-moving", {})
    per_reading = options.get("anchor", "reading") == "reading"
    if not reads_a_position(ctx.module):  # nothing to report: no data flow over every routine
        return
    motion = Motion(ctx.module)
    for routine in ctx.module.routines:
        if routine.kind is ir.RoutineKind.IMMEDIATE and options.get("skip_immediate"):
            continue
        states = flow.forward(routine, frozenset(), motion.transfer, frozenset.union)
        for item, moving in walk(routine, states, motion.transfer):
            if not moving or item is None:
                continue
            found = []
            for node in reads(item):
                if isinstance(node, ir.Status) and node.meaning in POSITION_READINGS:
                    lines = sorted({line for axis, line in moving if line > 0 and same_axis(axis, node.axis)})
                    if lines:
                        found.append((node, lines))
            if not found:
                continue
            if per_reading:
                for node, lines in found:
                    ctx.report(node.span or item.span, voice.say(
                        "position-read-while-moving", reading=voice.word(node.meaning), axis=node.axis,
                        lines=", ".join(map(str, lines)), line=lines[-1]))
            else:
                node = found[0][0]
                lines = sorted({line for _, found_lines in found for line in found_lines})
                ctx.report(item.span, voice.say(
                    "position-read-while-moving", reading=voice.word(node.meaning), axis=node.axis,
                    lines=", ".join(map(str, lines)), line=lines[-1]))
