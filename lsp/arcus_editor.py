"""The editor support of the Arcus PMX-4EX-SA (lsp/editor.py): a variable as a move target
(`XV2`), subroutine numbers after `GOSUB`, renaming subroutines and Vn, program memory in assembly
lines, and the editor model's indexer."""

from __future__ import annotations

import re

from mcc.lsp import catalog_info, model
from mcc.lsp.editor import Editor, Place

GOSUB = re.compile(r"^\s*GOSUB\s*(\d*)$", re.IGNORECASE)
# `XV2`, `X1000YV2`: a variable as a move target (arcus-pmx-4ex-sa.txt L2759 `XV10`, L2665 `UV10`)
MOVE_VARIABLE = re.compile(r"^\s*(?:[XYZU](?:[+-]?\d+|V\d+))*[XYZU](V\d*)$", re.IGNORECASE)
COMMAND = re.compile(r"^\s*([A-Za-z]+?)[XYZU]?(?:\s+|=|:)(.*)$")


class ArcusEditor(Editor):
    indexer = "mcc.lsp.arcus_index"
    places = (Place(MOVE_VARIABLE, (model.SYMBOL_VARIABLE,)), Place(GOSUB, (model.SYMBOL_SUBROUTINE,)))
    statement_start = re.compile(r"^\s*[A-Za-z]*$")
    prices_memory = True  # the compiled program in assembly lines (the backend's cost model)

    def word_start(self, before: str, start: int) -> int:
        """The axis letter before a variable is not part of it (`XV2` replaces from `V`)."""
        found = MOVE_VARIABLE.match(before)
        return found.start(1) if found is not None else start

    def allows(self, entry, place: str) -> bool:
        """What the catalog gives a pattern to (the statements the parser reads)."""
        return bool(entry.get("pattern"))

    def command_before(self, before: str):
        match = COMMAND.match(before)
        if match:
            return catalog_info.lookup("arcus", match.group(1)), match.group(2)
        return None, ""

    def validate_rename(self, snap, symbol: model.Symbol, new: str):
        from mcc.lsp.navigation import validate_numbered

        return validate_numbered(snap, symbol, new, routine_entry="SUB", variable_prefix="V")

    def memory(self, snap, listing, errors: tuple[int, ...]):
        from mcc.lsp.memory import by_source_lines

        return by_source_lines(snap, listing, "assembly lines", "asm_lines", "asm_budget", errors)


EDITOR = ArcusEditor()
