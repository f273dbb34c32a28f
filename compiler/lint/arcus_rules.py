"""Lint rules for the Arcus Performax standalone language (A3xx); pages in codes/arcus-lint.toml.

The IR of an Arcus program is neutral (Move, Slew for JOG, Home, Arc, Stop, WaitMotion per axis,
SetMotion for HSPD/LSPD/ACC/SCV, Setting for SSPD/SYN.../EO, Status readings); what stays
`Native("arcus", <spelling>)` (SSPDM) is recognised through the catalog's patterns.
Rules that mean the same in every dialect are written once in ir_rules.py; `VOICE` gives their
codes and messages here, and hooks for what only this dialect knows.
"""

from __future__ import annotations

from functools import lru_cache

from mcc.compiler import ir
from mcc.compiler.arcus import catalog as acat
from mcc.compiler.arcus import syntax as st
from mcc.compiler.diagnostics import Fix
from mcc.compiler.lint import flow, ir_rules
from mcc.compiler.lint.edits import line_bounds, replace
from mcc.compiler.lint.rules import Context, rule

ARCUS = "arcus"
MOTION = (ir.Move, ir.Slew, ir.Home, ir.Arc)
SETTING_KEYWORDS = {"speed_change": "SSPD", "compare_output": "SYNO"}  # neutral settings the rules follow
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


def forward_all(module: ir.Module, transfer, join=frozenset.union, entry=frozenset()):
    """(routine, item, state before it) for every reachable operation and terminator."""
    for routine in module.routines:
        states = flow.forward(routine, entry, transfer, join)
        for block in routine.blocks:
            if block.label in states:
                for item, state in flow.replay(block, states[block.label], transfer):
                    yield routine, item, state


# The rules written once over the IR (compiler/lint/ir_rules.py), in Arcus's codes and words ------------

def error_subroutine(ctx, routine) -> bool:
    """The subroutine the controller jumps to on an error (`[arcus] error_subroutine`: SUB 31 on
    the PMX-2ED-SA, p.43 §7.19.5, and the ACE-SDE, p.48 §6.21.5): no GOSUB needs to call it."""
    return routine.number is not None and routine.number == ctx.profile.get("arcus.error_subroutine")


def unused_sub_fix(ctx: Context, routine: ir.Routine) -> Fix | None:
    """Delete `SUB n` ... `ENDSUB` (the routine's span to its last return)."""
    last = routine.blocks[-1].terminator if routine.blocks else None
    if routine.span is None or not isinstance(last, ir.Return) or last.span is None \
            or last.span.line <= routine.span.line:
        return None
    start, _ = line_bounds(ctx.source, routine.span.line)
    _, end = line_bounds(ctx.source, last.span.line)
    return Fix("delete the subroutine", (replace(ctx.source.span(start, end), ""),), safe=False)


VOICE = ir_rules.Voice(
    ARCUS,
    codes={
        "position-read-while-moving": "A301",
        "move-before-speed": "A302",
        "busy-wait": "A303",
        "unused-subroutine": "A307",
        "variable-read-before-write": "A308",
        "division-by-zero": "A309",
        "motion-never-stopped": "A314",
    },
    messages={
        "position-read-while-moving": "{reading}{axis} is read while the move at line {line} may still be running: "
                                      "add WAIT{axis} before reading it (L2706)",
        "move-before-speed": "this moves axis {axis} before {names} {verb} set on every path: speeds are not kept "
                             "in flash (L833-L844); set them at the start of the program",
        "busy-wait": "this loop only tests its condition again and again: add DELAY=<ms> inside it (L1868), or "
                     "WAIT[axis] to wait for a move",
        "unused-subroutine": "no GOSUB calls SUB {number}: remove it, or call it (a host can run it with GS{number}, "
                             "L823)",
        "variable-read-before-write": "{name} is read before the program writes it on some path: variables are not "
                                      "kept in flash; set it first (e.g. {name}=0)",
        "division-by-zero": "'{op} 0': division by zero has no result",
        "motion-never-stopped.slew": "axis {axis} jogs until something stops it, and the program never does "
                                     "(STOP{axis}, STOP or ABORT)",
        "motion-never-stopped.move": "axis {axis} keeps moving after it reaches its target, and the program never "
                                     "stops it (STOP{axis}, STOP or ABORT)",
    },
    words={"position": "P", "encoder": "E", "max_speed": "HSPD", "initial_speed": "LSPD", "accel_time": "ACC"},
    options={
        "position-read-while-moving": {"anchor": "reading"},
        "move-before-speed": {"params": (ir.MotionParam.MAX_SPEED, ir.MotionParam.INITIAL_SPEED,
                                         ir.MotionParam.ACCEL_TIME)},
    },
    hooks={"fix": unused_sub_fix, "entry": error_subroutine},
)
ir_rules.register(VOICE)


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


def keywords_in(module: ir.Module) -> set[str]:
    """The catalog names of the module's operations (`keyword`). A rule about keywords the program
    never uses has nothing to find: it skips its walk of every routine (the editor server runs the
    rules on every keystroke; a 3,000-line program does not use SCV, SSPDM or SYNO)."""
    return {keyword(op)[0] for _, _, op in flow.ops(module)}


@rule("A304", ARCUS)
def speed_change_with_s_curve(ctx: Context) -> None:
    if not {"SCV", "SSPD"} <= keywords_in(ctx.module):  # an S-curve switched on, and a speed change
        return
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
    if not {"SSPDM", "SSPD"} <= keywords_in(ctx.module):  # the mode armed, and a speed change in it
        return

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
        for axis in ir_rules.motion_axes(item):
            if ("used", axis) in state:
                ctx.report(item.span, f"SSPDM{axis} is not 0 here: set SSPDM{axis}=0 before a normal move after "
                                      "on-the-fly speed moves (L564)")
                break


@rule("A312", ARCUS)
def output_used_by_sync(ctx: Context) -> None:
    if "SYNO" not in keywords_in(ctx.module):  # no synchronisation output switched on
        return
    transfer = switch_state("SYNO", None)
    for _, item, on in forward_all(ctx.module, transfer):
        if not isinstance(item, ir.SetOutput) or not on:
            continue
        outputs = {AXES.index(axis) + 1: axis for axis in on if axis in AXES}
        hit = sorted(outputs) if item.index is None else [item.index] if item.index in outputs else []
        for index in hit:
            ctx.report(item.span, f"DO{index} is driven by the synchronisation output of axis {outputs[index]} "
                                  f"(SYN{outputs[index]}O): it cannot be set until SYN{outputs[index]}F (L765)")


# A305 — whole program -------------------------------------------------------------------------

@rule("A305", ARCUS)
def drives_never_enabled(ctx: Context) -> None:
    first = next((op for _, _, op in flow.ops(ctx.module, MOTION)), None)
    if first is None:
        return
    if any(keyword(op)[0] == "EO" for _, _, op in flow.ops(ctx.module, (ir.Setting, ir.DriveEnable))):
        return
    ctx.report(first.span, "the program moves axes but never sets the enable outputs (EO): drives wired to them "
                           "stay disabled (L748)")


# A306 — subroutines -------------------------------------------------------------------------

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
