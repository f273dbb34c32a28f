"""Lint rules written once over the IR, for every dialect that has them (docs/LINT.md).

A position read while a move may still run, a move before its speeds are set, a loop that only
spins, a division by the constant 0, motion nothing ever stops, code that can never run, a
variable nothing reads, a subroutine nothing calls, a variable read before it is written: each
means the same whatever the dialect, so each is one function here over the IR's neutral
operations (`Move`, `WaitMotion`, `SetMotion`, `Status` readings, the CFG and the data flow of
`flow.py`), and the file's symbol table and def-use chains (`Analysis.symbols`, `.defuse`).

What stays per dialect is data, in a `Voice` each `<dialect>_rules.py` declares:

- `codes`: the shared rule's name -> the dialect's own code (M301, A301, ...): codes are stable,
  so a dialect keeps its numbers and a rule it does not list does not run for it;
- `messages`: the message of each rule (and of its variants, `"rule.variant"`) in the dialect's
  own words, a `str.format` template over the fields each rule documents below;
- `words`: the dialect's spelling of a neutral name used in messages (`max_speed` -> `HSPD`);
- `options`: the per-rule choices that differ by dialect (where a finding points);
- `hooks`: the few facts only the dialect knows, as functions (which of its `Native` commands
  stop an axis, the fix that deletes an Arcus `SUB ... ENDSUB`).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Callable, Iterable, Mapping

from mcc.compiler import ir
from mcc.compiler.diagnostics import Fix
from mcc.compiler.lint import flow
from mcc.compiler.lint.edits import delete_line
from mcc.compiler.lint.rules import Context, rule

# Readings of where an axis is (position counter, encoder) and of whether it still moves.
POSITION_READINGS = ("position", "encoder")
MOTION_FLAGS = ("moving", "moving_to_position", "motor_status")
FINITE_MOTION = (ir.Move, ir.Home, ir.Arc)  # motion that ends by itself
MOTION = (ir.Move, ir.Arc, ir.Slew, ir.Home)
TERMINATORS = (ir.Branch, ir.Jump, ir.Return, ir.End, ir.FallOff, ir.GotoRoutine)


@dataclass(frozen=True)
class Voice:
    """How one dialect says the shared rules: its codes, messages and words (data), and hooks."""

    dialect: str
    codes: Mapping[str, str]
    messages: Mapping[str, str]
    words: Mapping[str, str] = field(default_factory=dict)
    options: Mapping[str, Any] = field(default_factory=dict)
    hooks: Mapping[str, Callable] = field(default_factory=dict)

    def say(self, key: str, **fields: Any) -> str:
        return self.messages[key].format(**fields)

    def word(self, name: str) -> str:
        return self.words.get(name, name)

    def hook(self, name: str, default: Callable) -> Callable:
        return self.hooks.get(name, default)


SHARED: dict[str, Callable[[Context, Voice], None]] = {}
# The message variants a rule may ask for (`"rule.variant"`): a dialect that lists the rule gives
# each of them (tests/lint/test_ir_rules.py), plus the kinds its own hooks return.
VARIANTS: dict[str, tuple[str, ...]] = {
    "motion-never-stopped": ("slew", "move"),
    "unused-variable": ("never", "written"),
}


def shared(name: str):
    """Declare a shared rule under its neutral name (each dialect's code keeps its own `name`)."""

    def register(func: Callable[[Context, Voice], None]) -> Callable[[Context, Voice], None]:
        SHARED[name] = func
        return func

    return register


def register(voice: Voice) -> None:
    """Register the shared rules a dialect has, each under the dialect's code."""
    for name, code in voice.codes.items():
        check = SHARED[name]

        def run(ctx: Context, check=check) -> None:
            check(ctx, voice)

        run.__name__ = name.replace("-", "_")
        run.__doc__ = check.__doc__
        rule(code, voice.dialect)(run)


# helpers -------------------------------------------------------------------------------------------

def reads(item) -> Iterable:
    if item is None:
        return ()
    return flow.term_reads(item) if isinstance(item, TERMINATORS) else flow.op_reads(item)


def const(expr) -> float | None:
    return expr.value if isinstance(expr, ir.Const) else None


def motion_axes(op) -> tuple[str, ...]:
    """The axes an operation sets moving."""
    if isinstance(op, ir.Move):
        return tuple(axis for axis, _ in op.targets)
    if isinstance(op, ir.Arc):
        return op.axes
    if isinstance(op, (ir.Slew, ir.Home)):
        return (op.axis,)
    return ()


def same_axis(a: str, b: str) -> bool:
    """Two axis names that may be the same axis: equal, or one of them every axis / unaddressed."""
    return a == b or a in (ir.ALL_AXES, "") or b in (ir.ALL_AXES, "")


def walk(routine: ir.Routine, states: dict, transfer) -> Iterable[tuple[object, Any]]:
    """Every reachable operation and terminator of a routine with the state just before it."""
    for block in routine.blocks:
        if block.label in states:
            yield from flow.replay(block, states[block.label], transfer)


# position-read-while-moving ------------------------------------------------------------------------

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
    """Whether an operation or terminator of the module reads a position (or encoder) register."""
    for _, block in module.blocks():
        for item in (*block.ops, block.terminator):
            if any(isinstance(node, ir.Status) and node.meaning in POSITION_READINGS for node in reads(item)):
                return True
    return False


@shared("position-read-while-moving")
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


# move-before-speed ---------------------------------------------------------------------------------

@shared("move-before-speed")
def move_before_speed(ctx: Context, voice: Voice) -> None:
    """Option `params`: the motion settings a move needs (`ir.MotionParam`s), `kinds`: the operations
    that use them (default: moves, arcs, slews, homing); hooks `facts(item)`
    and `needs(item)` add settings only the dialect has (X150's distance register), `moves(item)`
    recognises a move the dialect keeps native. Fields: axis, names (the missing settings in the
    dialect's words, ", "), verb ("is" or "are"). One finding per routine: its first such move."""
    options = voice.options["move-before-speed"]
    params = tuple(options["params"])
    kinds = tuple(options.get("kinds", MOTION))
    extra_facts = voice.hook("facts", lambda item: ())
    extra_needs = voice.hook("needs", lambda item: ())
    native_move = voice.hook("moves", lambda item: False)

    def gen(item):
        facts = [(item.param, item.axis)] if isinstance(item, ir.SetMotion) and item.param in params else []
        return facts + list(extra_facts(item))

    facts = flow.MustFacts(ctx.module, gen)
    entries = flow.stream_entries(ctx.module, facts.transfer, frozenset.intersection, subroutines=False)
    for name, states in facts.states(entries).items():
        routine = ctx.module.routine(name)
        for item, state in walk(routine, states, facts.transfer):
            axes = motion_axes(item) if isinstance(item, kinds) else \
                (item.axis,) if native_move(item) else ()
            missing: list = []
            for axis in axes:
                needed = list(params) + list(extra_needs(item))
                missing = [p for p in needed if (p, axis) not in state and (p, ir.ALL_AXES) not in state]
                if missing:
                    names = ", ".join(voice.word(p.value if isinstance(p, ir.MotionParam) else p) for p in missing)
                    ctx.report(item.span, voice.say("move-before-speed", axis=axis, names=names,
                                                    verb="is" if len(missing) == 1 else "are"))
                    break
            if missing:
                break


# busy-wait -----------------------------------------------------------------------------------------

@shared("busy-wait")
def busy_wait(ctx: Context, voice: Voice) -> None:
    """A loop whose blocks (inner loops included) only compute: no delay, wait, motion, output,
    call or native command. Reported at the loop's test. No fields."""
    for routine in ctx.module.routines:
        forest = flow.loop_forest(routine)  # innermost first, each block in one loop: linear
        idle: dict[str, bool] = {}
        for loop in forest:
            idle[loop.header.label] = all(isinstance(op, ir.Assign) for block in loop.blocks for op in block.ops) \
                and all(idle[inner.header.label] for inner in loop.inner)
        for loop in forest:
            if isinstance(loop.header.terminator, ir.Branch) and idle[loop.header.label]:
                ctx.report(loop.header.terminator.span, voice.say("busy-wait"))


# division-by-zero ----------------------------------------------------------------------------------

@shared("division-by-zero")
def division_by_zero(ctx: Context, voice: Voice) -> None:
    """`/` or `%` by the constant 0. Field: op."""
    for _, block in ctx.module.blocks():
        for item in [*block.ops, block.terminator]:
            for node in reads(item):
                if isinstance(node, ir.BinOp) and node.op in ("/", "%") and const(node.right) == 0:
                    ctx.report(node.span or item.span, voice.say("division-by-zero", op=node.op))


# motion-never-stopped ------------------------------------------------------------------------------

def endless(op) -> str:
    """The kind of motion that runs until something stops it: "slew" (a jog, or a constant velocity
    known not to be 0), "move" (a move that keeps running at its target), or ""."""
    if isinstance(op, ir.Slew):
        return "slew" if op.velocity is None or const(op.velocity) not in (None, 0) else ""
    if isinstance(op, ir.Move) and any(key == "continuous" and const(value) == 1 for key, value in op.options):
        return "move"
    return ""


def stopped_axis(op) -> str | None:
    """The axis an operation may stop: a stop, a slew at a velocity that is (or may be) 0, or an
    input set up as a soft stop (the operator's switch stops the motion)."""
    if isinstance(op, ir.Stop):
        return op.axis
    if isinstance(op, ir.Slew) and op.velocity is not None and const(op.velocity) in (None, 0):
        return op.axis
    if isinstance(op, ir.Setting) and op.name == "input_function" and isinstance(op.value, ir.Text) \
            and op.value.value == "soft_stop":
        return op.axis
    return None


@shared("motion-never-stopped")
def motion_never_stopped(ctx: Context, voice: Voice) -> None:
    """Motion that only ends when stopped, on an axis nothing in the program stops. Hooks:
    `endless(op)` names the kind of a native endless move, `stops(op)` the axis a native command
    stops (or None). Message variants `.slew`, `.move` and the hook's kinds; field: axis. Option
    `once`: kinds reported once per file (a native move whose mode is only possibly endless)."""
    native_endless = voice.hook("endless", lambda op: "")
    native_stop = voice.hook("stops", lambda op: None)
    once = set(voice.options.get("motion-never-stopped", {}).get("once", ()))
    stopped: set[str] = set()
    moving: list[tuple[object, str]] = []
    for _, _, op in flow.ops(ctx.module):
        kind = endless(op) or native_endless(op)
        if kind:
            moving.append((op, kind))
        axis = stopped_axis(op)
        if axis is None:
            axis = native_stop(op)
        if axis is not None:
            stopped.add(axis)
    reported: set[str] = set()
    for op, kind in moving:
        axis = getattr(op, "axis", "") or (op.targets[0][0] if isinstance(op, ir.Move) and op.targets else "")
        if any(same_axis(axis, other) for other in stopped) or kind in reported:
            continue
        if kind in once:
            reported.add(kind)
        ctx.report(op.span, voice.say(f"motion-never-stopped.{kind}", axis=axis))


# unreachable-code ----------------------------------------------------------------------------------

@shared("unreachable-code")
def unreachable_code(ctx: Context, voice: Voice) -> None:
    """A block no path from its routine's entry reaches, that is not a label and that nothing
    jumps to; the conventional lone end after an endless main loop is not reported. Option
    `skip_immediate`. No fields."""
    module = ctx.module
    skip_immediate = voice.options.get("unreachable-code", {}).get("skip_immediate", False)
    targeted = {label for _, block in module.blocks() for label in ir.successors(block.terminator)}
    for routine in module.routines:
        if routine.kind is ir.RoutineKind.IMMEDIATE and skip_immediate:
            continue
        live = {b.label for b in flow.reachable(routine)}
        for block in routine.blocks:
            if block.label in live or block.named or block.label in targeted:
                continue
            if not block.ops and isinstance(block.terminator, (ir.End, ir.FallOff)):
                continue
            first = block.ops[0] if block.ops else block.terminator
            ctx.report(first.span, voice.say("unreachable-code"))


# unused-variable -----------------------------------------------------------------------------------

@shared("unused-variable")
def unused_variable(ctx: Context, voice: Voice) -> None:
    """A declared variable (`Module.variables` with a span) whose value nothing reads, from the
    def-use chains; updating a variable from itself (`IC Q1`) is not a read. Variants `.never`
    (nothing mentions it: the fix deletes the declaration's line) and `.written`; fields: name (as
    written), host (the `.host` message for a global variable, which a host may read). Hook
    `name_span(ctx, variable)`: the span of the declared name; hook `declaration_lines(ctx, variable)`:
    every line that declares it (a file may declare it again, which the device refuses), all deleted
    by the one fix."""
    defuse = ctx.analysis.defuse
    name_span = voice.hook("name_span", lambda ctx, var: var.span)
    for name, var in ctx.module.variables.items():
        if var.span is None or defuse.read(name):
            continue
        mentioned = defuse.mentioned(name)
        lines = voice.hook("declaration_lines", lambda ctx, var: [var.span.line])(ctx, var)
        fix = None if mentioned else Fix("delete the declaration",
                                         tuple(delete_line(ctx.source, line) for line in lines), safe=False)
        where = name_span(ctx, var)
        written = ctx.source.text[where.start:where.end] if where is not var.span else name
        host = voice.say("unused-variable.host") if var.scope == "global" and "unused-variable.host" in \
            voice.messages else ""
        ctx.report(where, voice.say("unused-variable." + ("written" if mentioned else "never"), name=written,
                                    host=host), fix=fix)


# unused-subroutine ---------------------------------------------------------------------------------

@shared("unused-subroutine")
def unused_subroutine(ctx: Context, voice: Voice) -> None:
    """A numbered routine (a subroutine or a stored program) that nothing in the file calls,
    transfers to or installs as a handler, from the symbol table. Hooks: `dynamic(ctx)` answers
    True when the file chooses routines at run time (then nothing is reported), `fix(ctx, routine)`.
    Field: number."""
    if voice.hook("dynamic", lambda ctx: False)(ctx):
        return
    symbols = ctx.analysis.symbols.routines
    make_fix = voice.hook("fix", lambda ctx, routine: None)
    entry = voice.hook("entry", lambda ctx, routine: False)  # the device itself runs it (an error handler)
    for routine in ctx.module.routines:
        if routine.number is None or routine.kind not in (ir.RoutineKind.SUBROUTINE, ir.RoutineKind.MAIN):
            continue
        if entry(ctx, routine):
            continue
        if symbols[routine.name].used:
            continue
        ctx.report(routine.span or ctx.source.line_span(1), voice.say("unused-subroutine", number=routine.number),
                   fix=make_fix(ctx, routine))


# variable-read-before-write ------------------------------------------------------------------------

@shared("variable-read-before-write")
def variable_read_before_write(ctx: Context, voice: Voice) -> None:
    """A variable read on a path where nothing has written it yet (once per routine and variable).
    Only variables the def-use chains show read are followed. Field: name."""
    defuse = ctx.analysis.defuse
    if not defuse.uses:
        return

    def gen(item):
        return (item.target.name,) if isinstance(item, ir.Assign) else ()

    facts = flow.MustFacts(ctx.module, gen)
    seen: set[tuple[str, str]] = set()
    for name, states in facts.states().items():
        routine = ctx.module.routine(name)
        for item, written in walk(routine, states, facts.transfer):
            for node in reads(item):
                if isinstance(node, ir.Var) and node.name not in written and (name, node.name) not in seen:
                    seen.add((name, node.name))
                    ctx.report(node.span or item.span, voice.say("variable-read-before-write", name=node.name))
