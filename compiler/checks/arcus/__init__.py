"""The semantic checks of Arcus PMX-4EX-SA (A1xx) over the whole file: one module per check,
`a<nnn>_<name>.py`, whose docstring is its code's page; importing this package registers them all.

The checks of one statement (keywords, forms, operands, ranges) are made while resolving it
(compiler/arcus/resolve.py) and the block structure while lowering (compiler/arcus/lower.py).
"""

from mcc.compiler.checks import discover, facts


facts("arcus", {
    "subroutine calls": lambda program: bool(program.lowering.program.calls),  # GOSUB n
    # the profile's arcus.apostrophe_comments is "warn" or "error" (docs/dialects/arcus.md)
    "apostrophe comments reported": lambda program: str(program.profile.get("arcus.apostrophe_comments",
                                                                             "warn")) != "ignore",
})

discover(__name__, __path__)
