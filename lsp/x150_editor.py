"""The editor support of the X150 (lsp/editor.py): the device address before a command, sequence
numbers after `XR`/`XG`/..., the commands a sequence may hold, snippets with the value glued to the
mnemonic, renaming sequences and VARn, bytes per stored sequence, and the editor model's indexer."""

from __future__ import annotations

import re

from mcc.lsp import catalog_info, model
from mcc.lsp.editor import Editor, Place

SEQUENCE = re.compile(r"(?:^|\s)\d*(?:XRP|XR|XG|XE|XU|GOSUB|GOTO)\s*(\d*)$", re.IGNORECASE)
ADDRESSED = re.compile(r"^\d+(?=[A-Za-z])")  # `1D`, `12XR`: the device address before a command
COMMAND = re.compile(r"(?:^|\s)\d*B?([A-Za-z]+)([^\s]*)$")


class X150Editor(Editor):
    indexer = "mcc.lsp.x150_index"
    places = (Place(SEQUENCE, (model.SYMBOL_SEQUENCE,), start_group=1),)  # the number after `1XR`
    statement_start = re.compile(r"(?:^|\s)\d*(B?[A-Za-z]*)$")  # the command after its device address
    statement_group = 1  # after the device address (`1` typed alone: nothing to replace)
    statement_symbols = False
    prices_memory = True  # each sequence is stored as bytes, one per character and delimiter (L241)

    def word_start(self, before: str, start: int) -> int:
        found = ADDRESSED.match(before[start:])
        return start + found.end() if found is not None else start

    def command_place(self, snap, line: int) -> str:
        inside = any(r.kind == "sequence" and r.span.line < line + 1 < r.span.end_line for r in snap.index.routines)
        return "sequence" if inside else "immediate"

    def allows(self, entry, place: str) -> bool:
        """Inside a sequence, only what the catalog marks storable (`seq` S)."""
        return place != "sequence" or entry.get("seq", "S") == "S"

    def snippet(self, entry) -> tuple[str, str]:
        """X150 writes the value glued to the mnemonic: <a>D<s>n, <a>XRn, <a>VARn."""
        syntax = (entry.syntax[0] if entry.syntax else entry.name).replace("<a>", "")
        body = syntax[len(entry.name):] if syntax.upper().startswith(entry.name.upper()) else ""
        if entry.get("arg", "none") in ("none", "") or not body:
            return entry.name, syntax
        return entry.name + "${1:" + catalog_info.escape(body.replace("<s>", "±")) + "}", syntax

    def command_before(self, before: str):
        """The longest catalog mnemonic that starts the word before the cursor, after its address."""
        match = COMMAND.search(before)
        if match:
            word = match.group(1).upper()
            for size in range(len(word), 0, -1):
                entry = catalog_info.lookup("x150", word[:size])
                if entry is not None:
                    return entry, word[size:] + match.group(2)
        return None, ""

    def validate_rename(self, snap, symbol: model.Symbol, new: str):
        from mcc.lsp.navigation import validate_numbered

        return validate_numbered(snap, symbol, new, routine_entry="XD", variable_prefix="VAR")

    def memory(self, snap, listing, errors: tuple[int, ...]):
        """Bytes per sequence as the X150 writer stores them (the figures of `mcc compile`)."""
        from mcc.backends.x150.writer import write
        from mcc.compiler import dialects, driver
        from mcc.compiler.x150 import naming
        from mcc.lsp.memory import RoutineUsage, Usage, routine_errors

        result = Usage("bytes", int(listing.stats.get("sequence_bytes", 0)),
                       int(listing.stats.get("sequence_budget", 0)), error_lines=errors)
        try:
            stored = write(snap.module, driver.profile_for(dialects.get(snap.dialect), snap.profile)).sequence_bytes
        except Exception:  # noqa: BLE001
            return result
        by_key: dict[tuple[int, int | None], int] = {}
        for name, size in stored.items():
            number = naming.sequence_number(name)
            if number is not None:
                key = (number, naming.device_of(name))
                by_key[key] = by_key.get(key, 0) + size
        for routine in sorted(snap.index.routines, key=lambda r: r.span.line):
            if routine.kind != "sequence":
                continue
            number = int(routine.symbol.split(":")[1])
            device = routine.name.rsplit("device ", 1)[1].rstrip(")") if "(device " in routine.name else None
            used = by_key.get((number, int(device) if device else None), 0)
            result.routines.append(RoutineUsage(routine.name, routine.span.line, used,
                                                routine_errors(snap, routine.name, result.error_lines)))
        return result


EDITOR = X150Editor()
