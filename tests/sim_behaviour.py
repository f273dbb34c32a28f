"""The one behavioural oracle of the tests: `same_behaviour(before, after)` runs both modules in the
simulator (mcc.sim) and asserts that they do the same things.

It replaces the small interpreters the Arcus and optimizer tests had. Both modules run on the
default scenarios of `before` (every input it reads low, high, and pulsing on its own; the first
`MAX_SCENARIOS`), and their traces are compared with `verify.STRICT`: moves and their ends, arcs,
slews, stops, homing, position changes, outputs, prints, limit hits, runtime errors, native
commands, handlers installed and removed and the drive switched, in order and in time (within the
verification tolerance), then why each run stopped and where the axes and outputs ended. Calls,
returns and assignments are not compared (outlining adds calls; a host reading variables is the
documented assumption of -O2's dead stores). A run cut by the step limit (a loop that never waits)
is compared on the events both made.
"""

from __future__ import annotations

from mcc.compiler import ir
from mcc.sim import Options
from mcc.sim.verify import STRICT, compare, default_scenarios

MAX_SCENARIOS = 4
OPTIONS = Options(until=60, max_steps=20_000, samples=False)


def same_behaviour(before: ir.Module, after: ir.Module, scenarios=None, options: Options | None = None) -> None:
    """Assert that `after` (optimized, compiled, read back) behaves as `before` does."""
    chosen = scenarios if scenarios is not None else default_scenarios(before, options=options or OPTIONS)[:MAX_SCENARIOS]
    found = compare(before, after, chosen, options or OPTIONS, kinds=STRICT, by_count=True)
    if found is not None:
        from mcc.compiler.ir_print import to_text

        raise AssertionError(f"{found}\n--- before:\n{to_text(before)}\n--- after:\n{to_text(after)}")

