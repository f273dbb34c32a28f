"""The Arcus syntax tree: faithful to the text, one `Line` per source line, every node with a span.

The tree records the shape of each line (a command made of parts, an assignment, a condition)
and keeps comments; what a word means (which keyword, which axis letter is glued to it) is
decided later from the catalog (resolve.py). Words keep their spelling; Arcus is case-insensitive,
so comparisons use `key` (upper case).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Union

from mcc.compiler.span import Span


@dataclass(slots=True)
class Part:
    """A word with the sign and number glued to it: `X1000`, `JOGX+`, `X-1000`, `DO7`, `GOSUB 1`."""

    word: str
    word_span: Span
    sign: str = ""
    sign_span: Span | None = None
    number: str = ""
    number_span: Span | None = None

    @property
    def span(self) -> Span:
        last = self.number_span or self.sign_span or self.word_span
        return self.word_span.to(last)

    @property
    def key(self) -> str:
        """The part as one upper-case text, as the catalog patterns read it: 'JOGX+', 'X-1000'."""
        return self.word.upper() + self.sign + self.number


@dataclass(slots=True)
class Number:
    text: str  # digits, with a leading '-' for a negative literal
    span: Span

    @property
    def value(self) -> int:
        return int(self.text)


@dataclass(slots=True)
class Ref:
    """A name used as a value: a variable (V10) or a register (DI1, MSTX, TR, HSPD)."""

    part: Part

    @property
    def span(self) -> Span:
        return self.part.span


@dataclass(slots=True)
class Unary:
    op: str  # "~"
    operand: "Node"
    span: Span


@dataclass(slots=True)
class Binary:
    op: str  # + - * / % & | << >>
    left: "Node"
    right: "Node"
    span: Span


Node = Union[Number, Ref, Unary, Binary]


@dataclass(slots=True)
class Comparison:
    op: str  # = != < <= > >=
    left: Node
    right: Node
    span: Span
    chained: list[tuple[str, Node]] = field(default_factory=list)  # a=b=c: further comparisons


@dataclass(slots=True)
class Condition:
    first: Comparison
    span: Span
    more: list[tuple[str, Comparison]] = field(default_factory=list)  # AND / OR: not Arcus


@dataclass(slots=True)
class Command:
    """A line made of parts: `ABORT`, `JOGX+`, `X1000Y2000`, `GOSUB 1`, `ARCP0:100:30000`."""

    parts: list[Part]
    colon: list[Node]  # the operands after ':' (ARC, CIR)
    span: Span


@dataclass(slots=True)
class Assignment:
    """`V1=V2+1`, `HSPDX=1000`, `DO7=1`, `DELAY=1000`."""

    target: Part
    value: Node
    span: Span


@dataclass(slots=True)
class Conditional:
    """`IF`, `ELSEIF` or `WHILE` with its condition."""

    keyword: str  # upper case
    keyword_span: Span
    condition: Condition
    span: Span


Statement = Union[Command, Assignment, Conditional]


@dataclass(slots=True)
class Comment:
    text: str  # including the ';' or "'" marker
    span: Span


@dataclass(slots=True)
class Line:
    number: int
    statement: Statement | None = None
    comment: Comment | None = None
    error: bool = False  # the line did not parse; it is kept verbatim in the source
    keyword: str = ""  # for a line that did not parse: IF, ELSEIF or WHILE when it starts with one
    span: Span | None = None  # for a line that did not parse: the whole line


@dataclass
class SyntaxTree:
    path: str
    lines: list[Line] = field(default_factory=list)
    # The ABS/INC modes that may be in force at each ARC/CIR, by (line, column): the modes leave the
    # IR with the lowering (they are in the moves), and lint rule A310 still needs them for arcs.
    arc_modes: dict[tuple[int, int], frozenset[str]] = field(default_factory=dict)

    def statements(self):
        for line in self.lines:
            if line.statement is not None:
                yield line.statement

    def comments(self):
        for line in self.lines:
            if line.comment is not None:
                yield line.comment


def walk(node: Node):
    """A node and its sub-nodes, depth first."""
    stack = [node]
    while stack:
        item = stack.pop()
        yield item
        if isinstance(item, Binary):
            stack += (item.right, item.left)
        elif isinstance(item, Unary):
            stack.append(item.operand)


def operator_count(node: Node) -> int:
    if not isinstance(node, (Binary, Unary)):
        return 0  # a number or a name: most values are
    return sum(1 for item in walk(node) if isinstance(item, (Binary, Unary)))
