"""Whole-program checks of an Arcus file: subroutine calls and comment style.

Per-statement checks (keywords, forms, operands, ranges) happen while resolving statements
(resolve.py) and block structure is checked while lowering (lower.py); these need the whole file.
"""

from __future__ import annotations

from mcc.compiler.arcus import syntax as st
from mcc.compiler.arcus.lower import Lowering
from mcc.compiler.diagnostics import Diagnostics, Severity


def check_calls(lowering: Lowering, diags: Diagnostics) -> None:
    """Every GOSUB n needs a SUB n in the file: the controller stops in error otherwise (L823)."""
    subs = lowering.program.subs
    missing: dict[int, list] = {}
    for call in lowering.program.calls:
        if call.valid and call.number not in subs:
            missing.setdefault(call.number, []).append(call)
    defined = ", ".join(str(n) for n in sorted(subs)) or "none"
    for number, calls in missing.items():
        first = calls[0]
        notes = (f"also called at line{'s' if len(calls) > 2 else ''} "
                 f"{', '.join(str(c.span.line) for c in calls[1:])}",) if len(calls) > 1 else ()
        diags.add("A106", first.number_span or first.span,
                  f"GOSUB {number}: there is no SUB {number} in this file (defined: {defined}); "
                  f"add SUB {number} ... ENDSUB after END", notes=notes)


def check_comments(tree: st.SyntaxTree, lowering: Lowering, diags: Diagnostics) -> None:
    """"'" comments are what the DXF converter writes (L1201); the language's comment is ';' (L1721)."""
    policy = str(lowering.profile.get("arcus.apostrophe_comments", "warn"))
    if policy == "ignore":
        return
    found = [c for c in tree.comments() if c.text.startswith("'")]
    if not found:
        return
    first = found[0]
    notes = (f"{len(found) - 1} more \"'\" comment{'s' if len(found) > 2 else ''} in this file",) if len(found) > 1 else ()
    diags.add("A127", first.span, "\"'\" starts a comment only in the DXF converter's output: the standalone "
                                  "language uses ';' (L1721); replace \"'\" by ';'", notes=notes,
              severity=Severity.ERROR if policy == "error" else None)
