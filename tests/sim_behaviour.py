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

from dataclasses import dataclass, field

from mcc.compiler import ir
from mcc.sim import Options
from mcc.sim.verify import STRICT, Runs, compare, default_scenarios

MAX_SCENARIOS = 4
OPTIONS = Options(until=60, max_steps=20_000, samples=False)


@dataclass
class Baseline:
    """What `same_behaviour` works out about one `before` module, kept by a test that compares it
    with many modules (every level and pass): its scenarios and its runs (verify.Runs), so that
    it is simulated once per scenario, not once per comparison. Only for a module that does not
    change meanwhile (the tests optimize copies)."""

    module: ir.Module
    scenarios: list = field(default_factory=list)
    runs: Runs | None = None


def same_behaviour(before: ir.Module, after: ir.Module, scenarios=None, options: Options | None = None,
                   baseline: Baseline | None = None) -> None:
    """Assert that `after` (optimized, compiled, read back) behaves as `before` does."""
    if baseline is not None and (baseline.module is not before or scenarios is not None or options is not None):
        raise ValueError("a Baseline is for its own module with the default scenarios and options")
    if baseline is not None and not baseline.scenarios:
        baseline.scenarios = default_scenarios(before, options=OPTIONS)[:MAX_SCENARIOS]
        baseline.runs = Runs(before, None)
    chosen = baseline.scenarios if baseline is not None else scenarios if scenarios is not None else \
        default_scenarios(before, options=options or OPTIONS)[:MAX_SCENARIOS]
    found = compare(before, after, chosen, options or OPTIONS, kinds=STRICT, by_count=True,
                    source_runs=baseline.runs if baseline is not None else None)
    if found is not None:
        from mcc.compiler.ir_print import to_text

        raise AssertionError(f"{found}\n--- before:\n{to_text(before)}\n--- after:\n{to_text(after)}")

