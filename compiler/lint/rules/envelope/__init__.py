"""The machine's envelope, one rule per question (issue 27, docs/LINT.md "Envelope"): does a move
leave the travel (G301), is a speed or acceleration above the mechanics' limit (G302), does a
relative move repeat in a loop whose count nothing bounds (G303), does an axis move before it is
homed when it must be (G304). Each reads the envelope of `[tool.mcc.axes]` and the profile's
`[envelope]` (compiler/envelope/axes.py) and the interval analysis of compiler/envelope/intervals.py
(helpers.py); without an envelope they report nothing. They are the same for every dialect, and
`rules.load` imports this package for every dialect.
"""

from mcc.compiler.lint.rules import discover

discover(__name__, __path__)
