"""The optimizer: IR-to-IR passes that make programs smaller and never change what they do.

`optimize(module, level, profile)` runs the passes of an optimization level (`O0`, `O1`, `O2`,
`Os`) or an explicit list, and returns the statistics per pass. docs/OPTIMIZER.md describes each
pass, what it assumes and an example.
"""

from mcc.compiler.opt.manager import LEVELS, PASSES, OptStats, optimize, pass_names

__all__ = ["LEVELS", "PASSES", "OptStats", "optimize", "pass_names"]
