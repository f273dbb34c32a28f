"""Pass 4: ABS or INC before each move whose mode is not the one in force, and nowhere else.

In the IR every move is absolute or relative; Arcus has only the mode selected by the last ABS or
INC (L1775, L2288). The pass runs on the structured routines, the program exactly as it will be
written, so that reading the output back finds every move in the mode it was written for. The
state at a point is the set of modes that may be in force ({ABS}, {INC} or both); a move leaves
its own mode in force, since it gets a switch whenever another may be in force before it.

It is interprocedural like the frontend's analysis (compiler/arcus/modes.py): the main program
starts in the profile's `boot_move_mode` (or in either mode with `[arcus]
write_initial_move_mode = true`, spec 7.3); a subroutine starts in the modes of its GOSUBs (one
never called starts like the main program); after a GOSUB the modes are those the subroutine
ends in (unchanged when it moves nothing). A routine that may start in either mode gets the
switch of its first move at its very start, before any loop, so that one switch serves it all.
"""

from __future__ import annotations

from dataclasses import replace

from mcc.backends.arcus.target import DIALECT
from mcc.backends.structure import EndNode, IfNode, Simple, WhileNode
from mcc.compiler import ir
from mcc.compiler.profiles import Profile

ABS, INC = "ABS", "INC"
BOTH = frozenset({ABS, INC})
NONE: frozenset[str] = frozenset()
NEED = {ir.MoveMode.ABSOLUTE: ABS, ir.MoveMode.RELATIVE: INC}
SELECTED = {ABS: frozenset({ABS}), INC: frozenset({INC})}  # the state after a move in that mode

State = frozenset[str]
MAIN = "<main>"  # the main program's body (with any setup lines before it); no GOSUB names it


def boot_state(profile: Profile, stated: str = "") -> State:
    """The modes the written program may start in: the profile's power-up mode, or either when the
    profile wants programs that do not rely on it (`write_initial_move_mode = true`) or the source
    states its mode before its first move (`Module.modes_stated`: an explicit leading ABS is kept,
    since a host or an earlier run may have left INC in force, L1569)."""
    if stated or profile.get("arcus.write_initial_move_mode", False):
        return BOTH
    boot = str(profile.get("arcus.boot_move_mode", "abs")).upper()
    return frozenset({boot}) if boot in (ABS, INC) else BOTH


def need(node) -> str | None:
    op = getattr(node, "op", None)
    return NEED.get(op.mode) if isinstance(op, ir.Move) else None


def walk(nodes: list):
    """Every Simple node of a structured body, depth first in written order."""
    for node in nodes:
        if isinstance(node, Simple):
            yield node
        elif isinstance(node, IfNode):
            for _, body in node.arms:
                yield from walk(body)
            yield from walk(node.orelse)
        elif isinstance(node, WhileNode):
            yield from walk(node.body)


class Modes:
    """The fixpoint over the structured routines, then the switches written into them."""

    def __init__(self, routines: dict[str, list], profile: Profile, stated: str = ""):
        self.routines = routines  # routine name -> structured body ("<main>" first)
        self.boot = boot_state(profile)
        self.stated = stated
        calls = {name: {n.op.routine for n in walk(body) if isinstance(n.op, ir.Call)}
                 for name, body in routines.items()}
        called = set().union(*calls.values()) if calls else set()
        self.fixed = {name for name in routines if name == MAIN or name not in called}
        self.moving = {name for name, body in routines.items() if any(need(n) for n in walk(body))}
        changed = True
        while changed:  # a routine that calls a moving routine may change the mode too
            changed = False
            for name, callees in calls.items():
                if name not in self.moving and callees & self.moving:
                    self.moving.add(name)
                    changed = True
        self.entry: dict[str, State] = {name: self.boot if name in self.fixed else NONE for name in routines}
        self.exit: dict[str, State | None] = {name: None for name in routines}
        self.prefix: dict[str, str] = {}

    # the analysis -------------------------------------------------------------------------------
    def start(self, name: str) -> State:
        if name in self.prefix:
            return frozenset({self.prefix[name]})
        return self.entry[name] or self.boot  # called only from code that never runs: as if uncalled

    def after(self, op: ir.Op, state: State) -> State:
        if not state:
            return state
        if isinstance(op, ir.Move) and op.mode in NEED:
            return frozenset({NEED[op.mode]})
        if isinstance(op, ir.Native) and op.dialect == DIALECT and not op.args and op.mnemonic in (ABS, INC):
            return frozenset({op.mnemonic})
        if isinstance(op, ir.Call) and op.routine in self.moving:
            returns = self.exit.get(op.routine)
            if returns is None:
                return NONE  # not solved yet: a later round knows
            return returns or BOTH  # it never ends here; the frontend may still see an end (WHILE 1=1)
        return state

    def flow(self, nodes: list, state: State, seen: dict[tuple, State], calls: dict[str, State],
             path: tuple = ()) -> State:
        """The modes after `nodes`; `seen` collects the modes before each move, `calls` at each GOSUB.
        Places are named by their path in the tree: the structurer may put one node in two places."""
        for index, node in enumerate(nodes):
            if isinstance(node, Simple):
                op = node.op
                if isinstance(op, ir.Move):  # most statements: what `need` and `after` do for a move
                    mode = NEED.get(op.mode)
                    if mode is not None:
                        where = path + (index,)
                        seen[where] = seen.get(where, NONE) | state
                        if state:
                            state = SELECTED[mode]
                    continue
                if isinstance(op, ir.Call) and state:
                    calls[op.routine] = calls.get(op.routine, NONE) | state
                state = self.after(op, state)
                continue
            where = path + (index,)
            if isinstance(node, EndNode):
                state = NONE
            elif isinstance(node, IfNode):
                out = NONE
                for arm, (_, body) in enumerate(node.arms):
                    out |= self.flow(body, state, seen, calls, where + (arm,))
                state = out | self.flow(node.orelse, state, seen, calls, where + ("else",))
            elif isinstance(node, WhileNode):
                head = state
                for _ in range(4):  # three non-empty states: the loop settles quickly
                    end = self.flow(node.body, head, seen, calls, where)
                    if end <= head:
                        break
                    head = head | end
                state = head  # the loop ends at its test
        return state

    def solve(self) -> dict[str, dict[tuple, State]]:
        for _ in range(3 * len(self.routines) + 4):
            seen: dict[str, dict[tuple, State]] = {}
            calls: dict[str, State] = {}
            changed = False
            for name, body in self.routines.items():
                out = self.flow(body, self.start(name), seen.setdefault(name, {}), calls)
                if out != self.exit[name]:
                    self.exit[name] = out
                    changed = True
            for name in self.routines:
                if name not in self.fixed and calls.get(name, NONE) != self.entry[name]:
                    self.entry[name] = calls.get(name, NONE)  # afresh: exits may narrow what follows a call
                    changed = True
            if not changed:
                return seen
        self.entry = {name: BOTH for name in self.routines}  # not settled (a guard): trust nothing
        self.exit = {name: BOTH for name in self.routines}
        self.prefix = {}
        seen = {}
        for name, body in self.routines.items():
            self.flow(body, BOTH, seen.setdefault(name, {}), {})
        return seen

    # writing the switches -------------------------------------------------------------------------
    def write(self) -> None:
        seen = self.solve()
        for name, body in self.routines.items():  # one switch at the start of a routine entered in either mode
            if self.start(name) == BOTH:
                first = next((need(n) for n in walk(body) if need(n)), None)
                if first is not None:
                    self.prefix[name] = first
        if self.stated and self.boot != BOTH:
            # The source states its modes: the switches go where the program may start in either
            # mode, but the prefixes above are the profile's, so that the output, which states its
            # modes too, compiles to itself; a program that opens with its switch keeps it there.
            self.boot = BOTH
            self.entry = {name: BOTH if name in self.fixed else NONE for name in self.routines}
            self.exit = {name: None for name in self.routines}
            first = next((need(n) for n in walk(self.routines[MAIN]) if need(n)), None)
            if self.stated == "start" and first is not None:
                self.prefix[MAIN] = first
        if self.prefix or self.stated:
            seen = self.solve()
        for name, body in self.routines.items():
            insert(body, seen.get(name, {}))
            if name in self.prefix:
                body.insert(0, Simple(ir.Native(DIALECT, self.prefix[name])))


def insert(nodes: list, seen: dict[tuple, State], path: tuple = ()) -> None:
    """ABS/INC before each move that may find another mode in force. A node the structurer put in
    two places is one object: compound nodes are copied, never changed in place."""
    out: list = []
    for index, node in enumerate(nodes):
        where = path + (index,)
        mode = need(node)
        if mode is not None and seen.get(where, NONE) != {mode}:
            out.append(Simple(ir.Native(DIALECT, mode, span=node.op.span)))
        elif isinstance(node, IfNode):
            node = replace(node, arms=[(cond, _inserted(body, seen, where + (arm,)))
                                       for arm, (cond, body) in enumerate(node.arms)],
                           orelse=_inserted(node.orelse, seen, where + ("else",)))
        elif isinstance(node, WhileNode):
            node = replace(node, body=_inserted(node.body, seen, where))
        out.append(node)
    nodes[:] = out


def _inserted(nodes: list, seen: dict[tuple, State], path: tuple) -> list:
    copy = list(nodes)
    insert(copy, seen, path)
    return copy


def write_switches(main: list, subs: list[tuple[ir.Routine, list, object]], profile: Profile,
                   stated: str = "", programs: list[tuple[ir.Routine, list, object]] = ()) -> None:
    """The whole pass: the main program's body and each subroutine's, in place. `stated`: the
    source states its mode before its first move (`Module.modes_stated`), so the output does too.
    `programs` run beside the main program (PRG n): either mode may be in force when they start."""
    routines = {MAIN: main}
    for routine, body, _ in (*subs, *programs):
        routines[routine.name] = body
    modes = Modes(routines, profile, stated)
    for routine, _, _ in programs:
        modes.entry[routine.name] = BOTH
    modes.write()
