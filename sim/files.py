"""Simulating a source file: check it, lower it, and run its IR (the work of `mcc sim`).

The no-traceback rule holds here as in the driver: an unexpected failure inside the simulator
becomes a G001 diagnostic on the file, and IR that breaks the contract is refused with S001.
"""

from __future__ import annotations

from dataclasses import dataclass

from mcc.compiler import driver, ir
from mcc.compiler.diagnostics import Diagnostics
from mcc.sim.interpreter import ContractError, Options, Simulator
from mcc.sim.scenario import Scenario
from mcc.sim.trace import Trace


@dataclass
class Simulated:
    result: driver.FileResult  # the checked file, with the simulator's diagnostics added
    trace: Trace | None  # None when the file has errors or its IR cannot be simulated


def simulate_module(module: ir.Module, path: str, scenario: Scenario | None, options: Options | None,
                    profile=None) -> tuple[Trace | None, Diagnostics]:
    """Run a module; problems come back as diagnostics, never as exceptions."""
    diags = Diagnostics()
    try:
        simulator = Simulator(module, scenario, options, profile)
    except ContractError as exc:
        diags.add("S001", exc.violation.span or driver.file_span(path),
                  f"cannot simulate: {exc}. The {module.dialect} frontend does not keep the IR contract "
                  "yet (see `mcc check --verify-ir`)")
        return None, diags
    try:
        trace = simulator.run()
    except Exception as exc:  # noqa: BLE001 - the no-traceback guarantee
        driver.internal_error(diags, path, exc, "simulating")
        return None, diags
    trace.path = path
    return trace, diags


def simulate_file(path: str, dialect: str | None = None, profile=None, scenario: Scenario | None = None,
                  options: Options | None = None, text: str | None = None) -> Simulated:
    result = driver.check_file(path, dialect, profile, text)
    module = result.analysis.module if result.analysis is not None else None
    if module is None or result.has_errors:
        return Simulated(result, None)
    prof = profile if profile is not None and profile.dialect == result.dialect else _default_profile(result)
    trace, diags = simulate_module(module, path, scenario, options, prof)
    if trace is not None:
        result.diagnostics = result.diagnostics + trace.diagnostics
        trace.diagnostics = list(result.diagnostics)
    result.diagnostics = result.diagnostics + diags.items
    return Simulated(result, trace)


def _default_profile(result: driver.FileResult):
    from mcc.compiler import dialects

    try:
        return driver.profile_for(dialects.get(result.dialect), None)
    except Exception:  # noqa: BLE001 - a profile is a refinement; the simulator runs without one
        return None


def sweep_file(path: str, dialect: str | None = None, profile=None, options: Options | None = None,
               text: str | None = None) -> tuple[driver.FileResult, list[tuple[str, Trace]]]:
    """Run a file over the scenarios `verify.default_scenarios` generates from it (every input it
    reads low, high, and toggling at the times its waits need): (the checked file, (scenario, trace)
    of each run). `mcc sim --sweep` reports the worst position of each axis (sim/cycles.py)."""
    import dataclasses

    from mcc.sim import verify

    result = driver.check_file(path, dialect, profile, text)
    module = result.analysis.module if result.analysis is not None else None
    if module is None or result.has_errors:
        return result, []
    prof = profile if profile is not None and profile.dialect == result.dialect else _default_profile(result)
    base = options or Options()
    runs = []
    for scenario in verify.default_scenarios(module, prof, options=dataclasses.replace(base, samples=False)):
        trace, diags = simulate_module(module, path, scenario, dataclasses.replace(base), prof)
        result.diagnostics = result.diagnostics + diags.items
        if trace is not None:
            runs.append((scenario.name or "scenario", trace))
    return result, runs
