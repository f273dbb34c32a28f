"""What the editor features know about one document, independent of its dialect.

Each dialect's indexer (`mcode_index`, `arcus_index`, `x150_index`) walks the syntax tree the
frontend built and describes it in these terms: tokens (what each word is, with its catalog
entry), symbols (labels, variables, subroutines, sequences: where they are defined and used),
routines (named stretches of the program, for the outline and program memory) and folding
ranges. Hover, completion, navigation, semantic tokens and the outline only read this model, so
they are written once for the three dialects.
"""

from __future__ import annotations

import bisect
from dataclasses import dataclass, field
from typing import Any

from mcc.compiler.span import SourceFile, Span

# token kinds (also the semantic token types, see semantic.py)
COMMAND, REGISTER, CONTROL, LABEL, VARIABLE, SUBROUTINE, NUMBER, STRING, COMMENT, OPERATOR, ADDRESS = (
    "command", "register", "control", "label", "variable", "subroutine", "number", "string", "comment",
    "operator", "address")

# symbol kinds
SYMBOL_LABEL, SYMBOL_VARIABLE, SYMBOL_SUBROUTINE, SYMBOL_SEQUENCE = "label", "variable", "subroutine", "sequence"


@dataclass
class Token:
    span: Span
    kind: str
    entry: Any = None  # the generic catalog entry (mcc.compiler.catalog.Entry) of a command or register
    symbol: str = ""  # the key of the symbol this token defines or uses
    definition: bool = False
    command: Any = None  # for a number: the catalog entry of the command it is an argument of
    value: float | None = None  # for a number: its value


@dataclass
class Symbol:
    key: str  # "label:G1", "variable:V3", "subroutine:1", "sequence:3"
    kind: str
    name: str  # as the user writes it: G1, V3, 1, 3
    definitions: list[Span] = field(default_factory=list)
    references: list[Span] = field(default_factory=list)
    detail: str = ""

    @property
    def label(self) -> str:
        return {"subroutine": f"SUB {self.name}", "sequence": f"sequence {self.name}"}.get(self.kind, self.name)


@dataclass
class Routine:
    """A named stretch of the program: an MCode program or label body, an Arcus main program or
    subroutine, an X150 sequence."""

    name: str
    kind: str  # "program" | "label" | "subroutine" | "sequence"
    span: Span  # the whole body
    selection: Span  # the name (the LB, SUB n, XDn)
    symbol: str = ""
    children: list["Routine"] = field(default_factory=list)


@dataclass
class Index:
    dialect: str
    tokens: list[Token] = field(default_factory=list)
    symbols: dict[str, Symbol] = field(default_factory=dict)
    routines: list[Routine] = field(default_factory=list)
    folds: list[tuple[int, int, str]] = field(default_factory=list)  # (first line, last line, kind), 1-based
    settings: dict[str, float] = field(default_factory=dict)  # values the file sets (MCode MS=256)
    _starts: list[int] = field(default_factory=list, repr=False)

    def symbol(self, key: str, kind: str, name: str) -> Symbol:
        found = self.symbols.get(key)
        if found is None:
            found = self.symbols[key] = Symbol(key, kind, name)
        return found

    def add(self, span: Span | None, kind: str, **extra) -> Token | None:
        if span is None:
            return None
        token = Token(span, kind, **extra)
        self.tokens.append(token)
        if token.symbol:
            sym = self.symbols.get(token.symbol)
            if sym is not None:
                (sym.definitions if token.definition else sym.references).append(span)
        return token

    def finish(self) -> "Index":
        self.tokens.sort(key=lambda t: (t.span.start, t.span.end))
        self._starts = [t.span.start for t in self.tokens]
        return self

    def token_at(self, offset: int) -> Token | None:
        """The token under `offset`, or the one that ends just there (the cursor after a word)."""
        i = bisect.bisect_right(self._starts, offset) - 1
        best = None
        for j in (i, i - 1):
            if 0 <= j < len(self.tokens):
                tok = self.tokens[j]
                if tok.span.start <= offset < tok.span.end:
                    return tok
                if tok.span.end == offset and best is None:
                    best = tok
        return best

    def symbol_at(self, offset: int) -> Symbol | None:
        token = self.token_at(offset)
        return self.symbols.get(token.symbol) if token is not None and token.symbol else None


# -- helpers the dialects' indexers share ----------------------------------------------------------
def span_lines(source: SourceFile, first: int, last: int) -> Span:
    """The span of lines `first` to `last` (1-based, inclusive, clipped to the file)."""
    last = min(last, source.line_count)
    start = source.line_starts[first - 1]
    end = source.line_starts[last - 1] + len(source.line_text(last))
    return source.span(start, end)


def comment_folds(index: Index, tree) -> None:
    """Runs of three or more comment-only lines fold as one comment."""
    run_start = None
    previous = None
    for line in tree.lines:
        only = getattr(line, "comment", None) is not None and not has_code(line)
        if only and run_start is not None and previous == line.number - 1:
            previous = line.number
            continue
        if run_start is not None and previous - run_start >= 2:
            index.folds.append((run_start, previous, "comment"))
        run_start, previous = (line.number, line.number) if only else (None, None)
    if run_start is not None and previous - run_start >= 2:
        index.folds.append((run_start, previous, "comment"))


def has_code(line) -> bool:
    """Whether a line of a dialect's syntax tree holds more than a comment."""
    return bool(getattr(line, "statement", None) or getattr(line, "commands", None) or getattr(line, "error", False))
