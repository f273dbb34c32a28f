"""The simulator: run a program's IR on a virtual machine in virtual time (docs/SIMULATOR.md).

`simulate(module, scenario, options)` returns a `Trace`; `mcc sim` is its command line and
`mcc.sim.verify.compare` runs two modules on the same scenarios and names their first divergence.
"""

from mcc.sim.interpreter import ContractError, Options, simulate
from mcc.sim.scenario import Scenario, ScenarioError
from mcc.sim.trace import Trace

__all__ = ["ContractError", "Options", "Scenario", "ScenarioError", "Trace", "simulate"]
