"""Go to definition, find references, document highlight and rename, over the symbols of the
editor model (labels, variables, subroutines, sequences)."""

from __future__ import annotations

import re

from lsprotocol import types as t

from mcc.lsp import catalog_info, model
from mcc.lsp.convert import range_of


class RenameError(Exception):
    """A new name that the dialect does not allow or that is taken; the message says why."""


def definition(snap, offset: int) -> list[t.Location]:
    symbol = snap.index.symbol_at(offset)
    if symbol is None:
        return []
    return [t.Location(snap.uri, range_of(span)) for span in symbol.definitions]


def references(snap, offset: int, include_declaration: bool) -> list[t.Location]:
    symbol = snap.index.symbol_at(offset)
    if symbol is None:
        return []
    spans = (symbol.definitions if include_declaration else []) + symbol.references
    return [t.Location(snap.uri, range_of(span)) for span in sorted(spans, key=lambda s: s.start)]


def highlight(snap, offset: int) -> list[t.DocumentHighlight]:
    symbol = snap.index.symbol_at(offset)
    if symbol is None:
        return []
    out = [t.DocumentHighlight(range=range_of(s), kind=t.DocumentHighlightKind.Write) for s in symbol.definitions]
    out += [t.DocumentHighlight(range=range_of(s), kind=t.DocumentHighlightKind.Read) for s in symbol.references]
    return out


def prepare_rename(snap, offset: int) -> t.PrepareRenamePlaceholder | None:
    token = snap.index.token_at(offset)
    if token is None or not token.symbol:
        return None
    symbol = snap.index.symbols[token.symbol]
    return t.PrepareRenamePlaceholder(range=range_of(token.span), placeholder=symbol.name)


def rename(snap, offset: int, new_name: str) -> t.WorkspaceEdit | None:
    symbol = snap.index.symbol_at(offset)
    if symbol is None:
        return None
    new_key, replace = validate(snap, symbol, new_name.strip())
    if new_key == symbol.key:
        return t.WorkspaceEdit(changes={snap.uri: []})
    edits = []
    for span in sorted(symbol.definitions + symbol.references, key=lambda s: s.start):
        old = snap.source.text[span.start:span.end]
        edits.append(t.TextEdit(range=range_of(span), new_text=replace(old)))
    return t.WorkspaceEdit(changes={snap.uri: edits})


def validate(snap, symbol: model.Symbol, new: str):
    """(the renamed symbol's key, a function from the old text of one occurrence to its new text),
    or RenameError with the reason: the dialect's editor knows its naming rules (lsp/editor.py)."""
    from mcc.lsp.editor import editor_of

    return editor_of(snap.dialect).validate_rename(snap, symbol, new)


def validate_numbered(snap, symbol: model.Symbol, new: str, routine_entry: str, variable_prefix: str):
    """`validate` for a dialect whose routines and variables are numbers: a routine number within the
    range of the catalog's `routine_entry` (Arcus SUB, X150 XD), a variable `variable_prefix` and a
    number within the catalog's index of that entry (Arcus V, X150 VAR)."""
    dialect = snap.dialect
    if symbol.kind in (model.SYMBOL_SUBROUTINE, model.SYMBOL_SEQUENCE):
        number = parse_number(new, "", f"a {symbol.kind} is a number")
        entry = catalog_info.lookup(dialect, routine_entry)
        low, high = entry.range if entry is not None and entry.range else (0, 2 ** 31)
        if not low <= number <= high:
            raise RenameError(f"{symbol.kind} numbers go from {low} to {high}; {number} is out of range")
        key = f"{symbol.kind}:{number}"
        taken(snap, symbol, key)
        return key, lambda old: re.sub(r"\d+", str(number), old, count=1)
    prefix = variable_prefix
    number = parse_number(new, prefix, f"a variable is {prefix} and its number ({prefix}5)")
    entry = catalog_info.lookup(dialect, prefix)
    index = entry.get("index") if entry is not None else None
    low, high = (index if isinstance(index, list) else (entry.range if entry and entry.range else (0, 2 ** 31)))
    if not low <= number <= high:
        raise RenameError(f"{prefix} variables go from {prefix}{low} to {prefix}{high}; {prefix}{number} does not exist")
    key = f"variable:{prefix}{number}"
    taken(snap, symbol, key)
    return key, lambda old: re.sub(r"\d+", str(number), old, count=1)


def parse_number(new: str, prefix: str, rule: str) -> int:
    match = re.fullmatch(rf"(?i)(?:{prefix})?\s*(\d+)" if prefix else r"(\d+)", new)
    if match is None:
        raise RenameError(f"'{new}' is not a valid name here: {rule}")
    return int(match.group(1))


def taken(snap, symbol: model.Symbol, key: str) -> None:
    other = snap.index.symbols.get(key)
    if other is not None and other.key != symbol.key and (other.definitions or other.references):
        where = other.definitions[0] if other.definitions else other.references[0]
        raise RenameError(f"{other.label} already exists (line {where.line}): renaming would merge two "
                          f"{other.kind}s; choose another")
