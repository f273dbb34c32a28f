"""Completion and signature help.

What is offered depends on where the cursor is, read from the text of the current line: a label
where an MCode command takes one (`BR x`, `CL x`, `TI 1,x`, `TT=0.5,x`, `OE=x`, ...), a condition
after `BR x,`/`CL x,` (variables, flags and inputs, lexium-mcode.txt L1807, L2124), a subroutine
number after `GOSUB` (Arcus), a sequence number after `XR`/`XG`/... (X150), a command at the start
of a statement (as a snippet from the catalog's syntax, only what the target product has, and only
what the program region allows), variables and readable registers elsewhere.

Every item carries the range it replaces (a `textEdit`): the word being typed as the dialect reads
it, not as the editor's word pattern does. An X150 device address (`1D`, `2G`) and an Arcus axis
letter before a variable (`XV2`) are not part of it, nor what stands before `,` or `=`; without the
range an editor filters the items by `1D` or `XV2` and shows none.
"""

from __future__ import annotations

import re

from lsprotocol import types as t

from mcc.lsp import catalog_info, model

MCODE_PREFIX = r"^\s*[!*^]?(?:[A-Za-z0-9]\s*)??"  # an optional party-mode device name
MCODE_LABEL = re.compile(  # the label/address of L1764 BP, L1807 BR, L2124 CL, L2156 CP, L2787 EX,
    # L4551 OE=, L5583 TA=, L5609 TC=, L5744 TM=, and after the first argument of L5711 TI,
    # L5776 TP=, L5848 TR=, L5908 TT=
    MCODE_PREFIX + r"(?:(?:BR|CL|BP|EX|CP)\s+|(?:OE|TA|TC|TM)\s*=\s*|(?:TI\s+|(?:TP|TR|TT)\s*=\s*)[^,]*,\s*)"
    r"[A-Za-z0-9]*$", re.IGNORECASE)
MCODE_CONDITION = re.compile(MCODE_PREFIX + r"(?:BR|CL)\s+[^,\s]+\s*,[^,]*$", re.IGNORECASE)  # L1807, L2124
ARCUS_GOSUB = re.compile(r"^\s*GOSUB\s*(\d*)$", re.IGNORECASE)
X150_SEQUENCE = re.compile(r"(?:^|\s)\d*(?:XRP|XR|XG|XE|XU|GOSUB|GOTO)\s*(\d*)$", re.IGNORECASE)
STATEMENT_START = {
    "mcode": re.compile(r"^\s*[!*^]?[A-Za-z]{0,3}$"),
    "arcus": re.compile(r"^\s*[A-Za-z]*$"),
    "x150": re.compile(r"(?:^|\s)\d*(B?[A-Za-z]*)$"),  # the command after its device address
}
WORD = re.compile(r"[A-Za-z0-9_]*$")
COMMAND_KINDS = {"mcode": ("instruction", "variable", "flag"),
                 "arcus": None, "x150": None}
VALUE_KINDS = {"mcode": ("variable", "flag", "keyword", "function")}


def complete(snap, line_text: str, character: int, line: int) -> t.CompletionList:
    before = line_text[:character]
    dialect = snap.dialect
    items: list[t.CompletionItem] = []
    start = word_start(dialect, before)
    if dialect == "mcode" and MCODE_LABEL.match(before):
        items = symbols(snap, model.SYMBOL_LABEL)
    elif dialect == "mcode" and MCODE_CONDITION.match(before) and not in_comment(snap, before):
        items = symbols(snap, model.SYMBOL_VARIABLE) + values(snap)
    elif dialect == "arcus" and ARCUS_MOVE_VARIABLE.match(before):
        items = symbols(snap, model.SYMBOL_VARIABLE)
    elif dialect == "arcus" and ARCUS_GOSUB.match(before):
        items = symbols(snap, model.SYMBOL_SUBROUTINE)
    elif dialect == "x150" and (found := X150_SEQUENCE.search(before)):
        items = symbols(snap, model.SYMBOL_SEQUENCE)
        start = found.start(1)  # the number after `1XR`
    elif dialect in STATEMENT_START and (found := STATEMENT_START[dialect].search(before)) \
            and not in_comment(snap, before):
        items = commands(snap, line) + (symbols(snap, model.SYMBOL_VARIABLE) if dialect != "x150" else [])
        if dialect == "x150":
            start = found.start(1)  # after the device address (`1` typed alone: nothing to replace)
    elif not in_comment(snap, before):
        items = symbols(snap, model.SYMBOL_VARIABLE) + values(snap)
    replaced = t.Range(t.Position(line, start), t.Position(line, character))
    return t.CompletionList(is_incomplete=False, items=[with_range(item, replaced) for item in items])


TRAILING_WORD = re.compile(r"[A-Za-z0-9_]*$")
X150_ADDRESSED = re.compile(r"^\d+(?=[A-Za-z])")  # `1D`, `12XR`: the device address before a command
# `XV2`, `X1000YV2`: a variable as a move target (arcus-pmx-4ex-sa.txt L2759 `XV10`, L2665 `UV10`)
ARCUS_MOVE_VARIABLE = re.compile(r"^\s*(?:[XYZU](?:[+-]?\d+|V\d+))*[XYZU](V\d*)$", re.IGNORECASE)


def word_start(dialect: str, before: str) -> int:
    """The column where the word being typed starts: the items replace from there to the cursor."""
    start = len(before) - len(TRAILING_WORD.search(before).group(0))
    word = before[start:]
    if dialect == "x150":
        found = X150_ADDRESSED.match(word)
        if found is not None:
            start += found.end()
    elif dialect == "arcus":
        found = ARCUS_MOVE_VARIABLE.match(before)
        if found is not None:
            start = found.start(1)
    return start


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


def region_mode(snap, line: int) -> str:
    """MCode: "program" inside a PG … PG region, else "immediate"."""
    for routine in snap.index.routines:
        if routine.kind == "program" and routine.span.line <= line + 1 <= routine.span.end_line:
            return "program"
    return "immediate"


def inside_sequence(snap, line: int) -> bool:
    return any(r.kind == "sequence" and r.span.line < line + 1 < r.span.end_line for r in snap.index.routines)


def allowed_here(snap, entry, line: int) -> bool:
    ok, _ = catalog_info.availability(entry, snap.profile)
    if not ok or entry.kind in catalog_info.UNAVAILABLE_KINDS:
        return False
    if snap.dialect == "mcode":
        if entry.kind not in COMMAND_KINDS["mcode"]:
            return False
        mode = entry.get("mode", "both")
        return mode == "both" or mode == region_mode(snap, line)
    if snap.dialect == "x150" and inside_sequence(snap, line):
        return entry.get("seq", "S") == "S"
    if snap.dialect == "arcus":
        return bool(entry.get("pattern"))
    return True


def commands(snap, line: int) -> list[t.CompletionItem]:
    """The commands allowed at `line`; the items depend only on the dialect, the profile and the
    kind of place, so they are built once per combination."""
    if snap.dialect == "mcode":
        place = region_mode(snap, line)
    elif snap.dialect == "x150":
        place = "sequence" if inside_sequence(snap, line) else "immediate"
    else:
        place = ""
    key = (snap.dialect, getattr(snap.profile, "name", ""), getattr(snap.profile, "product", ""),
           getattr(snap.profile, "firmware", ""), place)
    found = COMMAND_ITEMS.get(key)
    if found is None:
        found = COMMAND_ITEMS[key] = build_commands(snap, line)
    return list(found)


COMMAND_ITEMS: dict[tuple, list[t.CompletionItem]] = {}


def build_commands(snap, line: int) -> list[t.CompletionItem]:
    out = []
    for entry in catalog_info.entries(snap.dialect):
        if not allowed_here(snap, entry, line):
            continue
        text, syntax = catalog_info.snippet(entry, snap.dialect)
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
    kinds = VALUE_KINDS.get(snap.dialect)
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
    if snap.dialect == "mcode":
        match = re.match(r"^\s*[!*^]?([A-Za-z]{1,3}[0-9]?)(?:\s+|=)(.*)$", before)
        if match:
            return catalog_info.lookup("mcode", match.group(1)), match.group(2)
    elif snap.dialect == "arcus":
        match = re.match(r"^\s*([A-Za-z]+?)[XYZU]?(?:\s+|=|:)(.*)$", before)
        if match:
            return catalog_info.lookup("arcus", match.group(1)), match.group(2)
    elif snap.dialect == "x150":
        match = re.search(r"(?:^|\s)\d*B?([A-Za-z]+)([^\s]*)$", before)
        if match:
            word = match.group(1).upper()
            for size in range(len(word), 0, -1):
                entry = catalog_info.lookup("x150", word[:size])
                if entry is not None:
                    return entry, word[size:] + match.group(2)
    return None, ""
