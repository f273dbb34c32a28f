"""Every editor feature on random and mutated programs, in-process (the same functions the server
calls), so that hypothesis can shrink a failure: none may raise, whatever the text and position.
The protocol-level fuzz is in test_robustness.py."""

from __future__ import annotations

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from lsprotocol import types as t

from conftest import EXTENSIONS, sample_files
from mcc.lsp import actions, analysis, completion, formatting, hover, lenses, navigation, outline, semantic
from test_fuzz import TOKENS, mutate

FUZZ = settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])


def exercise(dialect: str, text: str, data) -> None:
    path = f"/fuzz/f{EXTENSIONS[dialect]}"
    snap = analysis.analyze("file://" + path, path, 1, text)
    internal = [d.message for d in snap.diagnostics if d.code == "G001"]
    assert not internal, internal
    length = len(snap.source.text)
    lines = snap.source.text.split("\n")
    for _ in range(5):
        offset = data.draw(st.integers(0, length))
        line, column = snap.source.position(offset)
        position = t.Position(line - 1, column - 1)
        hover.hover(snap, offset)
        completion.complete(snap, lines[line - 1], column - 1, line - 1)
        completion.signature(snap, lines[line - 1], column - 1)
        navigation.definition(snap, offset)
        navigation.references(snap, offset, True)
        navigation.highlight(snap, offset)
        navigation.prepare_rename(snap, offset)
        try:
            navigation.rename(snap, offset, data.draw(st.sampled_from(["G9", "7", "V3", "VAR4", "", "MA", "Q"])))
        except navigation.RenameError:
            pass
        actions.code_actions(snap, t.Range(position, position), t.CodeActionContext(diagnostics=[]))
    outline.document_symbols(snap)
    outline.folding_ranges(snap)
    outline.workspace_symbols([snap], "")
    semantic.encode(snap)
    lenses.code_lenses(snap)
    lenses.inlay_hints(snap, 0, len(lines))
    try:
        formatting.edits(snap, snap.source.text)
    except RuntimeError as exc:  # the formatter refusing to change a program's meaning is allowed
        assert "formatting would change the program" in str(exc)


@pytest.mark.parametrize("dialect", list(EXTENSIONS))
@FUZZ
@given(data=st.data())
def test_token_soup_through_every_feature(dialect: str, data) -> None:
    pieces = data.draw(st.lists(st.sampled_from(TOKENS[dialect]), max_size=40))
    exercise(dialect, "".join(pieces), data)


@pytest.mark.parametrize("dialect", list(EXTENSIONS))
@FUZZ
@given(data=st.data())
def test_mutated_samples_through_every_feature(dialect: str, data) -> None:
    text = data.draw(st.sampled_from(sample_files(dialect))).read_text(encoding="utf-8")
    exercise(dialect, mutate(text, data), data)
