"""Lint rules for Lexium MCode (M3xx). One function per code; the pages are in codes/mcode-lint.toml.

Rules work on the IR where the question is about behaviour (flow, trips, calls) and on the syntax
tree where it is about how something is written (`=<`, argument order, the last line). Facts about
commands come from the catalog (trip bits, float registers), never from tables written here.
Rules that mean the same in every dialect are written once in ir_rules.py; `VOICE` at the end
gives their MCode codes and messages.
"""

from __future__ import annotations

from functools import lru_cache

from mcc.compiler import ir
from mcc.compiler.diagnostics import Edit, Fix
from mcc.compiler.lint import flow, ir_rules
from mcc.compiler.lint.edits import delete_line, insert_after_line, replace
from mcc.compiler.lint.rules import Context, rule
from mcc.compiler.mcode import catalog as mcat
from mcc.compiler.mcode import syntax as st
from mcc.compiler.mcode.lower import TRIP_EVENTS

MCODE = "mcode"
# Flags a program polls to wait for the end of a move instead of H (L4207, L4427).
MOTION_FLAGS = ("moving", "moving_to_position")  # MV, MP
MOTION_OPS = (ir.Move, ir.Slew, ir.Home, ir.Arc)
EVENT_TRIP = {event: name for name, event in TRIP_EVENTS.items()}  # "input" -> "TI"
SUBROUTINE_KINDS = (ir.RoutineKind.SUBROUTINE, ir.RoutineKind.HANDLER)


# shared facts --------------------------------------------------------------------------------------

@lru_cache(maxsize=1)
def catalog() -> mcat.McodeCatalog:
    return mcat.load()


def trip_bit(event: str) -> int:
    """The TE bit of a trip event, from the catalog's `trip_bit` (TI 1, TP 2, ... TM 64)."""
    command = catalog().lookup(EVENT_TRIP.get(event, ""))
    return int(command.entry.get("trip_bit", 0)) if command is not None else 0


def reads_any(item, meanings: tuple[str, ...]) -> bool:
    """Whether an operation or terminator reads one of the named device readings."""
    found = flow.op_reads(item) if not isinstance(item, (ir.Branch, ir.Jump, ir.Return, ir.End, ir.FallOff)) \
        else flow.term_reads(item)
    return any(isinstance(n, ir.Status) and n.meaning in meanings for n in found)


def reads_input(item) -> bool:
    found = flow.term_reads(item) if isinstance(item, ir.Branch) else flow.op_reads(item) if item is not None else ()
    return any(isinstance(n, ir.Status) and n.meaning in ("input", "inputs") for n in found) or \
        isinstance(item, ir.WaitInput)


def is_te(op) -> bool:
    """A `TE=`: the neutral setting `handler_enable` (or a Native TE of an older lowering)."""
    return (isinstance(op, ir.Setting) and op.name == "handler_enable") or \
        (isinstance(op, ir.Native) and op.mnemonic == "TE" and bool(op.args))


def te_value(op):
    return op.value if isinstance(op, ir.Setting) else op.args[0]


def te_writes(module: ir.Module):
    """Every `TE=` of the module: (routine, block, op, constant value or None)."""
    for routine in module.routines:
        for block in routine.blocks:
            for op in block.ops:
                if is_te(op):
                    value = te_value(op)
                    yield routine, block, op, value.value if isinstance(value, ir.Const) else None


def handlers(module: ir.Module) -> list[ir.SetHandler]:
    return [op for _, _, op in flow.ops(module, ir.SetHandler)]


def line_of(span) -> int:
    return span.line if span is not None else 0


def comment_marker(ctx: Context) -> str:
    """The comment character the file already uses (backtick or apostrophe)."""
    for line in ctx.tree.lines:
        if line.comment is not None:
            return line.comment.text[0]
    return "'"


# M301 ---------------------------------------------------------------------------------------------

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


# M302 / M312 / M323 --------------------------------------------------------------------------------

@rule("M302", MCODE)
def branch_out_of_subroutine(ctx: Context) -> None:
    index = flow.block_index(ctx.module)
    for routine in ctx.module.routines:
        if routine.kind not in SUBROUTINE_KINDS:
            continue
        # only code the routine's own entry reaches: a label after its RT that nothing in the file
        # reaches is an entry point the host starts with EX, and leaving it with BR pushes nothing
        inside = {b.label for b in flow.reachable(routine)}
        for block, label, target, fallthrough in flow.foreign_jumps(ctx.module, routine, index):
            if fallthrough or block.label not in inside:
                continue
            what = "handler" if routine.kind is ir.RoutineKind.HANDLER else "subroutine"
            ctx.report(block.terminator.span,
                       f"BR leaves the {what} {routine.name} for {label} in {target.name}: the return address "
                       f"stays on the stack (stack errors, L5607); end the {what} with RT")


@rule("M312", MCODE)
def missing_return(ctx: Context) -> None:
    index = flow.block_index(ctx.module)
    for routine in ctx.module.routines:
        if routine.kind not in SUBROUTINE_KINDS:
            continue
        what = "handler" if routine.kind is ir.RoutineKind.HANDLER else "subroutine"
        for block in flow.reachable(routine):
            term = block.terminator
            if isinstance(term, ir.End):
                ctx.report(term.span, f"E ends the whole program inside the {what} {routine.name}, with its return "
                                      "address still on the stack: end it with RT")
            elif isinstance(term, ir.FallOff):
                ctx.report(term.span or routine.span,
                           f"the {what} {routine.name} runs past its last line without RT: add RT")
            elif isinstance(term, ir.Jump) and term.target in index and index[term.target][0] is not routine \
                    and flow.is_fallthrough(term, index[term.target][1]):
                ctx.report(routine.span, f"the {what} {routine.name} runs on into {term.target} (line "
                                         f"{line_of(term.span)}) without RT: add RT before that label")


# M323 (the program runs on into a subroutine) is a check of the frontend since issue 12, so that
# `mcc check` reports it too: compiler/mcode/checks.py, check_fall_into_subroutine.


# M303 / M317 / M322 / M315 / M319 / M318 — trips -------------------------------------------------

def te_sets_bit(op, bit: int) -> bool:
    """Whether `op` is a TE that sets `bit` (one whose value is not known counts as setting it)."""
    if not is_te(op):
        return False
    value = te_value(op)
    return not isinstance(value, ir.Const) or bool(int(value.value) & bit)


def handler_re_enables(module: ir.Module, routine: ir.Routine, bit: int) -> bool:
    """True when every path from the handler's entry to an RT sets TE with the trip's bit."""

    def transfer(done: bool, item) -> bool:
        if te_sets_bit(item, bit):
            return True
        if isinstance(item, ir.Call):
            callee = module.routine(item.routine)
            if callee is not None and any(te_sets_bit(op, bit) for block in callee.blocks for op in block.ops):
                return True
        return done

    states = flow.forward(routine, False, transfer, lambda a, b: a and b)
    for block in routine.blocks:
        if block.label in states and isinstance(block.terminator, ir.Return):
            done = states[block.label]
            for op in block.ops:
                done = transfer(done, op)
            if not done:
                return False
    return True


def main_re_arms(module: ir.Module, bit: int) -> bool:
    """The main program sets TE (with the bit) inside a loop, re-arming the trip itself."""
    for routine in module.routines:
        if routine.kind not in (ir.RoutineKind.MAIN, ir.RoutineKind.POWERUP):
            continue
        looping = flow.in_loops(routine)
        for block in routine.blocks:
            if block.label in looping and any(te_sets_bit(op, bit) for op in block.ops):
                return True
    return False


@rule("M303", MCODE)
def trip_not_re_enabled(ctx: Context) -> None:
    module = ctx.module
    for op in handlers(module):
        bit = trip_bit(op.event)
        if not bit or op.routine is None or op.event == "relative":  # TR repeats by itself (L5836)
            continue
        routine = module.routine(op.routine)
        if routine is None or handler_re_enables(module, routine, bit) or main_re_arms(module, bit):
            continue
        ctx.report(op.span, f"the {EVENT_TRIP[op.event]} trip fires once: its handler {routine.name} returns "
                            f"without setting TE bit {bit} again; add `TE={bit}` (or the sum of the trips "
                            "to keep) before its RT")


def defined_trip_bits(ctx: Context) -> int:
    """Trips the file defines, read from the syntax tree: a definition the frontend rejected (an
    undeclared variable in TP=Ds*3,X2) is still a definition, and is already reported."""
    bits = 0
    for stmt in ctx.tree.statements():
        command = catalog().lookup(stmt.head.key)
        if command is not None:
            bits |= int(command.entry.get("trip_bit", 0)) if command.ir == "trip" else 0
    return bits


@rule("M317", MCODE)
def trip_enable_undefined(ctx: Context) -> None:
    defined = defined_trip_bits(ctx)
    for _, _, op, value in te_writes(ctx.module):
        if value is None or not isinstance(value, int):
            continue
        missing = value & ~defined & 127
        if missing:
            names = [f"{bit} ({mnemonic})" for mnemonic, bit in trip_bits_table() if missing & bit]
            ctx.report(op.span, f"TE={value} enables trip{'s' if len(names) > 1 else ''} {', '.join(names)} that "
                                "this file never defines: the device answers Error 27 (L5678)")


def trip_bits_table() -> list[tuple[str, int]]:
    return [(name, trip_bit(event)) for name, event in TRIP_EVENTS.items()]


@rule("M322", MCODE)
def trip_never_enabled(ctx: Context) -> None:
    enabled = 0
    for _, _, _, value in te_writes(ctx.module):
        enabled |= 127 if value is None or not isinstance(value, int) else value
    for op in handlers(ctx.module):
        bit = trip_bit(op.event)
        if bit and not enabled & bit:
            ctx.report(op.span, f"the {EVENT_TRIP[op.event]} trip is defined but never enabled: add `TE={bit}` "
                                "after the definition (L8111)")


@rule("M315", MCODE)
def position_and_relative_trip(ctx: Context) -> None:
    seen: dict[str, ir.SetHandler] = {}
    for op in handlers(ctx.module):
        if op.event in ("position", "relative"):
            other = seen.get("relative" if op.event == "position" else "position")
            if other is not None:
                ctx.report(op.span, f"{EVENT_TRIP[op.event]} and {EVENT_TRIP[other.event]} (line "
                                    f"{line_of(other.span)}) cannot be used together: the device answers Error 39")
            seen.setdefault(op.event, op)


@rule("M319", MCODE)
def second_input_trip(ctx: Context) -> None:
    first: ir.SetHandler | None = None
    for op in handlers(ctx.module):
        if op.event != "input":
            continue
        if first is None:
            first = op
        elif (op.routine, op.args) != (first.routine, first.args):
            ctx.report(op.span, f"a second input trip: only one may be defined (L8114), this one replaces TI at "
                                f"line {line_of(first.span)}")


@rule("M318", MCODE)
def trip_argument_order(ctx: Context) -> None:
    for stmt in ctx.tree.statements():
        if stmt.head.key != "TA" or len(stmt.args) != 2:
            continue
        bits, label = stmt.args
        if isinstance(bits, st.Number) and isinstance(label, st.Name):
            text = ctx.source.text
            first, second = text[bits.span.start:bits.span.end], text[label.span.start:label.span.end]
            fix = Fix("put the label first", (replace(bits.span, second), replace(label.span, first)))
            ctx.report(stmt.span, f"TA takes the label first: `TA={second},{first}` (L5583)", fix=fix)


# M304 ---------------------------------------------------------------------------------------------

@rule("M304", MCODE)
def motion_at_power_up(ctx: Context) -> None:
    module = ctx.module

    def transfer(unguarded: bool, item) -> bool:
        return unguarded and not isinstance(item, ir.WaitInput)

    def edge(unguarded: bool, block: ir.Block, succ: ir.Block) -> bool:
        return unguarded and not reads_input(block.terminator)

    routines = flow.routine_index(module)

    def moves(routine_name: str, seen: set[str]) -> bool:
        """The routine, or one it calls (at any depth), starts motion."""
        work = [routine_name]
        while work:
            routine = routines.get(work.pop())
            if routine is None or routine.name in seen:
                continue
            seen.add(routine.name)
            for block in routine.blocks:
                for op in block.ops:
                    if isinstance(op, MOTION_OPS):
                        return True
                    if isinstance(op, ir.Call):
                        work.append(op.routine)
        return False

    for routine in module.routines:
        if routine.kind is not ir.RoutineKind.POWERUP:
            continue
        states = flow.forward(routine, True, transfer, lambda a, b: a or b, edge)
        for block in routine.blocks:
            if not states.get(block.label):
                continue
            for item, unguarded in flow.replay(block, True, transfer):
                if not unguarded:
                    break
                if isinstance(item, MOTION_OPS) or isinstance(item, ir.Call) and moves(item.routine, set()):
                    ctx.report(item.span, "the SU program starts motion as soon as the device is powered "
                                          "(DANGER, L5526): wait for an input first, or start it with EX")
                    return


# M305 / M310 — names and declarations --------------------------------------------------

@rule("M305", MCODE)
def unused_label(ctx: Context) -> None:
    labels = ctx.analysis.symbols.labels  # references: BR (not a fall-through), CL, EX, trips, OE

    def used(name: str) -> bool:
        return name in labels and labels[name].used

    for routine in ctx.module.routines:
        # a label nothing reaches (after RT, E or BR) is how the host starts a part of the program
        # (EX <label>): deleting it would cut that part off, so it is not reported (issue 24)
        starts = flow.entry_points(routine, used)
        for block in routine.blocks:
            if not block.named or used(block.label) or block.label == "SU" or block.label in starts:
                continue
            if routine.origin is not None and block is routine.entry:
                continue  # a program start: run with EX <label> or EX <address>
            fix = Fix("delete the label", (delete_line(ctx.source, block.span.line),), safe=False)
            ctx.report(block.span, f"label {block.label} is never the target of BR, CL, EX or a trip: remove it "
                                   "or branch to it", fix=fix)


def declared_name(ctx: Context, var: ir.Variable):
    """The span of the name in `VA <name>` (the IR keeps the whole statement's span)."""
    span = var.span
    for stmt in ctx.tree.statements():
        if stmt.span.line == span.line and stmt.head.key == "VA" and stmt.args:
            arg = stmt.args[0]
            return (arg.left if isinstance(arg, st.Comparison) else arg).span
    return span


def declaration_lines(ctx: Context, var: ir.Variable) -> list[int]:
    """Every `VA <name>` line of the variable (a repeated VA is M141's error; deleting the variable
    deletes them all at once)."""
    lines = []
    for stmt in ctx.tree.statements():
        if stmt.head.key == "VA" and stmt.args:
            arg = stmt.args[0]
            name = arg.left if isinstance(arg, st.Comparison) else arg
            if isinstance(name, st.Name) and name.key == var.name.upper():
                lines.append(stmt.span.line)
    return lines or [var.span.line]


@rule("M310", MCODE)
def declaration_in_loop(ctx: Context) -> None:
    for routine in ctx.module.routines:
        looping = flow.in_loops(routine)
        for block in routine.blocks:
            if block.label not in looping:
                continue
            for op in block.ops:
                if isinstance(op, ir.Native) and op.mnemonic == "VA":
                    name = op.args[0].name if op.args and isinstance(op.args[0], ir.Var) else "?"
                    ctx.report(op.span, f"VA {name} is inside a loop and runs on every pass: declare it once, "
                                        "before the loop")


# M308 / M311 / M321 — expressions ------------------------------------------------------------------

@rule("M308", MCODE)
def float_truncated(ctx: Context) -> None:
    for _, _, op in flow.ops(ctx.module, (ir.Assign, ir.SetMotion)):
        target = op.target.name if isinstance(op, ir.Assign) else None
        # the module's types, not the Lexium catalog's: on an MDrivePlus (profile mdrive-plus) F1 is a
        # user variable like any other (docs/dialects/mcode.md)
        if target is not None and ctx.module.type_of(target) is ir.VarType.FLOAT64:
            continue
        floats = sorted({n.name for n in ir.walk_expr(op.value)
                         if isinstance(n, ir.Var) and ctx.module.type_of(n.name) is ir.VarType.FLOAT64})
        if floats:
            what = target or "the setting"
            ctx.report(op.span, f"{', '.join(floats)} {'is a' if len(floats) == 1 else 'are'} floating point; "
                                f"{what} holds integers, so the fraction is discarded (L2812)")


def operators(expr) -> set[str]:
    """The binary operators of one arithmetic expression (a comparison's sides are separate)."""
    found: set[str] = set()
    stack = [expr]
    while stack:
        node = stack.pop()
        if isinstance(node, ir.BinOp):
            found.add(node.op)
            stack += [node.left, node.right]
        elif isinstance(node, ir.UnOp):
            stack.append(node.operand)
        elif isinstance(node, ir.Func):
            stack += list(node.args)
    return found


def expressions(item):
    """The arithmetic expressions of an operation or terminator, with comparisons split in two."""
    exprs = ir.term_exprs(item) if isinstance(item, ir.Branch) else ir.op_exprs(item)
    for expr in exprs:
        if isinstance(expr, ir.Compare):
            yield from (expr.left, expr.right)
        elif isinstance(expr, ir.Truth):
            yield expr.expr
        elif isinstance(expr, ir.Logic | ir.Not | ir.InputMatch):
            continue
        else:
            yield expr


@rule("M311", MCODE)
def mixed_operators(ctx: Context) -> None:
    for _, block in ctx.module.blocks():
        for item in [*block.ops, block.terminator]:
            for expr in expressions(item):
                ops = operators(expr)
                if len(ops) > 1:
                    ctx.report(expr.span or item.span,
                               f"this expression mixes {' and '.join(sorted(ops))}, and the manual defines no "
                               "precedence (mcc evaluates left to right): split it into one operation per statement")


@rule("M321", MCODE)
def reversed_comparison(ctx: Context) -> None:
    text = ctx.source.text
    for stmt in ctx.tree.statements():
        for arg in stmt.args:
            if isinstance(arg, st.Comparison) and arg.op == "=<":
                start = text.find("=<", arg.left.span.end, arg.right.span.start)
                if start < 0:
                    continue
                span = ctx.source.span(start, start + 2)
                ctx.report(span, "`=<` is not an MCode operator: write `<=` (L1259)",
                           fix=Fix("write <=", (Edit(span, "<="),)))


# M314 — moves ------------------------------------------------------------------------------

@rule("M314", MCODE)
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


# M316 — EX -----------------------------------------------------------------------------------------

@rule("M316", MCODE)
def execute_not_program_start(ctx: Context) -> None:
    index = flow.block_index(ctx.module)
    for _, _, op in flow.ops(ctx.module, ir.Native):
        if op.mnemonic != "EX" or not op.args or not isinstance(op.args[0], ir.LabelRef):
            continue
        found = index.get(op.args[0].name)
        if found is None:
            continue
        routine, block = found
        if routine.kind in SUBROUTINE_KINDS:
            ctx.report(op.args[0].span or op.span,
                       f"EX {op.args[0].name} runs a {routine.kind.value} directly: its RT has no call to return to "
                       "(stack error); run the program that calls it")
        elif block is not routine.entry or routine.origin is None:
            ctx.report(op.args[0].span or op.span,
                       f"EX {op.args[0].name} starts in the middle of program {routine.name}, skipping its start")


# M309 / M320 — saving -----------------------------------------------------------------------------

def statement_lines(ctx: Context) -> list[st.Line]:
    return [line for line in ctx.tree.lines if line.statement is not None]


@rule("M309", MCODE)
def program_not_saved(ctx: Context) -> None:
    lines = statement_lines(ctx)
    last_pg = None
    for line in lines:
        if line.statement.head.key == "PG":
            last_pg = line
    if last_pg is None:
        return
    after = [line for line in lines if line.number > last_pg.number]
    if any(line.statement.head.key == "S" and not line.statement.args for line in after):
        return
    marker = comment_marker(ctx)
    fix = Fix("add S and a comment line after the final PG",
              (insert_after_line(ctx.source, last_pg.number, f"S\n{marker} keep this line: it ends the S\n"),),
              safe=False)
    ctx.report(last_pg.statement.span, "the program is stored but never saved: add `S` after the final PG, or it is "
                                       "lost at power-off (L5269)", fix=fix)


@rule("M320", MCODE)
def save_on_last_line(ctx: Context) -> None:
    content = [line for line in ctx.tree.lines if line.statement is not None or line.comment is not None or line.error]
    if not content:
        return
    last = content[-1]
    stmt = last.statement
    if stmt is None or stmt.head.key != "S" or stmt.args:
        return
    marker = comment_marker(ctx)
    fix = Fix("add a comment line after S",
              (insert_after_line(ctx.source, last.number, f"{marker} keep this line: it ends the S\n"),))
    ctx.report(stmt.span, "S is the last line: add a comment line after it so its line end is sent (L5269)", fix=fix)


# The rules written once over the IR (compiler/lint/ir_rules.py), in MCode's codes and words -----------

VOICE = ir_rules.Voice(
    MCODE,
    codes={
        "position-read-while-moving": "M301",
        "unused-variable": "M306",
        "unreachable-code": "M307",
        "motion-never-stopped": "M313",
        "division-by-zero": "M324",
    },
    messages={
        "position-read-while-moving": "the position is read while the move at line {lines} may still be running: "
                                      "add `H` after the move so the program waits for it to finish",
        "unused-variable.never": "variable {name} is never used{host}",
        "unused-variable.written": "variable {name} is only written, never read{host}",
        "unused-variable.host": " (if a host reads it with PR, suppress this line)",
        "unreachable-code": "this line can never run: the line before it always branches, returns or ends and no "
                            "label leads here",
        "motion-never-stopped.move": "this move keeps running after it reaches its position (parameter 3 = 1) and "
                                     "no `SL 0` stops it anywhere in the program",
        "motion-never-stopped.slew": "SL keeps the axis running at this velocity and no `SL 0` stops it anywhere in "
                                     "the program",
        "division-by-zero": "'{op} 0' divides by zero, which the manual does not define (L6337-L6356): test the "
                            "divisor first",
    },
    words={"position": "P", "encoder": "C2"},
    options={
        # H is a program instruction (L4207): typed or downloaded outside a program there is no H to add
        "position-read-while-moving": {"anchor": "operation", "skip_immediate": True},
        "unreachable-code": {"skip_immediate": True},
    },
    hooks={"name_span": declared_name, "declaration_lines": declaration_lines},
)
ir_rules.register(VOICE)
