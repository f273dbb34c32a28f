"""Pass 5: the cost model. Every statement costs a number of the controller's assembly lines.

The PMX-4EX-SA stores a compiled program in a fixed number of assembly lines, and how many lines
each statement takes is not documented; the profile's `[arcus.cost]` table gives the model's
estimate per statement kind (docs/arcus-cost-model.md has the calibration). The statements are
numbered from 0 like the controller's program counter, each expanded into exactly as many listing
rows as it costs (so the listing's row numbers are addresses) and mapped back to the source; a
program over the budget is an error (A201) that names the model, the budget, the count and the
costliest source lines, and one close to it a warning (A204). Near or over the Windows software's
lower limit of compiled lines (`gui_limit`, 1785, L1079) is a warning (A240).
"""

from __future__ import annotations

import re

from mcc.backends.arcus.context import Context
from mcc.backends.arcus.target import AXES, Config
from mcc.backends.arcus.writer import Stmt
from mcc.compiler.span import Span

PLACEHOLDER = re.compile(r"\{(\w+)\}")


def cost_of(stmt: Stmt, config: Config) -> int:
    if stmt.key and all(part in AXES for part in stmt.key.split(" ")):  # a move: per axis named
        return sum(config.cost(axis) for axis in stmt.key.split(" "))
    return config.cost(stmt.key)


def price(stmts: list[Stmt], config: Config) -> int:
    """Sets each statement's cost and address; returns the program's total in assembly lines."""
    address = 0
    costs: dict[str, int] = {}  # per cost key: a program uses a few dozen keys
    for stmt in stmts:
        cost = costs.get(stmt.key)
        if cost is None:
            cost = costs[stmt.key] = cost_of(stmt, config)
        stmt.cost = cost
        stmt.address = address
        address += cost
    return address


def share(total: int, config: Config) -> float:
    """The percentage of the budget the program takes."""
    return 100.0 * total / config.budget if config.budget else 0.0


def assembly_rows(stmts: list[Stmt], total: int) -> list[tuple[str, tuple[Span, ...]]]:
    """The listing's detail: each priced statement's rows, jump targets resolved to addresses."""
    subs = {f"sub{int(stmt.text.split()[1])}": f"{stmt.address:04d}" for stmt in stmts if stmt.key == "SUB"}
    detail: list[tuple[str, tuple[Span, ...]]] = []
    for stmt in stmts:
        targets = {name: f"{entry(stmts, i, total) if name == 'next' else address(stmts, i, total):04d}"
                   for name, i in stmt.jumps.items()}
        targets.update(subs)
        rows = [f"{op:<5} {PLACEHOLDER.sub(lambda m: targets.get(m.group(1), '????'), operands)}".rstrip()
                for op, operands in stmt.rows]
        for row in fit(rows, stmt.cost):
            detail.append((row, stmt.spans))
    return detail


def address(stmts: list[Stmt], index: int, total: int) -> int:
    return stmts[index].address if index < len(stmts) else total


def entry(stmts: list[Stmt], index: int, total: int) -> int:
    """Where a failed IF/ELSEIF test lands: the test of the next ELSEIF (after its jump to
    ENDIF), the first line after ELSE, or the ENDIF."""
    stmt = stmts[index]
    if stmt.key == "ELSEIF":
        return stmt.address + min(1, stmt.cost - 1)
    if stmt.key == "ELSE":
        return stmt.address + stmt.cost
    return address(stmts, index, total)


def fit(rows: list[str], cost: int) -> list[str]:
    """Exactly `cost` rows: extra natural rows share the last one, missing ones are continuation rows."""
    if not rows:
        rows = ["NOP"]
    if len(rows) > cost:
        rows = rows[:cost - 1] + [" ; ".join(rows[cost - 1:])]
    while len(rows) < cost:
        rows.append(".     (continued: the model charges this statement another line)")
    return rows


def header(ctx: Context, total: int, statements: int) -> str:
    """The listing's first lines: which model priced it, how trustworthy it is, and the total."""
    config, profile = ctx.config, ctx.profile
    status = "calibrated" if config.calibrated else "uncalibrated estimates (spec 6.4 H-estimate)"
    return "\n".join([
        f"; mcc arcus listing for {profile.title or profile.product} (profile {profile.name})",
        f"; cost model: {config.model}, {status}; per-statement costs from [arcus.cost] of the profile",
        f"; budget: {config.budget} assembly lines; this program: {total} lines for {statements} statements "
        f"({share(total, config):.1f} %)",
        "; rows: mcc pseudo-instructions, one per assembly line the model counts, numbered like the program "
        "counter (SPC); the controller's real encoding (SA<n>) is undocumented",
    ])


def check_gui_limit(ctx: Context, total: int) -> None:
    """The second limit: the Arcus Windows software compiles at most 1785 lines (L1079), below the
    controller's 3230 (L827). It applies only to programs downloaded with that software, so it is a
    warning (A240) near or over it; a profile whose budget is already that limit does not repeat it."""
    config = ctx.config
    limit = config.gui_limit
    if not limit or (config.budget and (limit >= config.budget or total > config.budget)) \
            or total <= config.warn_fraction * limit:
        return  # no second limit, or the budget's own A201 already says more
    where = "over" if total > limit else "close to"
    ctx.diags.add("A240", ctx.file_span(),
                  f"the program needs {total} assembly lines under the cost model '{config.model}', {where} the "
                  f"{limit} compiled lines the Arcus Windows software accepts (L1079; the controller holds "
                  f"{config.budget}, L827): download it with another tool, shorten it, or set "
                  "`[arcus.cost] gui_limit = 0` if you do not use that software")


def check_budget(ctx: Context, stmts: list[Stmt], total: int) -> None:
    check_gui_limit(ctx, total)
    config = ctx.config
    if not config.budget:
        return
    if total <= config.budget:
        if total > config.warn_fraction * config.budget:
            ctx.diags.add("A204", ctx.file_span(),
                          f"the program needs {total} of the {config.budget} assembly lines of the target "
                          f"({share(total, config):.0f} %) under the cost model '{config.model}', "
                          "whose costs are estimates: it may not fit on the controller")
        return
    per_line: dict[tuple[str, int], int] = {}
    first_span: dict[tuple[str, int], Span] = {}
    for stmt in stmts:
        for span in stmt.spans[:1]:
            key = (span.file, span.line)
            per_line[key] = per_line.get(key, 0) + stmt.cost
            first_span.setdefault(key, span)
    top = sorted(per_line.items(), key=lambda item: (-item[1], item[0][1]))[:5]
    listed = ", ".join(f"line {line} ({cost})" for (_, line), cost in top)
    span = first_span[top[0][0]] if top else ctx.file_span()
    ctx.diags.add("A201", span,
                  f"the program needs {total} assembly lines under the cost model '{config.model}' but the "
                  f"budget of profile '{ctx.profile.name}' is {config.budget}: shorten it by "
                  f"{total - config.budget} lines (loops, subroutines); the costliest source lines are "
                  f"{listed or 'not known'}",
                  notes=tuple(f"{first_span[k].label}: {cost} assembly lines" for k, cost in top))
