"""Lint rules for the Parker/Digiplan X150 command language (X3xx); pages in codes/x150-lint.toml.

An X150 file is a stream: set-up commands sent immediately, sequences (`XDn ... XT`) stored for
later, and commands that run them. The IR gives each stretch of the stream and each sequence a
routine; settings made by the stream persist on the controller, so a sequence nothing in the file
calls starts with what the whole stream set. What a command *means* (stop, kill, goto, call) comes
from the catalog's `ir` field; only the manual's few shutdown commands are named here.
Rules that mean the same in every dialect are written once in ir_rules.py; `VOICE` gives their
codes and messages here, and hooks for what only this dialect knows.
"""

from __future__ import annotations

from functools import lru_cache

from mcc.compiler import ir
from mcc.compiler.lint import flow, ir_rules
from mcc.compiler.lint.rules import Context, rule
from mcc.compiler.x150 import catalog as xcat
from mcc.compiler.x150 import syntax as st

X150 = "x150"
SHUTDOWN = {"ST": "ST1", "OFF": "OFF"}  # L4019-L4027, L2796-L2800; re-enabled by ST0 / ON
STOPPING_IRS = ("stop", "kill")  # S, SB, LS, K (catalog `ir`)
LOOP_EXIT_IRS = ("stop", "kill", "goto", "return")
LOOP_EXIT_NAMES = ("Y", "HALT", "OFF")  # L5494, L1883, L2800


@lru_cache(maxsize=1)
def catalog() -> xcat.X150Catalog:
    return xcat.load()


def meaning(mnemonic: str) -> str:
    entry = catalog().lookup(mnemonic)
    return entry.ir if entry is not None else ""


def native(item, *names: str) -> bool:
    return isinstance(item, ir.Native) and item.dialect == X150 and item.mnemonic in names


def const(expr) -> float | None:
    return expr.value if isinstance(expr, ir.Const) else None


def uses_distance(move: ir.Move) -> bool:
    """A `G` moving by a D not known where it runs (the lowering reads the register %D<device>)."""
    return any(isinstance(value, ir.Var) and value.name.startswith("%D") for _, value in move.targets)


def is_go(item) -> bool:
    """A move: a preset Move, or a G that stays Native (continuous mode, L2498)."""
    return isinstance(item, (ir.Move, ir.Slew)) or native(item, "G")


def axis_of(item) -> str:
    if isinstance(item, ir.Move):
        return item.targets[0][0] if item.targets else ""
    return getattr(item, "axis", "")



def forward_all(module: ir.Module, transfer):
    """(routine, item, state before it) for every reachable operation, with the stream's state."""
    entries = flow.stream_entries(module, transfer, frozenset.union, subroutines=True)
    for routine in module.routines:
        states = flow.forward(routine, entries[routine.name], transfer, frozenset.union)
        for block in routine.blocks:
            if block.label in states:
                for item, state in flow.replay(block, states[block.label], transfer):
                    yield routine, item, state


# X302 ---------------------------------------------------------------------------------------------

def loop_end_input(tree: st.SyntaxTree) -> bool:
    """An input configured with function M ends loops (L2089)."""
    return any(isinstance(c.arg, st.IoFunction) and c.arg.function.upper() == "M" and c.mnemonic == "IN"
               for c in tree.commands())


def endless(command: st.Command) -> bool:
    if command.mnemonic != "L":
        return False
    return command.arg is None or isinstance(command.arg, st.Number) and command.arg.value == 0


def exits_loop(command: st.Command) -> bool:
    return command.mnemonic in LOOP_EXIT_NAMES or meaning(command.mnemonic) in LOOP_EXIT_IRS


@rule("X302", X150)
def endless_loop(ctx: Context) -> None:
    if loop_end_input(ctx.tree) or any(c.mnemonic == "Y" for c in ctx.tree.commands()):
        return  # an input with function M, or a Y sent by the host, ends the loop (L2089, L5494)
    stack: list[tuple[st.Command, bool]] = []  # (L command, has an exit)
    for command in ctx.tree.commands():
        if command.mnemonic in ("XD", "XT"):
            stack.clear()
        elif command.mnemonic == "L":
            stack.append((command, False))
        elif command.mnemonic == "N" and stack:
            opener, exited = stack.pop()
            if endless(opener) and not exited:
                ctx.report(opener.span, "this loop repeats forever and nothing in the program ends it: give L a "
                                        "count, or end it with Y, an input with function M (L2089) or a jump")
        elif exits_loop(command) and stack:
            stack = [(opener, True) for opener, _ in stack]


# X303 unused-subroutine (written once in ir_rules): sequences chosen at run time ----------------

def dynamic_selection(module: ir.Module, tree: st.SyntaxTree) -> bool:
    """Sequences chosen at run time: XR(VARn), GOTO(VARn), thumbwheels (XRD), select inputs (B/O)."""
    for _, _, op in flow.ops(module, ir.Native):
        if meaning(op.mnemonic) in ("call", "goto") and any(isinstance(a, ir.Var) for a in op.args):
            return True
        if op.mnemonic in ("XRD", "XRP"):
            return True
    return any(isinstance(c.arg, st.IoFunction) and c.arg.function.upper() in ("B", "O") for c in tree.commands())


# X304 ---------------------------------------------------------------------------------------------

@rule("X304", X150)
def comment_in_sequence(ctx: Context) -> None:
    inside = False
    first: st.Comment | None = None
    count = 0
    for line in ctx.tree.lines:
        for command in line.commands:
            if command.mnemonic == "XD":
                inside, first, count = True, None, 0
            elif command.mnemonic == "XT":
                if first is not None:
                    report_comments(ctx, first, count)
                inside, first = False, None
        ends_here = any(c.mnemonic == "XT" for c in line.commands)
        if inside and not ends_here and line.comment is not None:
            first = first or line.comment
            count += 1
    if inside and first is not None:
        report_comments(ctx, first, count)


def report_comments(ctx: Context, first: st.Comment, count: int) -> None:
    notes = (f"{count - 1} more comment{'s' if count > 2 else ''} in this sequence",) if count > 1 else ()
    ctx.report(first.span, "comments between XD and XT are not stored with the sequence (L5534)", notes=notes)


# X305 / X306 — WHEN --------------------------------------------------------------------------------

def re_arms(module: ir.Module, routine: ir.Routine, seen: set[str] | None = None) -> bool:
    """The routine (or a sequence it calls) sets a WHEN condition again."""
    seen = seen if seen is not None else set()
    work = [routine]
    while work:  # the sequences it calls, at any depth, without Python recursion
        current = work.pop()
        if current.name in seen and current is not routine:
            continue
        seen.add(current.name)
        for block in current.blocks:
            for op in block.ops:
                if isinstance(op, ir.SetHandler) and op.event == "when" and op.routine is None:
                    return True
                if isinstance(op, ir.Call) and op.routine not in seen:
                    callee = module.routine(op.routine)
                    if callee is not None:
                        work.append(callee)
    return False


@rule("X305", X150)
def when_not_re_armed(ctx: Context) -> None:
    module = ctx.module
    selected = {op.routine for _, _, op in flow.ops(module, ir.SetHandler) if op.event == "when" and op.routine}
    for name in sorted(selected):
        routine = module.routine(name)
        if routine is None or re_arms(module, routine):
            continue
        ctx.report(routine.span or ctx.source.line_span(1),
                   f"the XWHEN sequence {routine.number} does not end with WHEN(...): it runs only the first time "
                   "the condition is met (L4829)")


@rule("X306", X150)
def when_without_sequence(ctx: Context) -> None:
    handlers = [op for _, _, op in flow.ops(ctx.module, ir.SetHandler) if op.event == "when"]
    if any(op.routine for op in handlers):
        return
    for op in handlers:
        ctx.report(op.span, "WHEN watches this condition, but no XWHENn in this file selects the sequence to run "
                            "(L4827)")
        return


# X307 motion-never-stopped (written once in ir_rules): what stops an axis ---------------------

def stops(item) -> bool:
    if isinstance(item, ir.Stop):  # SB (the lowering's neutral stop)
        return True
    if isinstance(item, ir.Native) and item.dialect == X150:
        return meaning(item.mnemonic) in STOPPING_IRS or item.mnemonic in ("HALT", "OFF")
    return isinstance(item, ir.SetMotion) and item.param is ir.MotionParam.MAX_SPEED and const(item.value) == 0


# X308 — variable arithmetic -----------------------------------------------------------------

@rule("X308", X150)
def left_to_right_arithmetic(ctx: Context) -> None:
    for command in ctx.tree.commands():
        statement = command.arg
        if not isinstance(statement, st.VarStatement) or statement.value is None:
            continue
        ops = [op for op, _ in statement.value.rest]
        additive = False
        for op in ops:
            if op in "+-":
                additive = True
            elif op in "*/" and additive:
                ctx.report(statement.value.span, f"X150 evaluates left to right: this {op} applies to everything "
                                                 "before it, not only to the operand before it (L4638-L4642)")
                break


# X310 / X311 / X313 — motion state -----------------------------------------------------------------

def any_op(module: ir.Module, wanted) -> bool:
    """Whether an operation of the module is `wanted`: a rule whose state only an operation of
    that kind starts has nothing to find without one, and skips its walk of every routine (the
    editor server runs the rules on every keystroke)."""
    return any(wanted(op) for _, _, op in flow.ops(module))


@rule("X310", X150)
def move_while_disabled(ctx: Context) -> None:
    if not any_op(ctx.module, lambda op: isinstance(op, ir.DriveEnable) or native(op, "ST") or native(op, "OFF")):
        return  # the drive is never shut down

    def transfer(off: frozenset, item) -> frozenset:
        if isinstance(item, ir.DriveEnable):  # ST0 / ST1 (the lowering's neutral form)
            on = const(item.on)
            return off | {(item.axis, "ST1")} if on != 1 else frozenset(f for f in off if f[1] != "ST1")
        if native(item, "ST"):
            value = const(item.args[0]) if item.args else None
            return off | {(item.axis, "ST1")} if value != 0 else frozenset(f for f in off if f[1] != "ST1")
        if native(item, "OFF"):
            return off | {(item.axis, "OFF")}
        if native(item, "ON"):
            return frozenset(f for f in off if f[1] != "OFF")
        return off

    for _, item, off in forward_all(ctx.module, transfer):
        if is_go(item) and off:
            why = sorted({f[1] for f in off})
            ctx.report(item.span, f"the drive may be shut down here ({' / '.join(why)}): this move is ignored until "
                                  "ST0 / ON (L4025)")


@rule("X311", X150)
def repeated_absolute_move(ctx: Context) -> None:
    if not any_op(ctx.module, lambda op: isinstance(op, ir.Move) and op.mode is ir.MoveMode.ABSOLUTE):
        return  # no absolute move: nothing is reached

    def target(item) -> tuple:
        value = item.targets[0][1] if item.targets else None
        return (axis_of(item), value.value if isinstance(value, ir.Const) else getattr(value, "name", None))

    def transfer(reached: frozenset, item) -> frozenset:
        if isinstance(item, ir.Move):
            axis = axis_of(item)
            kept = frozenset(r for r in reached if r[0] != axis)
            return kept | {target(item)} if item.mode is ir.MoveMode.ABSOLUTE else kept
        if isinstance(item, ir.Assign) and item.target.name.startswith("%D"):
            return frozenset(r for r in reached if r[0] != item.target.name[2:])
        if isinstance(item, (ir.Call, ir.Home, ir.SetPosition, ir.Slew)) or native(item, "SP", "PZ", "G"):
            return frozenset()
        return reached

    # Since the lowering resolves D by data flow, a G that repeats the last absolute target (the
    # register unchanged, or set again to the same value) has the same Move target as the last one.
    for _, item, reached in forward_all(ctx.module, transfer):
        if isinstance(item, ir.Move) and item.mode is ir.MoveMode.ABSOLUTE and target(item) in reached:
            ctx.report(item.span, "in absolute mode (MPA) this G goes to the position the last G already reached: "
                                  "set a new D first (L2572)")


@rule("X313", X150)
def zero_velocity_move(ctx: Context) -> None:
    if not any_op(ctx.module, lambda op: isinstance(op, ir.SetMotion) and op.param is ir.MotionParam.MAX_SPEED
                  and const(op.value) == 0):
        return  # V0 is never set

    def transfer(zero: frozenset, item) -> frozenset:
        if isinstance(item, ir.SetMotion) and item.param is ir.MotionParam.MAX_SPEED:
            return zero | {item.axis} if const(item.value) == 0 else zero - {item.axis}
        return zero

    for _, item, zero in forward_all(ctx.module, transfer):
        if is_go(item) and (axis_of(item) in zero or ir.ALL_AXES in zero):
            ctx.report(item.span, "V0 is in force: with the motor at rest this G runs at the fastest possible "
                                  "velocity (L4547); set a real V")


# X312 ---------------------------------------------------------------------------------------------

@rule("X312", X150)
def direction_reversal_overridden(ctx: Context) -> None:
    pending: dict[int | None, st.Command] = {}
    for command in ctx.tree.commands():
        name = command.mnemonic
        if name == "H" and command.arg is None:
            pending[command.address] = command
        elif name == "D" and isinstance(command.arg, st.Number) and command.arg.text[:1] in "+-" \
                and command.address in pending:
            h = pending.pop(command.address)
            ctx.report(h.span, f"H reverses the next move, but the signed {command.text} at line {command.span.line} "
                               "sets the direction itself (L819): H has no effect")
        elif name in ("G", "XD", "XT"):
            pending.pop(command.address, None)


# The rules written once over the IR (compiler/lint/ir_rules.py), in X150's codes and words ------------

def distance_facts(item) -> tuple:
    """D is its own setting on X150: a move with a known distance, or setting the register, sets it."""
    if isinstance(item, ir.Move) and not uses_distance(item):
        return tuple(("distance", axis) for axis, _ in item.targets)
    if isinstance(item, ir.Assign) and item.target.name.startswith("%D"):
        return (("distance", item.target.name[2:]),)
    return ()


def distance_needed(item) -> tuple:
    return ("distance",) if isinstance(item, ir.Move) and uses_distance(item) else ()


def native_endless(item) -> str:
    """A G kept as X150 text: in continuous mode with a direction not known statically (L2498)."""
    return "native" if native(item, "G") else ""


def stopped_axis(item) -> str | None:
    """The axis an X150 command stops: S, SB, LS, K (catalog `ir`), HALT, OFF, or V0 (L4547)."""
    if stops(item):
        return getattr(item, "axis", "")
    return None


CONTINUOUS = "in continuous mode this G runs until S, SB, LS, K or V0 (L2498), and the program has none of them"

VOICE = ir_rules.Voice(
    X150,
    codes={
        "move-before-speed": "X301",
        "unused-subroutine": "X303",
        "motion-never-stopped": "X307",
        "division-by-zero": "X309",
    },
    messages={
        "move-before-speed": "G moves with the {names} left by whatever ran before: set {names} before the first G "
                             "(L1675)",
        "unused-subroutine": "nothing in this file runs sequence {number} (XR, XG, XP, XFK, XWHEN): remove it, or "
                             "suppress this if a host runs it",
        "motion-never-stopped.native": CONTINUOUS,
        "motion-never-stopped.slew": CONTINUOUS,
        "motion-never-stopped.move": CONTINUOUS,
        "division-by-zero": "division by zero: the result is undefined",
    },
    words={"accel": "A", "max_speed": "V", "distance": "D"},
    # GH homes at the speed it is given and with GA (L1701-L1711): only G uses A and V
    options={"move-before-speed": {"params": (ir.MotionParam.ACCEL, ir.MotionParam.MAX_SPEED),
                                   "kinds": (ir.Move, ir.Slew)},
             # a G kept as text may or may not be in continuous mode (X142 says why): said once per file
             "motion-never-stopped": {"once": ("native",)}},
    hooks={"facts": distance_facts, "needs": distance_needed, "moves": lambda item: native(item, "G"),
           "endless": native_endless, "stops": stopped_axis,
           "dynamic": lambda ctx: dynamic_selection(ctx.module, ctx.tree)},
)
ir_rules.register(VOICE)
