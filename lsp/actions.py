"""Code actions: every fix a diagnostic carries, "silence with noqa" in the dialect's own comment
syntax, and the explanation of the rule (the `mcc.explain` command)."""

from __future__ import annotations

from lsprotocol import types as t

from mcc.compiler.diagnostics import Diagnostic, Kind
from mcc.compiler.lint import suppress
from mcc.lsp.convert import range_of

EXPLAIN = "mcc.explain"


def overlaps(diag: Diagnostic, first: int, last: int) -> bool:
    return diag.span.line - 1 <= last and diag.span.end_line - 1 >= first


def code_actions(snap, rng: t.Range, context: t.CodeActionContext) -> list[t.CodeAction | t.Command]:
    wanted = set(context.only or ())
    sent = {(d.code, d.range.start.line) for d in context.diagnostics or ()}
    out: list[t.CodeAction | t.Command] = []
    for diag in snap.diagnostics:
        if not overlaps(diag, rng.start.line, rng.end.line) and (diag.code, diag.span.line - 1) not in sent:
            continue
        lsp_diag = [d for d in context.diagnostics or () if d.code == diag.code] or None
        if diag.fix is not None and diag.fix.edits:
            edits = [t.TextEdit(range=range_of(e.span), new_text=e.text) for e in diag.fix.edits]
            out.append(t.CodeAction(title=f"{diag.fix.description} ({diag.code})", kind=t.CodeActionKind.QuickFix,
                                    diagnostics=lsp_diag, is_preferred=diag.fix.safe,
                                    edit=t.WorkspaceEdit(changes={snap.uri: edits})))
        if diag.kind not in (Kind.SYNTAX, Kind.INTERNAL) and not diag.code.startswith("G10"):
            edit = noqa_edit(snap, diag)
            if edit is not None:
                out.append(t.CodeAction(title=f"Silence {diag.code} on this line (noqa)",
                                        kind=t.CodeActionKind.QuickFix, diagnostics=lsp_diag,
                                        edit=t.WorkspaceEdit(changes={snap.uri: [edit]})))
        # a bare Command (allowed in the answer): clients run it without a code-action round trip
        out.append(t.Command(title=f"Explain {diag.code}", command=EXPLAIN, arguments=[diag.code]))
    if wanted:
        out = [a for a in out if isinstance(a, t.CodeAction) and any(str(a.kind).startswith(str(w)) for w in wanted)]
    return dedupe(out)


def dedupe(actions: list) -> list:
    seen, out = set(), []
    for action in actions:
        if action.title not in seen:
            seen.add(action.title)
            out.append(action)
    return out


def noqa_edit(snap, diag: Diagnostic) -> t.TextEdit | None:
    """Add the code to the line's noqa, or a noqa comment to the line."""
    source = snap.source
    number = diag.span.line
    if not 1 <= number <= source.line_count:
        return None
    text = source.line_text(number)
    directive = suppress.find_directives(source, snap.dialect).get(number)
    base = source.line_starts[number - 1]
    if directive is not None:
        if directive.bare or diag.code in directive.codes:
            return None
        end = directive.span
        return t.TextEdit(range=range_of(source.span(end.end, end.end)),
                          new_text=(", " if directive.codes else ": ") + diag.code)
    marks = suppress.markers(snap.dialect)
    at = suppress.comment_start(text, marks)
    end = source.span(base + len(text), base + len(text))
    if at is not None:
        return t.TextEdit(range=range_of(end), new_text=f" noqa: {diag.code}")
    marker = marks[0] if marks else ";"
    return t.TextEdit(range=range_of(end), new_text=f"  {marker} noqa: {diag.code}")
