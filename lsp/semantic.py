"""Semantic tokens: the editor model's tokens, encoded as LSP's relative integers."""

from __future__ import annotations

from lsprotocol import types as t

from mcc.lsp import model
from mcc.lsp.units import Units

TYPES = ["function", "variable", "keyword", "label", "parameter", "number", "string", "comment", "operator",
         "namespace", "enumMember"]
MODIFIERS = ["declaration", "readonly", "deprecated"]
KIND_TO_TYPE = {model.COMMAND: "function", model.REGISTER: "enumMember", model.CONTROL: "keyword",
                model.LABEL: "label", model.VARIABLE: "variable", model.SUBROUTINE: "namespace",
                model.NUMBER: "number", model.STRING: "string", model.COMMENT: "comment",
                model.OPERATOR: "operator", model.ADDRESS: "parameter"}
LEGEND = t.SemanticTokensLegend(token_types=TYPES, token_modifiers=MODIFIERS)


def encode(snap, first_line: int = 0, last_line: int | None = None, units: Units = Units("utf-32")) -> t.SemanticTokens:
    """The tokens of lines first_line..last_line, columns and lengths in the client's `units`."""
    data: list[int] = []
    source = snap.source
    previous_line, previous_char, previous_end = 0, 0, 0
    for token in snap.index.tokens:
        span = token.span
        if span.end_line != span.line:
            continue  # LSP tokens stay on one line
        line, char = span.line - 1, span.column - 1
        if line < first_line or (last_line is not None and line > last_line):
            continue
        type_index = TYPES.index(KIND_TO_TYPE.get(token.kind, "variable"))
        modifiers = 1 if token.definition else 0
        end = span.end_column - 1
        if not units.characters:
            text = source.line_text(span.line) if span.line <= source.line_count else ""
            char, end = units.to_client(text, char), units.to_client(text, end)
        delta_line = line - previous_line
        delta_char = char - previous_char if delta_line == 0 else char
        if delta_line == 0 and char < previous_end:
            continue  # overlapping tokens: keep the first
        data += [delta_line, delta_char, max(end - char, 0), type_index, modifiers]
        previous_line, previous_char, previous_end = line, char, end
    return t.SemanticTokens(data=data)
