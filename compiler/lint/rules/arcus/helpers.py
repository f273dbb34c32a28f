"""What several Arcus rules (A3xx) share. The IR of an Arcus program is neutral (Move, Slew for
JOG, Home, Arc, Stop, WaitMotion per axis, SetMotion for HSPD/LSPD/ACC/SCV, Setting for
SSPD/SYN.../EO, Status readings); what stays `Native("arcus", <spelling>)` (SSPDM) is recognised
through the catalog's patterns (`keyword`).
"""

from __future__ import annotations

from functools import lru_cache

from mcc.compiler import ir
from mcc.compiler.arcus import catalog as acat
from mcc.compiler.lint import flow


ARCUS = "arcus"
MOTION = (ir.Move, ir.Slew, ir.Home, ir.Arc)
SETTING_KEYWORDS = {"speed_change": "SSPD", "compare_output": "SYNO"}  # neutral settings the rules follow


@lru_cache(maxsize=1)
def catalog() -> acat.ArcusCatalog:
    return acat.load()


def keyword(op) -> tuple[str, str]:
    """(catalog name, axis) of an operation the rules follow: `SSPDMX` -> ("SSPDM", "X"), the
    setting speed_change on X -> ("SSPD", "X"), compare_output on X -> ("SYNO", "X") (its value
    says on or off), SCVX=1 -> ("SCV", "X"), EO -> ("EO", ...)."""
    if isinstance(op, ir.Setting) and op.name in SETTING_KEYWORDS:
        return SETTING_KEYWORDS[op.name], op.axis
    if isinstance(op, ir.Setting) and op.name == "enable_outputs" or isinstance(op, ir.DriveEnable):
        return "EO", op.axis
    if isinstance(op, ir.SetMotion) and op.param is ir.MotionParam.PROFILE:
        return "SCV", op.axis
    if not isinstance(op, ir.Native) or op.dialect != ARCUS:
        return "", ""
    found = catalog().match(op.mnemonic.upper())
    return (found.keyword.name, found.axis) if found is not None else ("", "")


def const(expr) -> int | None:
    return int(expr.value) if isinstance(expr, ir.Const) else None


def argument(op) -> ir.Expr | None:
    """The value an operation writes (a setting's value, a Native's first argument)."""
    if isinstance(op, (ir.Setting, ir.SetMotion)):
        return op.value
    if isinstance(op, ir.DriveEnable):
        return op.on
    args = getattr(op, "args", ())
    return args[0] if args else None


def keywords_in(module: ir.Module) -> set[str]:
    """The catalog names of the module's operations (`keyword`). A rule about keywords the program
    never uses has nothing to find: it skips its walk of every routine (the editor server runs the
    rules on every keystroke; a 3,000-line program may use no SCV, SSPDM or SYNO at all)."""
    return {keyword(op)[0] for _, _, op in flow.ops(module)}


def forward_all(module: ir.Module, transfer, join=frozenset.union, entry=frozenset()):
    """(routine, item, state before it) for every reachable operation and terminator."""
    for routine in module.routines:
        states = flow.forward(routine, entry, transfer, join)
        for block in routine.blocks:
            if block.label in states:
                for item, state in flow.replay(block, states[block.label], transfer):
                    yield routine, item, state


def switch_state(name_on: str, name_off: str | None, on_value=lambda v: v != 0):
    """A transfer function tracking the axes where a setting may be on."""

    def transfer(on: frozenset, item) -> frozenset:
        name, axis = keyword(item)
        if name == name_on:
            value = const(argument(item))
            if value is None or on_value(value):
                return on | {axis}
            return on - {axis}
        if name_off is not None and name == name_off:
            return on - {axis}
        return on

    return transfer
