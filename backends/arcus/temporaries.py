"""The reserved temporaries (`[arcus] temporaries`, V60-V63 by default) and the check of their use.

Arcus evaluates one operator per statement, so longer expressions and AND/OR conditions need
scratch variables, and loop flags and dispatch loops need a variable that lives across a whole
loop. Both come from the same reserved pool, from opposite ends, so that they can only collide
when the program needs more than the profile reserves, which `check` reports.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from mcc.compiler import ir
from mcc.compiler.span import Span

if TYPE_CHECKING:
    from mcc.backends.arcus.context import Context


class Temps:
    """The reserved temporaries: expression temporaries from the low end (short-lived, a stack),
    loop flags and the dispatch variable from the high end (long-lived)."""

    def __init__(self, pool: list[int]):
        self.pool = pool
        self.live = 0
        self.peak = 0
        self.high = 0  # variables taken from the top
        self.base = 0  # the first of them the current routine may use
        self.exhausted = False
        # where the refusal (A205) points: the construct that found the pool used up, else the
        # expression that needed the most temporaries at once; the routine a loop flag is taken for
        self.exhausted_at: Span | None = None
        self.peak_at: Span | None = None
        self.routine_at: Span | None = None

    @property
    def last(self) -> ir.Var:
        """The variable written when the pool is used up (the program is then an error, A205)."""
        return ir.Var(f"V{self.pool[-1] if self.pool else 63}")

    def alloc(self, span: Span | None = None) -> ir.Var:
        """An expression temporary for the statement at `span`."""
        if self.live >= len(self.pool):
            self.exhausted = True
            self.exhausted_at = self.exhausted_at or span
            var = self.last
        else:
            var = ir.Var(f"V{self.pool[self.live]}")
        self.live += 1
        if self.live > self.peak:
            self.peak, self.peak_at = self.live, span or self.peak_at
        return var

    def release(self, count: int = 1) -> None:
        self.live -= count

    def top(self, depth: int) -> ir.Var | None:
        """The current routine's long-lived variable number `depth`, from the top of the pool.

        Each routine gets its own (`start_routine`): a loop flag or dispatch variable must survive
        the GOSUBs made while it is live, so callers and callees never share one."""
        index = self.base + depth
        self.high = max(self.high, index + 1)
        if index >= len(self.pool):
            self.exhausted = True
            self.exhausted_at = self.exhausted_at or self.routine_at
            return None
        return ir.Var(f"V{self.pool[-1 - index]}")

    def start_routine(self, span: Span | None = None) -> None:
        self.base = self.high
        self.routine_at = span

    @property
    def conflict(self) -> bool:
        return self.exhausted or self.peak + self.high > len(self.pool)

    @property
    def used(self) -> int:
        """How many temporaries the program needs at once (the listing's statistic)."""
        return self.peak + self.high


def check(ctx: "Context") -> None:
    """Too many temporaries at once (A205), and program variables that are temporaries (A203)."""
    temps = ctx.temps
    if temps.conflict:
        span = (temps.exhausted_at if temps.exhausted else None) or temps.peak_at or temps.exhausted_at \
            or temps.routine_at or ctx.file_span()
        ctx.diags.add("A205", span,
                      f"compiling this program needs {temps.used} temporary variables at once; "
                      f"the profile reserves {len(temps.pool)} ([arcus] temporaries = {temps.pool}): reserve "
                      "more or simplify the expressions")
    if temps.peak == 0 and temps.high == 0:
        return
    used = {f"V{n}" for n in temps.pool[:temps.peak]} | {f"V{n}" for n in temps.pool[len(temps.pool) - temps.high:]}
    for name in sorted(ctx.variable_names):
        upper = name.upper()
        if upper in used:
            variable = ctx.module.variables.get(name)
            span = variable.span if variable is not None and variable.span is not None else ctx.file_span()
            ctx.diags.add("A203", span, f"{upper} is one of the variables mcc reserves for temporaries "
                                        f"({', '.join(f'V{n}' for n in temps.pool)}) and this program needs it: "
                                        "the compiled code overwrites it; use V0-V59 or change "
                                        "[arcus] temporaries in the profile")
