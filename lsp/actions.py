"""Code actions: every fix a diagnostic carries, "silence with noqa" in the dialect's own comment
syntax, the explanation of the rule (the `mcc.explain` command), and "fix all" (`source.fixAll.mcc`,
what `mcc lint --fix` writes: the safe fixes, round after round, validated in the simulator)."""

from __future__ import annotations

from lsprotocol import types as t

from mcc.compiler.diagnostics import Diagnostic, Kind
from mcc.compiler.lint import suppress
from mcc.compiler.span import normalise_newlines
from mcc.lsp.convert import range_of
from mcc.lsp.edits import line_edits, with_newlines_of

EXPLAIN = "mcc.explain"
FIX_ALL = "source.fixAll.mcc"
FIX_ALL_TITLE = "Fix all auto-fixable problems (mcc)"


def kind_text(kind) -> str:
    return str(getattr(kind, "value", kind))


def fix_all_wanted(only) -> bool:
    """Whether a request's `only` kinds take in `source.fixAll.mcc` (no `only`: every kind)."""
    return not only or any(FIX_ALL == kind_text(w) or FIX_ALL.startswith(kind_text(w) + ".") for w in only)


def has_safe_fixes(snap) -> bool:
    return any(d.fix is not None and d.fix.edits and d.fix.safe for d in snap.diagnostics)


def fix_all_action(snap, edits: list[t.TextEdit] | None = None, data=None) -> t.CodeAction:
    """The "fix all" action: with its edits, or with `data` for codeAction/resolve to fill them in."""
    edit = t.WorkspaceEdit(changes={snap.uri: edits}) if edits is not None else None
    return t.CodeAction(title=FIX_ALL_TITLE, kind=FIX_ALL, edit=edit, data=data)


def fix_all_edits(snap, document: str) -> list[t.TextEdit]:
    """The edits that turn the editor's `document` into what `mcc lint --fix` writes for it: the safe
    fixes applied until the text settles (engine.lint_source), nothing when the simulator finds that
    the fixed program behaves differently (the command's default validation), the file's own line
    ends kept; positions in characters."""
    from mcc.compiler.lint import engine

    text = normalise_newlines(document)
    options = engine.Options(fix=True, dialect=snap.dialect, verify=True, verify_required=False)
    outcome = engine.lint_source(snap.path, text, snap.settings, options)
    if outcome.text is None or outcome.text == text or engine._diverges(outcome, text, options):
        return []
    return line_edits(document, with_newlines_of(document, outcome.text))


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
        out = [a for a in out if isinstance(a, t.CodeAction)
               and any(kind_text(a.kind).startswith(kind_text(w)) for w in wanted)]
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
