"""The X150 syntax tree: faithful to the text, one `Line` per source line, every node with a span.

An X150 line holds any number of commands separated by spaces and an optional `;` comment. Each
command is `[address][B][MNEMONIC][argument]` written without separators (`1A10`, `1BCPG50`,
`TRE_X1`); the tokeniser splits it by longest match against the catalog and parses the argument by
the catalog's argument class. The nodes below keep what was written (spelling, case, spans); the
lowering and the checks give it meaning.
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass, field
from itertools import chain
from operator import attrgetter
from typing import Union

from mcc.compiler.span import Span
from mcc.compiler.x150.catalog import Command as CatalogCommand


# --- arguments -------------------------------------------------------------------------------


@dataclass(slots=True)
class Number:
    text: str
    value: int | float
    span: Span


@dataclass(slots=True)
class VarRef:
    """VARn, or the `(VARn)` substitution written in place of a value (L4575-L4590)."""

    number: int
    span: Span

    @property
    def name(self) -> str:
        return f"VAR{self.number}"


@dataclass(slots=True)
class Source:
    """A device reading on the right of `VARn=` (POS ABS FEP RSIN TQ FUN NUM SMC)."""

    name: str
    span: Span


@dataclass(slots=True)
class Pattern:
    """An input (bbbbbbb_bbbbbbbbbb) or output (bbbbbb) pattern over 0, 1 and X, upper-cased."""

    bits: str
    span: Span


@dataclass(slots=True)
class IoFunction:
    """IN<n><function> / OUT<n><function> (1IN4C, 1OUT3B)."""

    index: int
    function: str
    span: Span


@dataclass(slots=True)
class Fields:
    """A composite argument: numeric fields (DPC208, FRD0,4,0, DVO2,2,1,1) and TX's trailing text."""

    values: list[int]
    spans: list[Span]
    tail: str | None
    span: Span


@dataclass(slots=True)
class Text:
    """Quoted text (DTXT"...", 1"...") without its quotes."""

    text: str
    span: Span


Operand = Union[Number, VarRef, Source]


@dataclass(slots=True)
class Chain:
    """`a op b op c ...`, evaluated strictly left to right (L4638-L4642)."""

    first: Operand
    rest: list[tuple[str, Operand]]
    span: Span


@dataclass(slots=True)
class VarStatement:
    """VARn (report), VARn=<chain>, VARn=<source>; also IVARn=<value>."""

    var: VarRef
    value: Chain | None
    span: Span


@dataclass(slots=True)
class Comparison:
    left: Operand
    op: str
    right: Operand
    span: Span


@dataclass(slots=True)
class InputTerm:
    """IN<pattern> inside a condition; `underscore` is False for the damaged form INXXX1 (L1414)."""

    pattern: Pattern
    underscore: bool
    span: Span


Term = Union[Comparison, InputTerm]


@dataclass(slots=True)
class Condition:
    terms: list[Term]
    joins: list[str]  # "AND" / "OR", one fewer than terms
    span: Span


Argument = Union[Number, VarRef, Pattern, IoFunction, Fields, Text, VarStatement, Condition]


# --- commands, comments, lines -----------------------------------------------------------------


@dataclass(slots=True)
class Problem:
    """A finding of the tokeniser, reported by the parser once the command is final."""

    code: str
    span: Span
    message: str


@dataclass(slots=True)
class Command:
    text: str  # as written, the joining space of a re-joined argument removed
    span: Span
    address: int | None = None
    # The spans of the address and of the mnemonic are made only when asked for (`address_span`,
    # `mnemonic_span`): most commands never need them, and a parse reads thousands of commands
    # (docs/PERFORMANCE.md). On a line without a re-joined space they are characters
    # [0, address_chars) and [mnemonic_from, mnemonic_to) of the token, on the command's own line
    # (so a copy moved with the command's span moves them too); else the spans given.
    address_chars: int = 0
    given_address_span: Span | None = None
    buffered: bool = False  # the B prefix of an immediate `*` command (L185)
    mnemonic: str = ""  # canonical upper-case catalog name; "" when not a known command
    written: str = ""  # the mnemonic as written (case kept)
    mnemonic_from: int = 0
    mnemonic_to: int = 0
    given_mnemonic_span: Span | None = None
    info: CatalogCommand | None = None  # the catalog entry (for VARn=FUN etc. the statement's entry)
    arg: Argument | None = None
    arg_span: Span | None = None
    host: bool = False  # `!number`: the host's reply to VARn=RSIN, data rather than a command
    rejoined: bool = False  # a space inside the command was removed (IF (..), 1OUTL XX10X1)
    problems: tuple[Problem, ...] = ()  # a tuple: most commands have none, and share the empty one

    @property
    def address_span(self) -> Span | None:
        chars = self.address_chars
        if chars:
            span = self.span
            return Span(span.file, span.line, span.column, span.line, span.column + chars, span.start,
                        span.start + chars)
        return self.given_address_span

    @address_span.setter
    def address_span(self, span: Span | None) -> None:
        self.given_address_span = span
        self.address_chars = 0

    @property
    def mnemonic_span(self) -> Span | None:
        begin, end = self.mnemonic_from, self.mnemonic_to
        if end:
            span = self.span
            return Span(span.file, span.line, span.column + begin, span.line, span.column + end, span.start + begin,
                        span.start + end)
        return self.given_mnemonic_span

    @mnemonic_span.setter
    def mnemonic_span(self, span: Span | None) -> None:
        self.given_mnemonic_span = span
        self.mnemonic_from = self.mnemonic_to = 0

    @property
    def ok(self) -> bool:
        """The command was read completely (known mnemonic, well-formed argument)."""
        return (self.info is not None or self.host) and not self.problems

    @property
    def is_upper(self) -> bool:
        return self.written == self.written.upper()

    def address_text(self) -> str:
        return str(self.address) if self.address is not None else ""


@dataclass(slots=True)
class Comment:
    text: str  # including the ;
    span: Span


@dataclass(slots=True)
class Line:
    number: int
    commands: list[Command] = field(default_factory=list)
    comment: Comment | None = None
    error: bool = False  # the line could not be split; it is kept verbatim and not lowered


@dataclass
class SyntaxTree:
    path: str
    lines: list[Line] = field(default_factory=list)

    def commands(self) -> Iterator[Command]:
        """Every command, in order (an iterator chained in C: a check goes over them several times)."""
        return chain.from_iterable(map(attrgetter("commands"), self.lines))
