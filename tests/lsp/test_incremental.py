"""The editor server's incremental check (lsp/incremental.py) gives exactly what a check from
scratch gives: after every edit of a random series, the syntax tree, the IR, the program memory
and the diagnostics of `mcc check` + `mcc lint` are compared with those of `engine.check_text` on
the same text. The edits are the fuzzer's: the dialects' own words, line breaks, quotes and
comment characters typed, deleted and replaced anywhere."""

from __future__ import annotations

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from conftest import EXTENSIONS, sample_files
from mcc.compiler import cancel, ir_print
from mcc.compiler.config import Settings
from mcc.compiler.lint import engine
from mcc.lsp import incremental
from test_fuzz import TOKENS

EDITS = settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.too_slow])


def starting_text(dialect: str) -> str:
    return sample_files(dialect)[0].read_text(encoding="utf-8")


def assert_same(path: str, text: str, cache: incremental.LineCache | None) -> incremental.LineCache | None:
    checked, cache = incremental.check_text(path, text, Settings(), None, cache)
    scratch = engine.check_text(path, text, Settings())
    ours, theirs = checked.analysis, scratch.analysis
    assert (ours is None) == (theirs is None)
    if ours is not None:
        assert ours.tree == theirs.tree
        assert (ours.module is None) == (theirs.module is None)
        if ours.module is not None:
            assert ir_print.to_text(ours.module) == ir_print.to_text(theirs.module)
        assert ours.memory == theirs.memory
    assert engine.settle(checked, Settings()) == engine.settle(scratch, Settings())
    return cache


@pytest.mark.parametrize("dialect", sorted(EXTENSIONS))
@EDITS
@given(data=st.data())
def test_incremental_check_matches_check_from_scratch(dialect, data):
    path = f"/edits/program{EXTENSIONS[dialect]}"
    text = data.draw(st.sampled_from(sample_files(dialect))).read_text(encoding="utf-8")
    cache = assert_same(path, text, None)
    words = TOKENS[dialect] + ["\n", "\n\n", " ", "1", "0"]
    for _ in range(data.draw(st.integers(1, 6))):
        start = data.draw(st.integers(0, len(text)))
        end = data.draw(st.integers(start, min(len(text), start + 12)))
        typed = "".join(data.draw(st.lists(st.sampled_from(words), max_size=3)))
        text = text[:start] + typed + text[end:]
        cache = assert_same(path, text, cache)


@pytest.mark.parametrize("dialect", sorted(EXTENSIONS))
def test_an_edit_parses_only_the_lines_it_changed(dialect):
    path = f"/edits/program{EXTENSIONS[dialect]}"
    text = starting_text(dialect)
    cache = assert_same(path, text, None)
    assert cache.parsed == len(set(text.rstrip("\n").split("\n")))  # each distinct line once
    lines = text.split("\n")
    middle = len(lines) // 2
    lines[middle] += "  1"  # one line longer: every line below it moves by three characters
    lines.insert(middle + 1, "   ")  # and down by two
    lines.insert(middle + 1, "   ")
    cache = assert_same(path, "\n".join(lines), cache)
    assert cache.parsed == 2  # the changed line and the new blank line (the second is the same text)


@pytest.mark.parametrize("dialect", sorted(EXTENSIONS))
def test_lines_the_limits_refuse_are_moved_with_their_diagnostics(dialect):
    """A number too long (G030) and a line too long (G007) are reported where they are after the
    lines above them change, as a check from scratch reports them."""
    path = f"/edits/program{EXTENSIONS[dialect]}"
    comment = {"mcode": "'", "arcus": ";", "x150": ";"}[dialect]
    long_number = {"mcode": "MA " + "1" * 60, "arcus": "X" + "1" * 60, "x150": "1D" + "1" * 60}[dialect]
    text = starting_text(dialect) + long_number + "\n" + comment + "x" * 5000 + "\n"
    cache = assert_same(path, text, None)
    cache = assert_same(path, "\n" + text.replace("\n", "\n\n", 1), cache)
    assert_same(path, comment + " moved\n" + text, cache)


def test_a_document_that_changes_dialect_starts_a_new_cache():
    cache = assert_same("/edits/program.mxt", starting_text("mcode"), None)
    checked, other = incremental.check_text("/edits/program.x150", starting_text("x150"), Settings(), None, cache)
    assert other is not cache and other.dialect.name == "x150"


def test_a_stale_check_stops_and_keeps_the_lines_it_parsed():
    path = "/edits/program.prg"
    text = starting_text("arcus")
    checked, cache = incremental.check_text(path, text, Settings(), None, None, stop=lambda: True)
    assert checked is None
    assert cache.parsed == len(set(text.rstrip("\n").split("\n")))
    cache = assert_same(path, text, cache)
    assert cache.parsed == 0


@pytest.mark.parametrize("dialect", sorted(EXTENSIONS))
@settings(max_examples=15, deadline=None,
          suppress_health_check=[HealthCheck.too_slow, HealthCheck.function_scoped_fixture])
@given(data=st.data())
def test_a_check_abandoned_at_any_checkpoint_leaves_a_cache_that_checks_right(dialect, data, monkeypatch):
    """A newer keystroke stops the check at the compiler's next checkpoint (compiler/cancel.py);
    whichever it is, the cache it leaves gives the next version what a check from scratch gives."""
    monkeypatch.setattr(cancel, "EVERY", 1)  # a checkpoint at every line of the lowering
    path = f"/edits/program{EXTENSIONS[dialect]}"
    text = starting_text(dialect)
    cache = assert_same(path, text, None)
    asked = {"count": 0}
    after = data.draw(st.integers(0, len(text.split("\n")) + 3))

    def stop() -> bool:
        asked["count"] += 1
        return asked["count"] > after

    edited = text.replace("\n", "\n\n", 1)
    checked, cache = incremental.check_text(path, edited, Settings(), None, cache, stop)
    assert (checked is None) == (asked["count"] > after)  # stopped at the first "stop"
    assert_same(path, edited.replace("\n", " 1\n", 3), cache)
