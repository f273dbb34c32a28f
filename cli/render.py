"""Rendering diagnostics for people (text with the source line and a caret) and for tools (JSON)."""

from __future__ import annotations

from mcc.compiler.diagnostics import Diagnostic, Severity
from mcc.compiler.span import SourceFile

SHOWN_WIDTH = 200  # longer source lines are shown as a window around the span, marked with "..."
STYLE = {Severity.ERROR: "bold red", Severity.WARNING: "bold yellow", Severity.INFO: "bold cyan"}


def format_diagnostic(diag: Diagnostic, source: SourceFile | None) -> list[tuple[str, str]]:
    """The lines of one diagnostic as (text, rich style) pairs."""
    span = diag.span
    head = f"{span.file}:{span.line}:{span.column}: {diag.severity.value}[{diag.code}] {diag.message}"
    lines = [(head, STYLE[diag.severity])]
    text = source.line_text(span.line) if source is not None else ""
    if text.strip():
        gutter = f"{span.line:>5} | "
        shown = text.expandtabs(1)
        width = span.end_column - span.column if span.end_line == span.line else len(shown) - span.column + 1
        column = span.column
        if len(shown) > SHOWN_WIDTH:
            shown, column, width = window(shown, column, max(1, width))
        lines.append((gutter + shown, ""))
        caret = " " * (len(gutter) - 2) + "| " + " " * (column - 1) + "^" * max(1, width)
        lines.append((caret, STYLE[diag.severity]))
    for note in diag.notes:
        lines.append((f"      = note: {note}", "dim"))
    if diag.fix is not None:
        lines.append((f"      = fix{'' if diag.fix.safe else ' (unsafe)'}: {diag.fix.description}", "green"))
    return lines


def window(line: str, column: int, width: int) -> tuple[str, int, int]:
    """A SHOWN_WIDTH-character piece of a long line around the span: (text, column, caret width)."""
    start = max(0, min(column - 1 - SHOWN_WIDTH // 4, len(line) - SHOWN_WIDTH))
    end = start + SHOWN_WIDTH
    head = "..." if start > 0 else ""
    tail = "..." if end < len(line) else ""
    column = column - start + len(head)
    width = max(1, min(width, end - (column - len(head) + start - 1)))
    return head + line[start:end] + tail, column, width


def summary_line(diags: list[Diagnostic], files: int) -> str:
    errors = sum(d.severity is Severity.ERROR for d in diags)
    warnings = sum(d.severity is Severity.WARNING for d in diags)
    infos = len(diags) - errors - warnings
    if not diags:
        return f"No problems found in {files} file{'s' if files != 1 else ''}."
    parts = [f"{errors} error{'s' if errors != 1 else ''}", f"{warnings} warning{'s' if warnings != 1 else ''}"]
    if infos:
        parts.append(f"{infos} note{'s' if infos != 1 else ''}")
    return f"Found {', '.join(parts)} in {files} file{'s' if files != 1 else ''}."


class TextWriter:
    """Writes styled lines: through rich on a terminal, as plain text otherwise."""

    def __init__(self, stream, color: bool):
        self.stream = stream
        self.console = None
        if color:
            from rich.console import Console  # only a terminal pays for importing rich

            self.console = Console(file=stream, highlight=False, soft_wrap=True)

    def line(self, text: str, style: str = "") -> None:
        if self.console is not None:
            from rich.text import Text

            self.console.print(Text(text, style=style or None))
        else:
            self.stream.write(text + "\n")


def write_text(writer: TextWriter, diags: list[Diagnostic], sources: dict[str, SourceFile]) -> None:
    for diag in diags:
        for text, style in format_diagnostic(diag, sources.get(diag.span.file)):
            writer.line(text, style)


def dump_json(payload: dict) -> str:
    import json  # only the formats that write JSON pay for importing it

    return json.dumps(payload, indent=2, ensure_ascii=False)


def machine_report(entries, fmt: str, rules_url: str | None = None) -> bool:
    """The formats `mcc check` and `mcc lint` share (besides text and json): print and answer True."""
    if fmt not in ("sarif", "github", "gitlab", "junit"):
        return False  # text and json: the caller's (nothing here to import for them)
    import click

    from mcc.compiler.lint import output

    if fmt == "sarif":
        click.echo(dump_json(output.to_sarif(entries, rules_url)))
    elif fmt == "github":
        for line in output.to_github(entries):
            click.echo(line)
    elif fmt == "gitlab":
        click.echo(dump_json(output.to_gitlab(entries)))
    elif fmt == "junit":
        click.echo(output.to_junit(entries), nl=False)
    else:
        return False
    return True

