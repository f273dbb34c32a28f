"""Diagnostics: what every check, linter rule and backend reports.

A diagnostic has a stable code (see `mcc.compiler.codes`), a severity, a kind, a message that
tells the user what to do, and a span. Severity and kind default to the code's registry entry, so
a check only states what is specific to the finding.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from enum import Enum

from mcc.compiler.span import Span


class Severity(str, Enum):
    ERROR = "error"
    WARNING = "warning"
    INFO = "info"

    @property
    def rank(self) -> int:
        return {"error": 2, "warning": 1, "info": 0}[self.value]


class Kind(str, Enum):
    SYNTAX = "syntax"
    SEMANTIC = "semantic"
    LINT = "lint"
    INTERNAL = "internal"


@dataclass(frozen=True, slots=True)
class Edit:
    """Replace the text of `span` with `text` (an empty span inserts)."""

    span: Span
    text: str


@dataclass(frozen=True, slots=True)
class Fix:
    description: str
    edits: tuple[Edit, ...]
    safe: bool = True

    def to_json(self) -> dict:
        """The fix in JSON output: what it does, whether `--fix` applies it ("safe") or only
        `--fix --unsafe-fixes` ("unsafe"), and its edits (the text of each range, 1-based lines
        and columns, end exclusive, replaced by `content`; an empty range inserts)."""
        return {
            "message": self.description,
            "applicability": "safe" if self.safe else "unsafe",
            "edits": [{"content": e.text, "line": e.span.line, "column": e.span.column,
                       "end_line": e.span.end_line, "end_column": e.span.end_column} for e in self.edits],
        }


@dataclass(slots=True)
class Diagnostic:
    code: str
    severity: Severity
    kind: Kind
    message: str
    span: Span
    notes: tuple[str, ...] = ()
    fix: Fix | None = None

    def sort_key(self) -> tuple:
        return (self.span.file, self.span.line, self.span.column, self.code)

    def to_json(self) -> dict:
        return {
            "code": self.code,
            "severity": self.severity.value,
            "kind": self.kind.value,
            "message": self.message,
            "line": self.span.line,
            "column": self.span.column,
            "end_line": self.span.end_line,
            "end_column": self.span.end_column,
            **({"notes": list(self.notes)} if self.notes else {}),
            **({"fix": self.fix.to_json()} if self.fix else {}),
        }


@dataclass
class Diagnostics:
    """A collector that fills severity and kind from the code registry."""

    items: list[Diagnostic] = field(default_factory=list)

    def add(self, code: str, span: Span, message: str, *, notes: tuple[str, ...] | list[str] = (),
            fix: Fix | None = None, severity: Severity | None = None) -> Diagnostic:
        from mcc.compiler.codes import registry

        info = registry().get(code)
        diag = Diagnostic(
            code=code,
            severity=severity or (info.severity if info else Severity.ERROR),
            kind=info.kind if info else Kind.INTERNAL,
            message=message,
            span=span,
            notes=tuple(notes),
            fix=fix,
        )
        self.items.append(diag)
        return diag

    def extend(self, other: "Diagnostics | list[Diagnostic]") -> None:
        self.items.extend(other.items if isinstance(other, Diagnostics) else other)

    def __iter__(self):
        return iter(self.items)

    def __len__(self) -> int:
        return len(self.items)

    def refuse_syntax_errors(self) -> None:
        """Raise `SyntaxErrors` when any collected diagnostic is a syntax error (formatters: a text
        that does not parse is not reformatted, as black and ruff refuse it)."""
        first = next((d for d in self.items if d.kind is Kind.SYNTAX and d.severity is Severity.ERROR), None)
        if first is not None:
            raise SyntaxErrors(first, sum(1 for d in self.items if d.kind is Kind.SYNTAX))

    @property
    def has_errors(self) -> bool:
        return any(d.severity is Severity.ERROR for d in self.items)

    def sorted(self) -> list[Diagnostic]:
        return sorted(self.items, key=Diagnostic.sort_key)


class SyntaxErrors(Exception):
    """The text has syntax errors, so it is left as written; `first` says where."""

    def __init__(self, first: Diagnostic, count: int = 1) -> None:
        more = f" (and {count - 1} more)" if count > 1 else ""
        super().__init__(f"syntax error at {first.span.line}:{first.span.column}: {first.code} {first.message}{more}")
        self.first = first
        self.count = count
