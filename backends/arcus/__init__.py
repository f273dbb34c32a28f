"""The Arcus PMX-4EX-SA backend: IR → canonical standalone text + an assembly-level listing.

`emit(module, profile)` is the whole interface. The work is done in five passes, one module each:

1. **Legalize** (legalize.py): a copy of each routine's CFG in which every operation is one Arcus
   statement, expressions split through the reserved temporaries (temporaries.py), units and
   neutral names converted (convert.py).
2. **Structure** (mcc.backends.structure, shared by targets without GOTO): IF/ELSEIF/ELSE and WHILE
   rebuilt from the CFG; loops left from one other place get a flag variable; anything else makes
   the routine a dispatch loop on a reserved variable, reported as a note (A202).
3. **Move modes** (move_modes.py): ABS/INC where a move needs a mode not known to be in force, on
   the structured program over all routines, so that the output read back means the same.
4. **Layout** (writer.py): main program, END, then the SUB blocks, one canonical statement per line.
5. **Cost** (costmodel.py): every statement expanded into the assembly lines of the profile's cost
   model, numbered like the controller's program counter; over the budget is an error (A201).

The backend reads only the IR, the profile and the Arcus catalog (for keyword spellings and what a
register may be used for); it never sees a syntax tree. Programs of any dialect come in: the
units and neutral names are converted in convert.py, and what the PMX-4EX-SA cannot express is
refused (G003) with the construct, its line and why. A program from another dialect starts with
a comment block stating the assumptions of the conversion (header.py). What the passes share lives in context.py
(the names given, the diagnostics) and target.py (the target's tables and the profile's settings).
"""

from __future__ import annotations

from mcc.backends.arcus import costmodel, header, move_modes, temporaries
from mcc.backends.arcus.context import Context
from mcc.backends.arcus.convert import Scale
from mcc.backends.arcus.legalize import Legalizer, lowest_speed
from mcc.backends.arcus.target import DIALECT
from mcc.backends.arcus.writer import Writer
from mcc.backends.listing import Listing
from mcc.backends.structure import EndNode, structure
from mcc.compiler import in_force, ir
from mcc.compiler.profiles import Profile
from mcc.compiler.span import Span

__all__ = ["emit", "memory", "DIALECT"]

MEMORY_CODES = ("A201", "A204", "A240")  # what `mcc check` reports of the cost model


def emit(module: ir.Module, profile: Profile) -> Listing:
    """Canonical Arcus standalone text and its assembly-level listing for an IR module."""
    ctx, stmts, dispatched = program(module, profile)
    return listing(ctx, stmts, dispatched, header.lines(module, profile, ctx))


def program(module: ir.Module, profile: Profile) -> tuple[Context, list, int]:
    """Passes 1-4: the program's statements in layout order (not yet priced), the context and
    how many routines became dispatch loops."""
    lowest = lowest_speed() / float(Scale(module.steps_per_rev, profile.steps_per_rev).factor)
    module = with_fixed_speeds(in_force.with_source_power_up(module, profile, lowest), profile)
    problems: list[in_force.Unresolved] = []  # an axis's own speeds as the PMX-4EX-SA applies them (L447-L457)
    sets = tuple(ir.MotionParam(name) for name in profile.get("arcus.axis_sets", []) or [])
    module = with_initial_values(in_force.with_axis_sets(module, sets, problems))
    ctx = Context(module, profile)
    for problem in problems:
        ctx.unsupported_at(problem.span, str(problem))
    ctx.number_subroutines()
    main: list = []
    subs: list[tuple[ir.Routine, list, Span | None]] = []
    programs: list[tuple[ir.Routine, list, Span | None]] = []  # PRG n blocks beside the main program
    dispatched = 0
    for routine in module.routines:
        kind = routine.kind
        if kind in (ir.RoutineKind.HANDLER, ir.RoutineKind.POWERUP):
            ctx.unsupported_at(routine.span, f"{routine.name} is a {kind.value} routine; Arcus has no event "
                                             "handlers or power-up entry")
            continue
        code, end_span, fallback = compile_routine(ctx, routine)
        dispatched += fallback
        if kind is ir.RoutineKind.SUBROUTINE:
            subs.append((routine, code, end_span))
        elif kind is ir.RoutineKind.PROGRAM:
            programs.append((routine, code, end_span))
        elif kind is ir.RoutineKind.IMMEDIATE:  # commands that run before the program
            main = [n for n in code if not isinstance(n, EndNode)] + main
        else:
            main += code
    move_modes.write_switches(main, subs, profile, module.modes_stated, programs)
    temporaries.check(ctx)
    stmts = Writer(ctx).program(main, subs, programs)
    return ctx, stmts, dispatched


def with_fixed_speeds(module: ir.Module, profile: Profile) -> ir.Module:
    """An X150 program starts every move from standstill; LSPD has no 0, so the output sets it at
    its lowest (`in_force.with_fixed_initial_speed`), the value the ramp times are computed with
    (`legalize.ramp_ms`)."""
    return in_force.with_fixed_initial_speed(
        module, lowest_speed() / float(Scale(module.steps_per_rev, profile.steps_per_rev).factor))


def with_initial_values(module: ir.Module) -> ir.Module:
    """Arcus declares no variables: a source variable's initial value (MCode `VA Q1=25`) becomes an
    assignment where the program starts, before anything else runs (the first routine the device
    runs: commands sent before the program, else the main program). An initial 0 is the value an
    Arcus variable starts with (docs/dialects/arcus.md, "Variables") and is not written. A copy; a
    module without other initial values is returned as it is."""
    declared = [v for v in module.variables.values()
                if v.init is not None and not (isinstance(v.init, ir.Const) and v.init.value == 0)]
    if not declared:
        return module
    copy = ir.copy_module(module)
    first = next((r for kind in (ir.RoutineKind.IMMEDIATE, ir.RoutineKind.MAIN) for r in copy.routines
                  if r.kind is kind and r.blocks), None)
    if first is not None:
        assigns = [ir.Assign(ir.Var(v.name, v.span), v.init, v.span) for v in declared]
        first.blocks[0].ops[:0] = assigns
    return copy


def memory(module: ir.Module, profile: Profile) -> tuple[dict, list]:
    """Program memory as `mcc check` reports it: the program priced exactly as `emit` prices it
    (the same passes and cost model), and the budget diagnostics only; the rest of what the backend
    reports is about writing the listing and belongs to `mcc compile`."""
    if not bool((profile.get("arcus.cost", {}) or {}).get("in_check", True)):
        return {}, []  # the profile leaves memory to `mcc compile` (a faster check)
    ctx, stmts, _ = program(module, profile)
    config = ctx.config
    total = costmodel.price(stmts, config)
    costmodel.check_budget(ctx, stmts, total)  # the listing's text and rows are not needed here
    usage = {"unit": "assembly lines", "used": total, "budget": config.budget,
             "percent": round(costmodel.share(total, config), 1), "cost_model": config.model}
    if config.gui_limit and config.gui_limit < config.budget:
        usage["gui_limit"] = config.gui_limit
    return usage, [d for d in ctx.diags if d.code in MEMORY_CODES]


def compile_routine(ctx: Context, routine: ir.Routine) -> tuple[list, Span | None, bool]:
    """Passes 1-2 for one routine: its structured tree, where it ends, and whether it is a dispatch loop."""
    legal = Legalizer(ctx, routine).run()
    temps = ctx.temps
    temps.start_routine(routine.span)

    def dispatch_var() -> ir.Var:
        var = temps.top(0)
        return var if var is not None else temps.last  # the pool is used up: reported as A205

    done = structure(legal, temps.top, dispatch_var, ctx.config.max_copied)
    if done.fallback is not None:
        ctx.diags.add("A202", routine.span or ctx.file_span(),
                      f"{routine.name}: {done.fallback}; it is written as a dispatch loop on {done.var.name} "
                      f"(WHILE {done.var.name}!=0 with one IF arm per block)")
    return done.body, done.exit_span, done.fallback is not None


def listing(ctx: Context, stmts: list, dispatched: int, comments: list[str] = ()) -> Listing:
    """Passes 4-5 put together: the text, its priced assembly rows, statistics and the budget check.
    `comments` (the conversion's assumptions) head the text; comments cost no assembly line."""
    config = ctx.config
    total = costmodel.price(stmts, config)
    result = Listing(DIALECT)
    for comment in comments:
        result.emit(comment)
    for stmt in stmts:
        result.emit(stmt.text, *stmt.spans)
    result.detail = costmodel.assembly_rows(stmts, total)
    result.stats = {"statements": len(stmts), "asm_lines": total, "asm_budget": config.budget,
                    "asm_percent": round(costmodel.share(total, config), 1), "cost_model": config.model,
                    "temporaries": ctx.temps.used, "dispatch_loops": dispatched}
    result.header = costmodel.header(ctx, total, len(stmts))
    costmodel.check_budget(ctx, stmts, total)
    result.diagnostics = ctx.diags
    return result
