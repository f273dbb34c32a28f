"""Semantic tokens: the editor model's tokens, encoded as LSP's relative integers."""

from __future__ import annotations

from lsprotocol import types as t

from mcc.lsp import model

TYPES = ["function", "variable", "keyword", "label", "parameter", "number", "string", "comment", "operator",
         "namespace", "enumMember"]
MODIFIERS = ["declaration", "readonly", "deprecated"]
KIND_TO_TYPE = {model.COMMAND: "function", model.REGISTER: "enumMember", model.CONTROL: "keyword",
                model.LABEL: "label", model.VARIABLE: "variable", model.SUBROUTINE: "namespace",
                model.NUMBER: "number", model.STRING: "string", model.COMMENT: "comment",
                model.OPERATOR: "operator", model.ADDRESS: "parameter"}
LEGEND = t.SemanticTokensLegend(token_types=TYPES, token_modifiers=MODIFIERS)


def encode(snap, first_line: int = 0, last_line: int | None = None) -> t.SemanticTokens:
    data: list[int] = []
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
        delta_line = line - previous_line
        delta_char = char - previous_char if delta_line == 0 else char
        if delta_line == 0 and char < previous_end:
            continue  # overlapping tokens: keep the first
        data += [delta_line, delta_char, max(span.end_column - span.column, 0), type_index, modifiers]
        previous_line, previous_char, previous_end = line, char, span.end_column - 1
    return t.SemanticTokens(data=data)
