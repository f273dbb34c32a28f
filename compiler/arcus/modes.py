"""Which move mode (ABS or INC) is in force at each move: a forward data-flow pass over the IR.

Arcus move targets are absolute or incremental according to the last ABS or INC executed (L1775,
L2288). In the IR a move is ABSOLUTE or RELATIVE, so the lowering resolves the modes here and
then takes ABS and INC out of the IR (their effect is in the moves). During lowering they are
`Native('arcus', 'ABS'|'INC')`.

The state at a point is the set of modes that may be in force there. The main program starts in
the profile's `arcus.boot_move_mode` ("abs" by default, the mode the Arcus software shows at
power-up, L974; "unknown" allows both). The pass is interprocedural: a subroutine starts in the
modes of all its GOSUBs (one that no GOSUB calls starts like the main program, as a host GS would
run it), and after a GOSUB the modes are the ones the subroutine returns in (unchanged when it
never switches). A move where both modes are possible cannot be written as one IR move: it is
reported (A128) with what to add.
"""

from __future__ import annotations

from mcc.compiler import ir
from mcc.compiler.cfg import dataflow
from mcc.compiler.cfg.graph import BlockIndex
from mcc.compiler.diagnostics import Diagnostics
from mcc.compiler.profiles import Profile

ABS, INC = "ABS", "INC"
BOTH = frozenset({ABS, INC})
NONE: frozenset[str] = frozenset()
SWITCHES = {"ABS": ABS, "INC": INC}
MODE_OF = {ABS: ir.MoveMode.ABSOLUTE, INC: ir.MoveMode.RELATIVE}

State = frozenset[str]


def switch(op: ir.Op) -> str | None:
    """The mode an operation selects (ABS / INC), or None."""
    if isinstance(op, ir.Native) and op.dialect == "arcus" and not op.args:
        return SWITCHES.get(op.mnemonic.upper())
    return None


def boot_state(profile: Profile | None) -> State:
    boot = str(profile.get("arcus.boot_move_mode", "abs") if profile is not None else "abs").upper()
    return frozenset({boot}) if boot in (ABS, INC) else BOTH


def changers(module: ir.Module) -> set[str]:
    """Routines that may switch the mode, directly or through the routines they call."""
    return _Program(module).changing


def relevant_ops(block: ir.Block) -> list[ir.Op]:
    """The operations of `block` that `_Flow.after` does not pass through unchanged (ABS, INC and
    calls): the fixpoint walks each block several times, and most operations are neither."""
    return [op for op in block.ops if isinstance(op, ir.Call) or switch(op) is not None]


class _Plan:
    """One routine's blocks as positions, for the walks of `_Flow.routine` (each routine is walked
    in every round of both fixpoints of `resolve`): per block, the operations that matter and the
    positions of its successors inside the routine (the analysis library's block index); the blocks
    that call or return. Walking lists by position instead of dictionaries by label, with the
    operations that matter found once,
    made the pass grow with the program as the others do (it had grown 7x from 8,000 to 32,000
    lines, issue 26)."""

    def __init__(self, routine: ir.Routine):
        self.routine = routine
        self.relevant = [relevant_ops(block) for block in routine.blocks]
        self.successors = BlockIndex.of_routine(routine).succ
        # the blocks the final walk over the solved states looks at, in order: those that call a
        # routine (the states at the calls) and those that return (True: the state they return in)
        self.finishing = [(index, isinstance(block.terminator, (ir.Return, ir.FallOff)))
                          for index, block in enumerate(routine.blocks)
                          if isinstance(block.terminator, (ir.Return, ir.FallOff))
                          or any(isinstance(op, ir.Call) for op in self.relevant[index])]


class _Program:
    """What both fixpoints of `resolve` read of a module that does not change meanwhile, found in
    one pass over its operations: each routine's plan, the routines that may switch the mode
    (directly or through the routines they call) and the routines some call names."""

    def __init__(self, module: ir.Module):
        self.plans = {routine.name: _Plan(routine) for routine in module.routines}
        direct: set[str] = set()
        calls: dict[str, set[str]] = {}
        for routine in module.routines:
            for ops in self.plan(routine).relevant:
                for op in ops:
                    if switch(op) is not None:
                        direct.add(routine.name)
                    elif isinstance(op, ir.Call):
                        calls.setdefault(routine.name, set()).add(op.routine)
        self.changing = ir.callers_of(direct, calls)
        self.called = {name for names in calls.values() for name in names}

    def plan(self, routine: ir.Routine) -> _Plan:
        found = self.plans.get(routine.name)
        if found is None or found.routine is not routine:  # two routines of one name: each its own
            found = _Plan(routine)
        return found


class _Flow:
    """The fixpoint over routines: entry and return states per routine."""

    def __init__(self, module: ir.Module, boot: State, program: _Program | None = None):
        self.module = module
        self.boot = boot
        self.program = _Program(module) if program is None else program  # shared by the flows of one module
        self.changing = self.program.changing
        self.kinds = {routine.name: routine.kind for routine in module.routines}
        called = self.program.called
        self.entry: dict[str, State] = {}
        for routine in module.routines:
            uncalled = routine.kind is not ir.RoutineKind.SUBROUTINE or routine.name not in called
            self.entry[routine.name] = boot if uncalled else NONE
        self.uncalled = {name for name, state in self.entry.items() if state}
        self.exit: dict[str, State] = {r.name: NONE for r in module.routines}
        # id(routine) -> the modes at the start of each of its blocks, by position (lists, not a
        # dictionary of every block by label: the program's longest routine sets the cost)
        self.states: dict[int, list[State]] = {}
        self.final = False  # set once the exits are known: see `after`

    def after(self, op: ir.Op, state: State, calls: dict[str, State] | None) -> State:
        if not state:
            return state  # unreachable stays unreachable
        selected = switch(op)
        if selected is not None:
            return frozenset({selected})
        if isinstance(op, ir.Call):
            if calls is not None:
                calls[op.routine] = calls.get(op.routine, NONE) | state
            if op.routine in self.changing and state:
                returned = self.exit.get(op.routine, BOTH) if op.routine in self.exit else BOTH
                # A subroutine that never returns (it ENDs the program) leaves what follows the
                # call unreachable; its moves keep the modes in force at the call, so that
                # compiling the program again writes them the same way.
                return returned or (state if self.final else NONE)
        return state

    def routine(self, routine: ir.Routine, calls: dict[str, State]) -> State:
        """Solve one routine from its entry state; the union of the states it returns in."""
        if not routine.blocks:
            return NONE
        plan = self.program.plan(routine)
        relevant = plan.relevant
        after = self.after

        def through(index: int, state: State) -> State:
            for op in relevant[index]:
                state = after(op, state, None)
            return state

        # the modes that may be in force at each block's start: a union over paths (the library's
        # solver; first in, first out: a union of sets reaches the same fixed point in any order, and
        # this one needs no depth-first walk of the routine first); a block no path reaches has
        # none, nor does any block of a routine entered in none (a subroutine whose calls are not
        # reached yet)
        entry = self.entry[routine.name]
        solved = dataflow.solve(None, plan.successors, {0: entry}, through, frozenset.union) if entry else {}
        states: list[State] = [solved.get(index, NONE) for index in range(len(relevant))]
        returns = NONE
        for index, returning in plan.finishing:
            state = states[index]
            for op in relevant[index]:
                state = self.after(op, state, calls)
            if returning:
                returns |= state
        if self.final:  # the states of the last walk are the ones kept (each round walks every routine)
            self.states[id(routine)] = states
        return returns

    def widen_entries(self, calls: dict[str, State]) -> bool:
        """Join the states at the calls of a routine into its callees' entry states; True when one grew."""
        grew = False
        for name, state in calls.items():
            if name in self.uncalled or self.kinds.get(name) is not ir.RoutineKind.SUBROUTINE:
                continue
            new = self.entry[name] | state
            if new != self.entry[name]:
                self.entry[name] = new
                grew = True
        return grew

    def solve(self) -> None:
        """Solve the routines until no entry or exit state grows. A routine's calls widen its
        callees' entry states at once (not after the whole round), so a callee solved later in
        the same round already sees them: the same least fixpoint in fewer passes over the
        program, whose longest routine dominates the cost of `mcc check` (issue 26)."""
        for _ in range(2 * len(self.module.routines) + 4):  # states only grow: a few rounds suffice
            changed = False
            for routine in self.module.routines:
                calls: dict[str, State] = {}
                returns = self.routine(routine, calls)
                if returns != self.exit[routine.name]:
                    self.exit[routine.name] = returns
                    changed = True
                changed |= self.widen_entries(calls)
            if not changed:
                break
        # Once every exit is known, a call of a subroutine that never returns (it ENDs the program)
        # leaves the unreachable code after it in the modes in force at the call, so compiling the
        # program again writes its moves the same way.
        self.final = True
        for routine in self.module.routines:
            self.routine(routine, {})


def resolve(module: ir.Module, profile: Profile | None, diags: Diagnostics) -> dict[tuple[int, int], State]:
    """Give every move of an Arcus module its mode, report moves whose mode depends on the path
    (A128), and take ABS/INC out of the IR. Returns the modes possible at each ARC/CIR."""
    flow = _Flow(module, boot_state(profile))
    flow.solve()
    module.modes_stated = _stated(module, flow)
    arcs: dict[tuple[int, int], State] = {}
    for routine in module.routines:
        solved = flow.states.get(id(routine), ())
        for position, block in enumerate(routine.blocks):
            state = solved[position] if position < len(solved) else NONE
            kept: list[ir.Op] = []
            for op in block.ops:  # only ABS, INC and calls change the state (`_Flow.after`)
                if isinstance(op, ir.Move):
                    if op.mode is ir.MoveMode.MODAL:
                        op.mode = _mode(op, state, flow.boot, diags)
                    kept.append(op)
                    continue
                if isinstance(op, ir.Arc) and op.span is not None:
                    arcs[(op.span.line, op.span.column)] = state
                selected = switch(op)
                if selected is not None:
                    state = flow.after(op, state, None)
                    continue  # ABS and INC leave the IR: each move carries its mode
                if isinstance(op, ir.Call):
                    state = flow.after(op, state, None)
                kept.append(op)
            block.ops = kept
    return arcs


def _stated(module: ir.Module, flow: _Flow) -> str:
    """Whether the program states the mode of every move itself (an ABS or INC on every path before
    it), so that none depends on the mode the controller powered up in or a host or an earlier run
    left (L1569: INC stays in force): solved again from "either mode" at the start. "start" when
    the main program's first statement is the switch; "paths" otherwise; "" when not stated."""
    if flow.boot != BOTH:
        flow = _Flow(module, BOTH, flow.program)  # the same module, unchanged: the same plans
        flow.solve()
    for routine in module.routines:
        solved = flow.states.get(id(routine), ())
        for position, block in enumerate(routine.blocks):
            state = solved[position] if position < len(solved) else NONE
            for op in block.ops:
                if isinstance(op, (ir.Move, ir.Arc)) and len(state) > 1:
                    if not isinstance(op, ir.Move) or op.mode is ir.MoveMode.MODAL:
                        return ""
                if switch(op) is not None or isinstance(op, ir.Call):
                    state = flow.after(op, state, None)
    main = next((r for r in module.routines if r.kind is ir.RoutineKind.MAIN and r.blocks), None)
    opening = main.blocks[0].ops[:1] if main is not None else []
    return "start" if opening and switch(opening[0]) is not None else "paths"


def _mode(op: ir.Move, state: State, boot: State, diags: Diagnostics) -> ir.MoveMode:
    if len(state) == 1:
        return MODE_OF[next(iter(state))]
    if not state:  # unreachable (after END, reported as A110): read it as the program starts
        return MODE_OF[next(iter(boot))] if len(boot) == 1 else ir.MoveMode.ABSOLUTE
    if op.span is not None:
        why = "the program starts in an unknown mode (profile arcus.boot_move_mode = \"unknown\")" \
            if boot == BOTH else "ABS is in force on some paths to it and INC on others"
        diags.add("A128", op.span, f"this move is absolute or incremental depending on how it is reached: {why}; "
                                   "write ABS or INC before it so that it means one thing")
    return ir.MoveMode.ABSOLUTE
