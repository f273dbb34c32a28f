"""Completion and signature help.

What is offered depends on where the cursor is, read from the text of the current line: a label
where an MCode command takes one (`BR x`, `CL x`, `TI 1,x`, `TT=0.5,x`, `OE=x`, ...), a condition
after `BR x,`/`CL x,` (variables, flags and inputs, lexium-mcode.txt L1807, L2124), a subroutine
number after `GOSUB` (Arcus), a sequence number after `XR`/`XG`/... (X150), a command at the start
of a statement (as a snippet from the catalog's syntax, only what the target product has, and only
what the program region allows), variables and readable registers elsewhere. This module is
written once; what differs by dialect (the places, where a statement starts, which commands a
place allows, snippets, the command before the cursor) is the dialect's Editor's
(lsp/<dialect>_editor.py, lsp/editor.py).

Every item carries the range it replaces (a `textEdit`): the word being typed as the dialect reads
it, not as the editor's word pattern does. An X150 device address (`1D`, `2G`) and an Arcus axis
letter before a variable (`XV2`) are not part of it, nor what stands before `,` or `=`; without the
range an editor filters the items by `1D` or `XV2` and shows none.
"""

from __future__ import annotations

import re

from lsprotocol import types as t

from mcc.lsp import catalog_info, model
from mcc.lsp.editor import editor_of


def complete(snap, line_text: str, character: int, line: int) -> t.CompletionList:
    before = line_text[:character]
    editor = editor_of(snap.dialect)
    items: list[t.CompletionItem] = []
    start = word_start(snap.dialect, before)
    place = next((p for p in editor.places if p.pattern.search(before)
                  and not (p.outside_comment and in_comment(snap, before))), None)
    statement = editor.statement_start.search(before) if editor.statement_start is not None else None
    if place is not None:
        items = [item for kind in place.symbols for item in symbols(snap, kind)] + (values(snap) if place.values else [])
        if place.start_group is not None:
            start = place.pattern.search(before).start(place.start_group)  # the number after `1XR`
    elif statement is not None and not in_comment(snap, before):
        items = commands(snap, line) + (symbols(snap, model.SYMBOL_VARIABLE) if editor.statement_symbols else [])
        if editor.statement_group is not None:
            start = statement.start(editor.statement_group)  # after the device address
    elif not in_comment(snap, before):
        items = symbols(snap, model.SYMBOL_VARIABLE) + values(snap)
    replaced = t.Range(t.Position(line, start), t.Position(line, character))
    return t.CompletionList(is_incomplete=False, items=[with_range(item, replaced) for item in items])


TRAILING_WORD = re.compile(r"[A-Za-z0-9_]*$")


def word_start(dialect: str, before: str) -> int:
    """The column where the word being typed starts: the items replace from there to the cursor
    (the dialect's editor moves it past what is not part of the word: a device address, an axis)."""
    start = len(before) - len(TRAILING_WORD.search(before).group(0))
    return editor_of(dialect).word_start(before, start)


def with_range(item: t.CompletionItem, replaced: t.Range) -> t.CompletionItem:
    """A copy of `item` that replaces `replaced` (the word being typed) with its text. No
    `filterText`: LSP filters by the label then, which is what it would say; and Neovim's
    omnifunc (0.7, the Debian package the editor test runs) takes the start of the replaced
    range from the items' `textEdit` only for items without one, else from its own word pattern
    (`1D`, `XV2`: the whole), and then drops every item (tests/editors/test_neovim_completion.py)."""
    return t.CompletionItem(**{**{f: getattr(item, f) for f in FIELDS},
                               "text_edit": t.TextEdit(range=replaced, new_text=item.insert_text or item.label)})


FIELDS = ("label", "kind", "detail", "documentation", "insert_text", "insert_text_format", "sort_text")


def in_comment(snap, before: str) -> bool:
    from mcc.compiler.lint.suppress import comment_start, markers

    return comment_start(before, markers(snap.dialect)) is not None


def symbols(snap, kind: str) -> list[t.CompletionItem]:
    out = []
    for symbol in snap.index.symbols.values():
        if symbol.kind != kind:
            continue
        where = f"line {symbol.definitions[0].line}" if symbol.definitions else "not defined here"
        out.append(t.CompletionItem(
            label=symbol.name, kind=t.CompletionItemKind.Variable if kind == model.SYMBOL_VARIABLE
            else t.CompletionItemKind.Reference,
            detail=f"{symbol.kind} ({where}, used {len(symbol.references)}×)",
            sort_text=f"0{symbol.name}"))
    return out


def allowed_here(snap, entry, place: str) -> bool:
    ok, _ = catalog_info.availability(entry, snap.profile)
    if not ok or entry.kind in catalog_info.UNAVAILABLE_KINDS:
        return False
    return editor_of(snap.dialect).allows(entry, place)


def commands(snap, line: int) -> list[t.CompletionItem]:
    """The commands allowed at `line`; the items depend only on the dialect, the profile and the
    kind of place (the dialect's editor says which: a program region, a sequence), so they are
    built once per combination."""
    place = editor_of(snap.dialect).command_place(snap, line)
    key = (snap.dialect, getattr(snap.profile, "name", ""), getattr(snap.profile, "product", ""),
           getattr(snap.profile, "firmware", ""), place)
    found = COMMAND_ITEMS.get(key)
    if found is None:
        found = COMMAND_ITEMS[key] = build_commands(snap, place)
    return list(found)


COMMAND_ITEMS: dict[tuple, list[t.CompletionItem]] = {}


def build_commands(snap, place: str) -> list[t.CompletionItem]:
    out = []
    editor = editor_of(snap.dialect)
    for entry in catalog_info.entries(snap.dialect):
        if not allowed_here(snap, entry, place):
            continue
        text, syntax = editor.snippet(entry)
        out.append(t.CompletionItem(
            label=entry.name, kind=t.CompletionItemKind.Function if entry.kind in ("instruction", "motion")
            else t.CompletionItemKind.Keyword,
            detail=f"{entry.title} — {syntax}",
            documentation=t.MarkupContent(kind=t.MarkupKind.Markdown,
                                          value=catalog_info.hover_markdown(entry, snap.profile)),
            insert_text=text, insert_text_format=t.InsertTextFormat.Snippet,
            sort_text=f"1{entry.name}"))
    return out


def values(snap) -> list[t.CompletionItem]:
    kinds = editor_of(snap.dialect).value_kinds
    out = []
    for entry in catalog_info.entries(snap.dialect):
        if kinds is not None and entry.kind not in kinds:
            continue
        if kinds is None and not (entry.get("read") or entry.get("operand") or entry.kind == "variable"):
            continue
        if not catalog_info.availability(entry, snap.profile)[0]:
            continue
        out.append(t.CompletionItem(label=entry.name, kind=t.CompletionItemKind.Constant,
                                    detail=entry.title, sort_text=f"2{entry.name}"))
    return out


# -- signature help ------------------------------------------------------------------------------

def signature(snap, line_text: str, character: int) -> t.SignatureHelp | None:
    """The syntax of the command whose arguments are being typed, with the current argument."""
    before = line_text[:character]
    from mcc.compiler.lint.suppress import comment_start, markers

    if comment_start(before, markers(snap.dialect)) is not None:
        return None
    entry, args_text = command_before(snap, before)
    if entry is None or not entry.syntax:
        return None
    active = args_text.count(",")
    signatures = []
    for syntax in entry.syntax:
        params = [t.ParameterInformation(label=p) for p in catalog_info.PLACEHOLDER.findall(syntax)]
        signatures.append(t.SignatureInformation(
            label=syntax, documentation=f"{entry.title}: {entry.summary}", parameters=params or None))
    best = next((i for i, s in enumerate(entry.syntax) if len(catalog_info.PLACEHOLDER.findall(s)) > active), 0)
    return t.SignatureHelp(signatures=signatures, active_signature=best, active_parameter=active)


def command_before(snap, before: str):
    """(the catalog entry of the command whose arguments are being typed, the arguments typed)."""
    return editor_of(snap.dialect).command_before(before)
