"""The semantic checks of the X150/X150E (X1xx) over the whole program: one module per check,
`x<nnn>_<name>.py`, whose docstring is its code's page; importing this package registers them all.

They read the lowering's units (sequence definitions), transfer sites (XR, XG, GOSUB, ...) and
nesting depths. The checks of one command against the catalog (case, address, product, values,
text, what a sequence may store) are in compiler/x150/checks.py, the definition structure in
compiler/x150/structure.py and the local nesting in compiler/x150/lower.py (docs/decisions/0021).
What several checks share (the bytes a sequence stores, the call-nesting walk) is in helpers.py.
"""

from mcc.compiler.checks import discover, facts


facts("x150", {
    "sequences": lambda program: any(u.is_sequence and u.start is not None for u in program.lowering.units),
    "sequence transfers": lambda program: bool(program.lowering.sites),  # XR, XG, GOSUB, GOTO, XP, XFK, XWHEN
    "sequence calls": lambda program: any(s.kind == "call" and s.targets for s in program.lowering.sites),
})

discover(__name__, __path__)
