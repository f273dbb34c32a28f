"""Pass 2: an ABS or INC statement before a move whose mode is not known to be the one in force.

Moves in the IR say whether they are absolute, relative, or in whatever mode the program selected
last (MODAL). Arcus has only the modal form, so the legalised CFG gets an ABS/INC wherever the
mode written so far is not the one the move needs. Two states flow through the CFG (the lattice is
`mcc.compiler.arcus.modes`): the mode the IR's own ABS/INC select (what a
MODAL move means) and the mode the written program has in force (which an inserted ABS/INC
changes). An ABSOLUTE/RELATIVE move needs the written mode to be its own; a MODAL move needs it to
be the IR's mode when that one is known, and is reported (A208) when an inserted ABS/INC may have
changed a mode the source left unknown.
"""

from __future__ import annotations

from mcc.backends.arcus.context import Context
from mcc.backends.arcus.target import DIALECT
from mcc.compiler import ir
from mcc.compiler.arcus import modes


def insert(routine: ir.Routine, ctx: Context, moved: set[str]) -> None:
    """ABS/INC before each move of `routine` whose mode is not the one in force, in place.

    `moved` names the routines a call to which leaves the mode unknown (`modes.changers`)."""
    entry = modes.entry_state(routine, ctx.profile)

    def transfer(block: ir.Block, state: tuple[str, str, bool], ops: list | None) -> tuple[str, str, bool]:
        meant, written, changed = state  # changed: an inserted switch may hide an unknown mode
        for op in block.ops:
            if isinstance(op, ir.Move):
                need = modes.STATE_OF.get(op.mode) or (meant if meant != modes.UNKNOWN else None)
                if need is not None and written != need:
                    written = need
                    changed = changed or meant != written
                    if ops is not None:
                        ops.append(ir.Native(DIALECT, need, span=op.span))
                elif need is None and changed and ops is not None:
                    uncertain(op, ctx)
            if ops is not None:
                ops.append(op)
            selected = modes.switch(op)
            if selected is not None:
                meant = written = selected
                changed = False
            elif isinstance(op, ir.Call) and op.routine in moved:
                meant = written = modes.UNKNOWN
        return meant, written, changed

    if not routine.blocks:
        return
    blocks = {b.label: b for b in routine.blocks}
    states: dict[str, tuple[str, str, bool]] = {routine.blocks[0].label: (entry, entry, False)}
    work = [routine.blocks[0].label]
    while work:
        label = work.pop()
        out = transfer(blocks[label], states[label], None)
        for succ in ir.successors(blocks[label].terminator):
            if succ not in blocks:
                continue
            old = states.get(succ)
            new = out if old is None else (modes.meet(old[0], out[0]), modes.meet(old[1], out[1]),
                                           old[2] or out[2])
            if old != new:
                states[succ] = new
                work.append(succ)
    for block in routine.blocks:
        if block.label in states:
            ops: list[ir.Op] = []
            transfer(block, states[block.label], ops)
            block.ops = ops


def uncertain(op: ir.Move, ctx: Context) -> None:
    if ctx.first_report(op):
        ctx.diags.add("A208", ctx.span_of(op),
                      "this move uses the ABS/INC mode in force, which is not known here, and an ABS or INC "
                      "written for an earlier move with an explicit mode may have changed it: make the move's "
                      "mode explicit in the source")
