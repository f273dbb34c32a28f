"""What several passes share: structural keys that ignore spans, predecessors, and the rules for
what may observe or change a variable between two operations."""

from __future__ import annotations

import dataclasses
from enum import Enum

from mcc.compiler import ir

MAX_KEY_DEPTH = 200


_FIELDS: dict[type, tuple[str, ...]] = {}


def key(node, depth: int = 0):
    """A hashable structural key of an IR node that ignores spans (equal keys: same meaning).

    Numbers keep their type (`1` and `1.0` print differently and may mean different things on a
    device), so they never share a key."""
    if depth > MAX_KEY_DEPTH:
        return ("deep", id(node))  # never equal to another node: a pass simply does not match it
    kind = type(node)
    if kind is ir.Var:
        return ("Var", node.name)
    if kind is ir.Const:
        return ("Const", type(node.value).__name__, node.value, node.unit.value)
    if isinstance(node, Enum):
        return node.value
    if kind is tuple or kind is list:
        return tuple(key(n, depth + 1) for n in node)
    if isinstance(node, (int, float)):
        return (kind.__name__, node)
    names = _FIELDS.get(kind)
    if names is None:
        if not (dataclasses.is_dataclass(node) and not isinstance(node, type)):
            return node
        names = _FIELDS[kind] = tuple(f.name for f in dataclasses.fields(node) if f.name != "span")
    return (kind.__name__,) + tuple(key(getattr(node, name), depth + 1) for name in names)


def predecessors(module: ir.Module) -> dict[str, list[str]]:
    """Block label -> the labels of the blocks whose terminator can transfer to it."""
    preds: dict[str, list[str]] = {block.label: [] for _, block in module.blocks()}
    for _, block in module.blocks():
        for succ in ir.successors(block.terminator):
            preds.setdefault(succ, []).append(block.label)
    return preds


def reached(blocks: dict[str, ir.Block], roots: list[str]) -> set[str]:
    """The labels of `blocks` that a path from `roots` reaches along jumps and branches."""
    seen: set[str] = set()
    todo = list(roots)
    while todo:
        label = todo.pop()
        if label in seen or label not in blocks:
            continue
        seen.add(label)
        todo.extend(ir.successors(blocks[label].terminator))
    return seen


def referenced_labels(module: ir.Module) -> set[str]:
    """Labels named outside the CFG's edges: label values (`TP=100,K2`) and routine entries."""
    found: set[str] = set()
    for routine in module.routines:
        if routine.entry is not None:
            found.add(routine.entry.label)
    for _, block in module.blocks():
        exprs = [e for op in block.ops for e in ir.op_exprs(op)] + list(ir.term_exprs(block.terminator))
        for expr in exprs:
            for node in ir.walk_expr(expr):
                if isinstance(node, ir.LabelRef):
                    found.add(node.name)
    return found


def handler_writes(module: ir.Module) -> tuple[set[str], bool]:
    """Variables an event handler (or anything it calls) may assign, and whether one changes motion
    settings: a handler can run between any two operations, so these are never taken as known."""
    callees: dict[str, set[str]] = {r.name: set() for r in module.routines}
    writes: dict[str, set[str]] = {r.name: set() for r in module.routines}
    motion: dict[str, bool] = {r.name: False for r in module.routines}
    for routine in module.routines:
        for block in routine.blocks:
            for op in block.ops:
                if isinstance(op, ir.Assign):
                    writes[routine.name].add(op.target.name)
                elif isinstance(op, ir.Call):
                    callees[routine.name].add(op.routine)
                elif isinstance(op, (ir.SetMotion, ir.Native)):
                    motion[routine.name] = True
    variables: set[str] = set()
    changes_motion = False
    for routine in module.routines:
        if routine.kind is not ir.RoutineKind.HANDLER:
            continue
        stack, seen = [routine.name], set()
        while stack:
            name = stack.pop()
            if name in seen or name not in writes:
                continue
            seen.add(name)
            variables |= writes[name]
            changes_motion = changes_motion or motion[name]
            stack.extend(callees[name])
    return variables, changes_motion


def clobbers_everything(op) -> bool:
    """An operation after which no variable's value is known: a call (the callee may assign any
    variable), a native command (its effect is not modelled) or a pause (the host may send commands
    while the program waits, MCode L4935)."""
    return isinstance(op, (ir.Call, ir.Native, ir.Pause))


def assigned(op) -> str | None:
    return op.target.name if isinstance(op, ir.Assign) else None
