"""The MCode syntax tree: faithful to the text, one `Line` per source line, every node with a span.

The formatter and the editor features work on this tree; the lowering turns it into the IR.
Names keep their spelling; comparisons of names are case-insensitive (MCode is, L3767, L6871).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Union

from mcc.compiler.span import Span


@dataclass(slots=True)
class Name:
    text: str
    span: Span

    @property
    def key(self) -> str:
        return self.text.upper()


@dataclass(slots=True)
class Number:
    text: str
    span: Span

    @property
    def value(self) -> int | float:
        return float(self.text) if "." in self.text else int(self.text)


@dataclass(slots=True)
class String:
    text: str  # without the quotes
    span: Span


@dataclass(slots=True)
class Unary:
    op: str  # "-" or "!"
    operand: "Node"
    span: Span


@dataclass(slots=True)
class Binary:
    op: str  # + - * / & | ^ !
    left: "Node"
    right: "Node"
    span: Span


@dataclass(slots=True)
class FuncCall:
    name: str
    operand: "Node"
    span: Span


@dataclass(slots=True)
class Comparison:
    op: str  # = <> < <= > >= =<
    left: "Node"
    right: "Node"
    span: Span


@dataclass(slots=True)
class Juxtaposed:
    """A string followed by another item without the separating comma (PR "P=" P)."""

    first: String
    second: "Node"
    span: Span


Node = Union[Name, Number, String, Unary, Binary, FuncCall, Comparison, Juxtaposed]


@dataclass(slots=True)
class Statement:
    head: Name
    form: str  # "bare" (MA), "assign" (A=1), "command" (MA 100), "number" (NE=1 bare number)
    args: list[Node]
    span: Span
    party: str = ""  # a party-mode prefix written as a symbol: ! * ^
    suffix: str = ""  # ";" after PR items: no line end is printed


@dataclass(slots=True)
class Comment:
    text: str  # including the ` or ' marker
    span: Span


@dataclass(slots=True)
class Line:
    number: int
    statement: Statement | None = None
    comment: Comment | None = None
    error: bool = False  # the line did not parse; it is kept verbatim


@dataclass
class SyntaxTree:
    path: str
    lines: list[Line] = field(default_factory=list)

    def statements(self):
        for line in self.lines:
            if line.statement is not None:
                yield line.statement


def node_span(node: Node) -> Span:
    return node.span
