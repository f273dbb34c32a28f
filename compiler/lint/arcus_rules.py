"""Lint rules for the Arcus Performax standalone language (A3xx); pages in codes/arcus-lint.toml.

The IR of an Arcus program is neutral (Move, Slew for JOG, Home, Arc, Stop, WaitMotion per axis,
SetMotion for HSPD/LSPD/ACC/SCV, Setting for SSPD/SYN.../EO, Status readings); what stays
`Native("arcus", <spelling>)` (SSPDM) is recognised through the catalog's patterns.
"""

from __future__ import annotations

from functools import lru_cache

from mcc.compiler import ir
from mcc.compiler.arcus import catalog as acat
from mcc.compiler.arcus import syntax as st
from mcc.compiler.diagnostics import Fix
from mcc.compiler.lint import flow
from mcc.compiler.lint.edits import line_bounds, replace
from mcc.compiler.lint.rules import Context, rule

ARCUS = "arcus"
MOTION = (ir.Move, ir.Slew, ir.Home, ir.Arc)
SPEED_PARAMS = (ir.MotionParam.MAX_SPEED, ir.MotionParam.INITIAL_SPEED, ir.MotionParam.ACCEL_TIME)
PARAM_NAMES = {ir.MotionParam.MAX_SPEED: "HSPD", ir.MotionParam.INITIAL_SPEED: "LSPD",
               ir.MotionParam.ACCEL_TIME: "ACC"}
SETTING_KEYWORDS = {"speed_change": "SSPD", "compare_output": "SYNO"}  # neutral settings the rules follow
READ_WHILE_MOVING = ("position", "encoder")  # IR meanings of P[axis] and E[axis]
FINITE_MOTION = (ir.Move, ir.Home, ir.Arc)  # motion that ends by itself (a jog does not)
AXES = ("X", "Y", "Z", "U")


@lru_cache(maxsize=1)
def catalog() -> acat.ArcusCatalog:
    return acat.load()


def keyword(op) -> tuple[str, str]:
    """(catalog name, axis) of an operation the rules follow: `SSPDMX` -> ("SSPDM", "X"), the
    setting speed_change on X -> ("SSPD", "X"), compare_output on X -> ("SYNO", "X") (its value
    says on or off), SCVX=1 -> ("SCV", "X"), EO -> ("EO", ...)."""
    if isinstance(op, ir.Setting) and op.name in SETTING_KEYWORDS:
        return SETTING_KEYWORDS[op.name], op.axis
    if isinstance(op, ir.Setting) and op.name == "enable_outputs" or isinstance(op, ir.DriveEnable):
        return "EO", op.axis
    if isinstance(op, ir.SetMotion) and op.param is ir.MotionParam.PROFILE:
        return "SCV", op.axis
    if not isinstance(op, ir.Native) or op.dialect != ARCUS:
        return "", ""
    found = catalog().match(op.mnemonic.upper())
    return (found.keyword.name, found.axis) if found is not None else ("", "")


def const(expr) -> int | None:
    return int(expr.value) if isinstance(expr, ir.Const) else None


def argument(op) -> ir.Expr | None:
    """The value an operation writes (a setting's value, a Native's first argument)."""
    if isinstance(op, (ir.Setting, ir.SetMotion)):
        return op.value
    if isinstance(op, ir.DriveEnable):
        return op.on
    args = getattr(op, "args", ())
    return args[0] if args else None


def motion_axes(op) -> tuple[str, ...]:
    """Axes an operation sets moving."""
    if isinstance(op, ir.Move):
        return tuple(axis for axis, _ in op.targets)
    if isinstance(op, ir.Arc):
        return op.axes
    if isinstance(op, (ir.Slew, ir.Home)):
        return (op.axis,)
    return ()


def reads(item):
    if item is None:
        return ()
    return flow.term_reads(item) if isinstance(item, (ir.Branch, ir.Jump, ir.Return, ir.End, ir.FallOff)) \
        else flow.op_reads(item)


def forward_all(module: ir.Module, transfer, join=frozenset.union, entry=frozenset()):
    """(routine, item, state before it) for every reachable operation and terminator."""
    for routine in module.routines:
        states = flow.forward(routine, entry, transfer, join)
        for block in routine.blocks:
            if block.label in states:
                for item, state in flow.replay(block, states[block.label], transfer):
                    yield routine, item, state


# A301 ---------------------------------------------------------------------------------------------

@rule("A301", ARCUS)
def position_read_while_moving(ctx: Context) -> None:
    def transfer(moving: frozenset, item) -> frozenset:
        if isinstance(item, ir.WaitMotion):
            return frozenset(m for m in moving if m[0] != item.axis)
        polled = {n.axis for n in reads(item) if isinstance(n, ir.Status) and n.meaning == "motor_status"}
        if polled:
            moving = frozenset(m for m in moving if m[0] not in polled)
        axes = motion_axes(item) if isinstance(item, FINITE_MOTION) else ()
        return moving | {(axis, item.span.line) for axis in axes} if axes else moving

    for _, item, moving in forward_all(ctx.module, transfer):
        if not moving:
            continue
        for node in reads(item):
            if isinstance(node, ir.Status) and node.meaning in READ_WHILE_MOVING:
                lines = sorted(line for axis, line in moving if axis == node.axis)
                if lines:
                    name = "P" if node.meaning == "position" else "E"
                    ctx.report(node.span or item.span,
                               f"{name}{node.axis} is read while the move at line {lines[-1]} may still be "
                               f"running: add WAIT{node.axis} before reading it (L2706)")


# A302 ---------------------------------------------------------------------------------------------

@rule("A302", ARCUS)
def move_before_speed(ctx: Context) -> None:
    def gen(item):
        if isinstance(item, ir.SetMotion) and item.param in SPEED_PARAMS:
            return ((item.param, item.axis),)
        return ()

    facts = flow.MustFacts(ctx.module, gen)
    for name, states in facts.states().items():
        unset = first_unset(first_per_routine(ctx.module.routine(name), states, facts.transfer))
        if unset is not None:  # one finding per routine: the first move is where to fix it
            item, axis, missing = unset
            names = ", ".join(PARAM_NAMES[p] for p in missing)
            ctx.report(item.span, f"this moves axis {axis} before {names} {'is' if len(missing) == 1 else 'are'} set "
                                  "on every path: speeds are not kept in flash (L833-L844); set them at the start of "
                                  "the program")


def first_unset(items):
    for item, state in items:
        for axis in motion_axes(item):
            missing = [p for p in SPEED_PARAMS if (p, ir.ALL_AXES) not in state]
            if missing and any((p, axis) not in state for p in SPEED_PARAMS):
                return item, axis, missing
    return None


def first_per_routine(routine: ir.Routine, states: dict, transfer):
    """Every reachable operation of a routine with the state before it, in block order."""
    for block in routine.blocks:
        if block.label in states:
            yield from flow.replay(block, states[block.label], transfer)


# A303 ---------------------------------------------------------------------------------------------

def busy(block: ir.Block) -> bool:
    """A block that does nothing but compute: no delay, wait, motion, output, call or native command."""
    return all(isinstance(op, ir.Assign) for op in block.ops)


@rule("A303", ARCUS)
def busy_wait(ctx: Context) -> None:
    for routine in ctx.module.routines:
        forest = flow.loop_forest(routine)  # innermost first, each block in one loop: linear
        idle: dict[str, bool] = {}  # header -> the whole loop (inner loops included) only computes
        for loop in forest:
            idle[loop.header.label] = all(busy(block) for block in loop.blocks) and \
                all(idle[inner.header.label] for inner in loop.inner)
        for loop in forest:
            header = loop.header
            if not isinstance(header.terminator, ir.Branch):
                continue
            if idle[header.label]:
                ctx.report(header.terminator.span,
                           "this loop only tests its condition again and again: add DELAY=<ms> inside it (L1868), "
                           "or WAIT[axis] to wait for a move")


# A304 / A311 / A312 — per-axis modes ---------------------------------------------------------------

def switch_state(name_on: str, name_off: str | None, on_value=lambda v: v != 0):
    """A transfer function tracking the axes where a setting may be on."""

    def transfer(on: frozenset, item) -> frozenset:
        name, axis = keyword(item)
        if name == name_on:
            value = const(argument(item))
            if value is None or on_value(value):
                return on | {axis}
            return on - {axis}
        if name_off is not None and name == name_off:
            return on - {axis}
        return on

    return transfer


@rule("A304", ARCUS)
def speed_change_with_s_curve(ctx: Context) -> None:
    transfer = switch_state("SCV", None)
    for _, item, on in forward_all(ctx.module, transfer):
        name, axis = keyword(item)
        if name == "SSPD" and axis in on:
            ctx.report(item.span, f"S-curve is on for axis {axis} (SCV{axis}=1): on-the-fly speed change cannot be "
                                  f"used on it (L2432); set SCV{axis}=0 first")


@rule("A311", ARCUS)
def speed_mode_not_reset(ctx: Context) -> None:
    """The state holds ("armed", axis) after SSPDM<axis> != 0 and ("used", axis) once an SSPD ran
    in that mode; the move that SSPD changes is fine, a move after it is not."""

    def transfer(state: frozenset, item) -> frozenset:
        name, axis = keyword(item)
        if name == "SSPDM":
            value = const(argument(item))
            cleared = frozenset(f for f in state if f[1] != axis)
            return cleared if value == 0 else cleared | {("armed", axis)}
        if name == "SSPD" and ("armed", axis) in state:
            return state | {("used", axis)}
        return state

    for _, item, state in forward_all(ctx.module, transfer):
        for axis in motion_axes(item):
            if ("used", axis) in state:
                ctx.report(item.span, f"SSPDM{axis} is not 0 here: set SSPDM{axis}=0 before a normal move after "
                                      "on-the-fly speed moves (L564)")
                break


@rule("A312", ARCUS)
def output_used_by_sync(ctx: Context) -> None:
    transfer = switch_state("SYNO", None)
    for _, item, on in forward_all(ctx.module, transfer):
        if not isinstance(item, ir.SetOutput) or not on:
            continue
        outputs = {AXES.index(axis) + 1: axis for axis in on if axis in AXES}
        hit = sorted(outputs) if item.index is None else [item.index] if item.index in outputs else []
        for index in hit:
            ctx.report(item.span, f"DO{index} is driven by the synchronisation output of axis {outputs[index]} "
                                  f"(SYN{outputs[index]}O): it cannot be set until SYN{outputs[index]}F (L765)")


# A305 / A314 — whole program -------------------------------------------------------------------------

@rule("A305", ARCUS)
def drives_never_enabled(ctx: Context) -> None:
    first = next((op for _, _, op in flow.ops(ctx.module, MOTION)), None)
    if first is None:
        return
    if any(keyword(op)[0] == "EO" for _, _, op in flow.ops(ctx.module, (ir.Setting, ir.DriveEnable))):
        return
    ctx.report(first.span, "the program moves axes but never sets the enable outputs (EO): drives wired to them "
                           "stay disabled (L748)")


@rule("A314", ARCUS)
def jog_never_stopped(ctx: Context) -> None:
    stopped = {op.axis for _, _, op in flow.ops(ctx.module, ir.Stop)}
    for _, _, op in flow.ops(ctx.module, ir.Slew):
        if op.axis not in stopped and ir.ALL_AXES not in stopped:
            ctx.report(op.span, f"axis {op.axis} jogs until something stops it, and the program never does "
                                f"(STOP{op.axis}, STOP or ABORT)")


# A306 / A307 — subroutines -------------------------------------------------------------------------

def calls(module: ir.Module) -> dict[str, list[ir.Call]]:
    graph: dict[str, list[ir.Call]] = {r.name: [] for r in module.routines}
    for routine, _, op in flow.ops(module, ir.Call):
        graph[routine.name].append(op)
    return graph


@rule("A306", ARCUS)
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


@rule("A307", ARCUS)
def unused_subroutine(ctx: Context) -> None:
    called = {op.routine for _, _, op in flow.ops(ctx.module, ir.Call)}
    for routine in ctx.module.routines:
        if routine.kind is not ir.RoutineKind.SUBROUTINE or routine.name in called or routine.span is None:
            continue
        last = routine.blocks[-1].terminator if routine.blocks else None
        fix = None
        if isinstance(last, ir.Return) and last.span is not None and last.span.line > routine.span.line:
            start, _ = line_bounds(ctx.source, routine.span.line)
            _, end = line_bounds(ctx.source, last.span.line)
            fix = Fix("delete the subroutine", (replace(ctx.source.span(start, end), ""),), safe=False)
        ctx.report(routine.span, f"no GOSUB calls SUB {routine.number}: remove it, or call it (a host can run it with "
                                 f"GS{routine.number}, L823)", fix=fix)


# A308 / A309 — variables and arithmetic -------------------------------------------------------------

@rule("A308", ARCUS)
def variable_read_before_write(ctx: Context) -> None:
    def gen(item):
        return (item.target.name,) if isinstance(item, ir.Assign) else ()

    facts = flow.MustFacts(ctx.module, gen)
    seen: set[tuple[str, str]] = set()
    for name, states in facts.states().items():
        routine = ctx.module.routine(name)
        for block in routine.blocks:
            if block.label not in states:
                continue
            for item, written in flow.replay(block, states[block.label], facts.transfer):
                for node in reads(item):
                    if isinstance(node, ir.Var) and node.name not in written and (name, node.name) not in seen:
                        seen.add((name, node.name))
                        ctx.report(node.span or item.span,
                                   f"{node.name} is read before the program writes it on some path: variables are not "
                                   f"kept in flash; set it first (e.g. {node.name}=0)")


@rule("A309", ARCUS)
def division_by_zero(ctx: Context) -> None:
    for _, block in ctx.module.blocks():
        for item in [*block.ops, block.terminator]:
            for node in reads(item):
                if isinstance(node, ir.BinOp) and node.op in ("/", "%") and const(node.right) == 0:
                    ctx.report(node.span or item.span, f"'{node.op} 0': division by zero has no result")


# A310 ---------------------------------------------------------------------------------------------

@rule("A310", ARCUS)
def arc_in_incremental_mode(ctx: Context) -> None:
    """The lowering resolves ABS/INC into the moves and keeps the modes possible at each arc."""
    arc_modes = getattr(ctx.tree, "arc_modes", {})
    for _, _, item in flow.ops(ctx.module, ir.Arc):
        if item.span is not None and "INC" in arc_modes.get((item.span.line, item.span.column), ()):
            ctx.report(item.span, "ARC/CIR while INC may be in force: whether the centre is then relative is "
                                  "not documented (L586); write ABS before it")


# A313 / A315 — how it is written --------------------------------------------------------------------

@rule("A313", ARCUS)
def constant_condition(ctx: Context) -> None:
    for stmt in ctx.tree.statements():
        if not isinstance(stmt, st.Conditional):
            continue
        comp = stmt.condition.first
        if isinstance(comp.left, st.Number) and isinstance(comp.right, st.Number) and not comp.chained:
            truth = compare(comp.op, comp.left.value, comp.right.value)
            if stmt.keyword == "WHILE" and truth:
                continue  # WHILE 1=1: the documented endless loop (L2649)
            outcome = "always" if truth else "never"
            ctx.report(comp.span, f"{stmt.keyword} compares two numbers: the branch is {outcome} taken")


def compare(op: str, a: int, b: int) -> bool:
    return {"=": a == b, "!=": a != b, "<": a < b, "<=": a <= b, ">": a > b, ">=": a >= b}.get(op, False)


@rule("A315", ARCUS)
def trailing_comment(ctx: Context) -> None:
    for line in ctx.tree.lines:
        if line.statement is None or line.comment is None:
            continue
        text = ctx.source.line_text(line.number)
        indent = text[:len(text) - len(text.lstrip())]
        start, _ = line_bounds(ctx.source, line.number)
        code_end = line.statement.span.end
        comment = line.comment
        fix = Fix("move the comment to its own line", (
            replace(ctx.source.span(start, start), f"{indent}{comment.text.rstrip()}\n"),
            replace(ctx.source.span(code_end, comment.span.end), ""),
        ))
        ctx.report(comment.span, "the specification wants comments on their own line (L1725)", fix=fix)
