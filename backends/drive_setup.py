"""Drive set-up that a target configures outside the program, or does not have (issue 24,
docs/decisions/0019-drive-setup-dropped.md).

Some settings act only on the drive's hardware: MCode's motor run and hold currents (`RC`, `HC`,
lexium-mcode.txt L5134, L3077), X150's operator-panel key enables on a target without a panel. The
X150 and the PMX-4EX-SA set the motor current on the drive, outside the program, and nothing a
program does (motion, outputs, prints, variables, timing) depends on it. Such a setting is marked
`drive_only` in `ir_names.SETTINGS`; in a conversion to a dialect that has no such setting it is
left out with a warning (G051) on its line, and the output lists it in a comment at its top, so the
user sets the target drive up by hand. `[tool.mcc] cross.drop-drive-setup = false`
(docs/CONFIGURATION.md) keeps the old refusal: the setting goes to the backend, which refuses it.

A program that reads such a setting back (`PR RC`) keeps it: the reading would change. The pass
works on a copy of the module, run before the backend (compiler/driver.py), so the source's module,
which the validation simulates, keeps every setting.
"""
from __future__ import annotations

from dataclasses import dataclass

from mcc.compiler import ir
from mcc.compiler.ir_names import SETTINGS
from mcc.compiler.span import Span

CODE = "G051"


@dataclass(frozen=True)
class Dropped:
    """One setting left out: its name, the source line and what the line set."""

    name: str
    span: Span | None
    meaning: str

    @property
    def line(self) -> int:
        return self.span.line if self.span is not None else 0


def droppable(name: str, target: str) -> bool:
    """Whether the setting `name` is drive set-up only and `target` has no statement for it."""
    info = SETTINGS.get(name)
    return info is not None and info.drive_only and target not in info.dialects


def _read_back(module: ir.Module) -> set[str]:
    """The settings the program reads back as a value (`Status(name)`): those stay."""
    names: set[str] = set()
    for _, block in module.blocks():
        exprs = [e for op in block.ops for e in ir.op_exprs(op)] + list(ir.term_exprs(block.terminator))
        for expr in exprs:
            for node in ir.walk_expr(expr):
                if isinstance(node, ir.Status) and node.meaning in SETTINGS:
                    names.add(node.meaning)
    return names


def drop(module: ir.Module, target: str) -> tuple[ir.Module, list[Dropped]]:
    """`module` without the drive set-up `target` has no statement for, and what was left out.
    The module itself is returned unchanged when there is nothing to leave out."""
    kept_names = _read_back(module)

    def leaves(op: ir.Op) -> bool:
        return isinstance(op, ir.Setting) and op.name not in kept_names and droppable(op.name, target)

    if not any(leaves(op) for _, block in module.blocks() for op in block.ops):
        return module, []
    dropped: list[Dropped] = []
    work = ir.copy_module(module)
    for _, block in work.blocks():
        kept = []
        for op in block.ops:
            if leaves(op):
                dropped.append(Dropped(op.name, op.span, SETTINGS[op.name].meaning))
            else:
                kept.append(op)
        block.ops[:] = kept
    return work, dropped


def message(item: Dropped, target_title: str) -> str:
    """The G051 warning for one setting left out."""
    return (f"the setting '{item.name}' ({item.meaning}) only sets up the drive, which {target_title} sets up "
            "outside the program or does not have: it is left out and listed at the top of the output; where the "
            "target drive has it (a motor current), set it up there by hand; set `cross.drop-drive-setup = false` "
            "in [tool.mcc] to refuse the program instead")


def comment_lines(dropped: list[Dropped], comment: str) -> list[str]:
    """The comment lines that list what was left out, for the top of the output."""
    if not dropped:
        return []
    lines = [f"{comment} drive set-up left out, set it on the drive (G051):"]
    for item in dropped:
        lines.append(f"{comment}   line {item.line}: {item.name}")
    return lines


def with_comments(listing, dropped: list[Dropped], comment: str) -> None:
    """Insert the list of what was left out after the comment lines that head `listing` (the
    backend's own statement of its assumptions)."""
    from mcc.backends.listing import ListingLine

    lines = comment_lines(dropped, comment)
    if not lines:
        return
    at = 0
    while at < len(listing.lines) and listing.lines[at].text.startswith(comment):
        at += 1
    spans = [()] + [(item.span,) if item.span is not None else () for item in dropped]
    listing.lines[at:at] = [ListingLine(text, sources) for text, sources in zip(lines, spans)]
