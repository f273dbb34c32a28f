"""The semantic checks of Lexium MCode (M1xx) over the whole file: one module per check,
`m<nnn>_<name>.py`, whose docstring is its code's page; importing this package registers them all.

They read the lowering's tables (label references, the name table) and the IR; the checks of one
statement against the catalog are made while resolving it (compiler/mcode/resolve.py), the program
regions while lowering (compiler/mcode/lower.py). What several checks share is in helpers.py.
"""

from mcc.compiler import ir
from mcc.compiler.checks import Program, discover, facts
from mcc.compiler.checks.mcode.helpers import line_limit


def _names(program: Program) -> bool:
    names = program.lowering.resolver.names
    return bool(names.labels or names.variables)


def _long_lines(program: Program) -> bool:
    text = program.source.text
    limit = line_limit(program)
    return len(text) > limit and max(map(len, text.split("\n"))) > limit


def _subroutines(program: Program) -> bool:
    return any(r.kind in (ir.RoutineKind.SUBROUTINE, ir.RoutineKind.HANDLER) for r in program.module.routines)


facts("mcode", {
    "label references": lambda program: bool(program.lowering.label_refs),  # BR, CL, EX, OE, trips
    "user names": _names,  # labels or variables
    "long lines": _long_lines,  # a line longer than the profile's limits.line_length
    "subroutines": _subroutines,  # a subroutine or handler a program could run into
    # the profile's mcode.comment_line_policy is "warn" or "error" (docs/dialects/mcode.md)
    "comment overflow reported": lambda program: program.profile.get("mcode.comment_line_policy", "warn") != "ignore",
})

discover(__name__, __path__)
