"""The launch request: check the program, load the scenario and the profile, make the simulator.

The same steps as `mcc sim` (sim/files.py), stopping before the run: a program with errors, a
malformed scenario or an unknown profile refuses the launch with the reasons, never a traceback.
Launch arguments (launch.json): program (required), scenario (a TOML file, docs/SIMULATOR.md),
profile, dialect, until (virtual seconds, default the scenario's or 60), maxSteps, stopOnEntry,
cwd (what relative paths are relative to).
"""

from __future__ import annotations

import os

DEFAULT_UNTIL = 60.0


class LaunchError(Exception):
    def __init__(self, message: str, details: list[str] | None = None):
        super().__init__(message)
        self.details = details or []


def prepare(args: dict):
    """(simulator, absolute program path) for the launch arguments `args`."""
    from mcc.compiler import driver, profiles
    from mcc.sim import scenario as scenario_mod
    from mcc.sim.files import _default_profile
    from mcc.sim.interpreter import ContractError, Options, Simulator

    cwd = str(args.get("cwd") or os.getcwd())
    program = args.get("program")
    if not program or not isinstance(program, str):
        raise LaunchError("launch needs \"program\": the file to debug")
    path = os.path.abspath(os.path.join(cwd, os.path.expanduser(program)))
    if not os.path.isfile(path):
        raise LaunchError(f"no program file '{path}'")
    profile = None
    if args.get("profile"):
        try:
            profile = profiles.load(str(args["profile"]))
        except profiles.ProfileError as exc:
            raise LaunchError(f"profile: {exc}") from None
    scenario = None
    if args.get("scenario"):
        try:
            scenario = scenario_mod.load(os.path.join(cwd, os.path.expanduser(str(args["scenario"]))))
        except scenario_mod.ScenarioError as exc:
            raise LaunchError(f"scenario: {exc}") from None
    dialect = args.get("dialect") or None
    result = driver.check_file(path, dialect, profile)
    errors = [d for d in result.diagnostics if d.severity.value == "error"]
    module = result.analysis.module if result.analysis is not None else None
    if errors or module is None:
        details = [f"{os.path.basename(path)}:{d.span.line}:{d.span.column}: {d.code} {d.message}" for d in errors]
        raise LaunchError(f"{os.path.basename(path)} has {len(errors)} error(s); fix them first: "
                          + "; ".join(details[:3]), details)
    prof = result.profile if result.profile is not None else _default_profile(result)
    until = args.get("until")
    if until is None:
        until = scenario.until if scenario is not None and scenario.until is not None else DEFAULT_UNTIL
    try:
        options = Options(until=float(until), max_steps=int(args.get("maxSteps", 1_000_000)),
                          skip_rounds=False)  # every round runs, so a breakpoint in a loop sees each one
        simulator = Simulator(module, scenario, options, prof)
    except (TypeError, ValueError) as exc:
        raise LaunchError(f"until/maxSteps: {exc}") from None
    except ContractError as exc:
        raise LaunchError(f"cannot simulate: {exc}") from None
    simulator.trace.path = path
    return simulator, path
