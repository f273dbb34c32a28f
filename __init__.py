"""mcc: a compiler toolchain for motion-controller programs.

The repository root is this package; `mcc.compiler` holds the frontends, the IR and the checks,
`mcc.backends` the code generators, `mcc.cli` the command line and `mcc.grammars` the Lark files.
"""

__version__ = "0.1.0"
