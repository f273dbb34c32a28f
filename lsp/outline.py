"""Document symbols (the outline), workspace symbols and folding ranges."""

from __future__ import annotations

from lsprotocol import types as t

from mcc.lsp import model
from mcc.lsp.convert import range_of

KINDS = {"program": t.SymbolKind.Module, "label": t.SymbolKind.Function, "subroutine": t.SymbolKind.Function,
         "sequence": t.SymbolKind.Function, "variable": t.SymbolKind.Variable}


def document_symbols(snap) -> list[t.DocumentSymbol]:
    out = [routine_symbol(r) for r in snap.index.routines]
    covered = {r.symbol for r in walk(snap.index.routines)}
    for symbol in snap.index.symbols.values():
        if symbol.key in covered or not symbol.definitions:
            continue
        if symbol.kind == model.SYMBOL_VARIABLE:
            span = symbol.definitions[0]
            out.append(t.DocumentSymbol(name=symbol.name, kind=t.SymbolKind.Variable, range=range_of(span),
                                        selection_range=range_of(span), detail="variable"))
    return sorted(out, key=lambda s: (s.range.start.line, s.range.start.character))


def walk(routines):
    for routine in routines:
        yield routine
        yield from walk(routine.children)


def routine_symbol(routine: model.Routine) -> t.DocumentSymbol:
    return t.DocumentSymbol(
        name=routine.name, kind=KINDS.get(routine.kind, t.SymbolKind.Function), detail=routine.kind,
        range=range_of(routine.span), selection_range=range_of(routine.selection),
        children=[routine_symbol(c) for c in routine.children] or None)


def workspace_symbols(snaps, query: str) -> list[t.SymbolInformation]:
    query = query.lower()
    out = []
    for snap in snaps:
        for routine in walk(snap.index.routines):
            if query in routine.name.lower():
                out.append(t.SymbolInformation(name=routine.name, kind=KINDS.get(routine.kind, t.SymbolKind.Function),
                                               location=t.Location(snap.uri, range_of(routine.selection)),
                                               container_name=snap.path.rsplit("/", 1)[-1]))
        for symbol in snap.index.symbols.values():
            if symbol.kind == model.SYMBOL_VARIABLE and symbol.definitions and query in symbol.name.lower():
                out.append(t.SymbolInformation(name=symbol.name, kind=t.SymbolKind.Variable,
                                               location=t.Location(snap.uri, range_of(symbol.definitions[0])),
                                               container_name=snap.path.rsplit("/", 1)[-1]))
    return out


def folding_ranges(snap) -> list[t.FoldingRange]:
    out = []
    for first, last, kind in sorted(set(snap.index.folds)):
        out.append(t.FoldingRange(start_line=first - 1, end_line=last - 1,
                                  kind=t.FoldingRangeKind.Comment if kind == "comment" else t.FoldingRangeKind.Region))
    return out
