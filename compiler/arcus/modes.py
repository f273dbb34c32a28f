"""Which move mode (ABS or INC) is in force at each move: a forward data-flow pass over the IR.

Arcus move targets are absolute or incremental according to the last ABS or INC executed (L1775,
L2288). The frontend records a move as ABSOLUTE or RELATIVE only where the mode is the same on
every path to it, MODAL otherwise; the backend runs the same analysis over the program it writes
and inserts ABS/INC where a move needs a mode that is not in force. It works on the IR only
(ABS and INC are `Native('arcus', 'ABS'|'INC')`), so both can use it.

The state entering the main program is the profile's `arcus.boot_move_mode` ("unknown" by
default: a host or an earlier run may have left INC); a subroutine starts in an unknown mode (the
host can call it with GS, L823); a call makes the mode unknown when the callee (or anything it
calls) contains ABS or INC.
"""

from __future__ import annotations

from typing import Callable

from mcc.compiler import ir
from mcc.compiler.profiles import Profile

ABS, INC, UNKNOWN = "ABS", "INC", "?"
SWITCHES = {"ABS": ABS, "INC": INC}
MODE_OF = {ABS: ir.MoveMode.ABSOLUTE, INC: ir.MoveMode.RELATIVE}
STATE_OF = {ir.MoveMode.ABSOLUTE: ABS, ir.MoveMode.RELATIVE: INC}


def switch(op: ir.Op) -> str | None:
    """The mode an operation selects (ABS / INC), or None."""
    if isinstance(op, ir.Native) and op.dialect == "arcus" and not op.args:
        return SWITCHES.get(op.mnemonic.upper())
    return None


def changers(module: ir.Module, explicit_moves: bool = False) -> set[str]:
    """Routines that may change the mode, directly or through the routines they call.

    With `explicit_moves` (the backend's view) a routine with an ABSOLUTE or RELATIVE move counts
    too: the backend may write ABS or INC before that move."""
    direct: set[str] = set()
    calls: dict[str, set[str]] = {}
    for routine in module.routines:
        for block in routine.blocks:
            for op in block.ops:
                if switch(op) is not None or (explicit_moves and isinstance(op, ir.Move)
                                              and op.mode is not ir.MoveMode.MODAL):
                    direct.add(routine.name)
                elif isinstance(op, ir.Call):
                    calls.setdefault(routine.name, set()).add(op.routine)
    result = set(direct)
    changed = True
    while changed:
        changed = False
        for name, callees in calls.items():
            if name not in result and callees & result:
                result.add(name)
                changed = True
    return result


def entry_state(routine: ir.Routine, profile: Profile | None) -> str:
    if routine.kind is ir.RoutineKind.MAIN and profile is not None:
        boot = str(profile.get("arcus.boot_move_mode", "unknown")).upper()
        return boot if boot in (ABS, INC) else UNKNOWN
    return UNKNOWN


def transfer(block: ir.Block, state: str, moved: set[str],
             visit: Callable[[ir.Op, str], None] | None = None) -> str:
    for op in block.ops:
        if visit is not None:
            visit(op, state)
        selected = switch(op)
        if selected is not None:
            state = selected
        elif isinstance(op, ir.Call) and op.routine in moved:
            state = UNKNOWN
    return state


def meet(a: str | None, b: str) -> str:
    return b if a is None or a == b else UNKNOWN


def analyse(routine: ir.Routine, entry: str, moved: set[str]) -> dict[str, str]:
    """The mode entering each reachable block."""
    if not routine.blocks:
        return {}
    blocks = {b.label: b for b in routine.blocks}
    states: dict[str, str] = {routine.blocks[0].label: entry}
    work = [routine.blocks[0].label]
    while work:
        label = work.pop()
        block = blocks[label]
        out = transfer(block, states[label], moved)
        for succ in ir.successors(block.terminator):
            if succ not in blocks:
                continue
            new = meet(states.get(succ), out)
            if states.get(succ) != new:
                states[succ] = new
                work.append(succ)
    return states


def assign_move_modes(module: ir.Module, profile: Profile | None) -> None:
    """Give each MODAL move of an Arcus module the mode in force, where it is known."""
    moved = changers(module)
    for routine in module.routines:
        states = analyse(routine, entry_state(routine, profile), moved)

        def visit(op: ir.Op, state: str) -> None:
            if isinstance(op, ir.Move) and op.mode is ir.MoveMode.MODAL and state in MODE_OF:
                op.mode = MODE_OF[state]

        for block in routine.blocks:
            if block.label in states:
                transfer(block, states[block.label], moved, visit)
