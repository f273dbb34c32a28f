"""The engine's guarantees: no traceback from any input or any rule, sequential runs for one file,
progress only on a terminal, the target table of the configuration."""

from __future__ import annotations

import io
import sys
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from conftest import EXTENSIONS, dialects_with, sample_files
from mcc.compiler import config
from mcc.compiler.config import Settings
from mcc.compiler.lint import engine, rules

ALPHABET = st.characters(codec="utf-8", exclude_categories=("Cs",))


def mutate(text: str, data) -> str:
    for kind, pos, piece in data.draw(st.lists(st.tuples(st.integers(0, 2), st.integers(0, len(text)),
                                                         st.text(ALPHABET, max_size=4)), max_size=6)):
        if kind == 0:
            text = text[:pos] + piece + text[pos:]
        elif kind == 1:
            text = text[:pos] + text[pos + len(piece) + 1:]
        else:
            text = text[:pos] + text[pos:pos + 12] + text[pos:]
    return text


@pytest.mark.parametrize("dialect", dialects_with("frontend"))
@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(data=st.data())
def test_lint_and_fmt_never_crash_on_mutated_samples(dialect: str, data) -> None:
    from mcc.compiler.lint.formatting import format_text

    samples = sample_files(dialect)
    text = mutate(data.draw(st.sampled_from(samples)).read_text(encoding="utf-8"), data)
    path = f"f{EXTENSIONS[dialect]}"
    _, diags = engine.lint_text(path, text, Settings())
    assert not [d.message for d in diags if d.code == "G001"]
    once = format_text(text, path, dialect)
    assert format_text(once, path, dialect) == once


def test_a_failing_rule_becomes_an_internal_error_and_the_others_still_run(monkeypatch) -> None:
    def broken(ctx):
        raise RuntimeError("boom")

    rules.load("mcode")
    original = rules.RULES["M311"]
    monkeypatch.setitem(rules.RULES, "M311", rules.Rule("M311", ("mcode",), broken))
    _, diags = engine.lint_text("p.mxt", "VA Q1\nPG 1\nLB G1\n  E\nPG\nS\n' k\n", Settings())
    found = {d.code: d for d in diags}
    assert "G001" in found and "running lint rule M311" in found["G001"].message
    assert "M306" in found  # another rule still reported
    assert original.code == "M311"


def test_one_file_or_one_job_never_starts_a_pool(monkeypatch, tmp_path: Path) -> None:
    def no_pool(*args, **kwargs):
        raise AssertionError("a process pool was started")

    monkeypatch.setattr(engine, "ProcessPoolExecutor", no_pool)
    paths = []
    for i in range(3):
        path = tmp_path / f"p{i}.mxt"
        path.write_text("VA Q1\nPR Q1\n")
        paths.append((str(path), Settings()))
    assert len(engine.run(paths[:1], engine.Options(), jobs=4)) == 1
    assert len(engine.run(paths, engine.Options(), jobs=1)) == 3


def test_progress_bar_only_on_a_terminal(monkeypatch) -> None:
    from mcc.cli import lint as cli_lint

    class Terminal(io.StringIO):
        def isatty(self) -> bool:
            return True

    monkeypatch.setattr(sys, "stderr", io.StringIO())
    assert cli_lint.progress_starter(500, "linting") is None  # not a terminal
    terminal = Terminal()
    monkeypatch.setattr(sys, "stderr", terminal)
    assert cli_lint.progress_starter(5, "linting") is None  # a short run
    start = cli_lint.progress_starter(50, "linting")
    advance = start()
    advance(25)
    advance(25)
    assert "linting" in terminal.getvalue()


def test_target_per_dialect(tmp_path: Path) -> None:
    (tmp_path / "mcc.toml").write_text('[target]\nmcode = "lmm"\narcus = "pmx-4ex-sa"\n')
    settings = config.Resolver().for_path(str(tmp_path / "x.mxt"))
    assert settings.profile("mcode").name == "lmm"
    assert settings.profile("arcus").name == "pmx-4ex-sa"
    assert settings.profile("x150") is None


def test_target_for_the_wrong_dialect_is_reported(tmp_path: Path) -> None:
    path = tmp_path / "mcc.toml"
    path.write_text('[target]\nmcode = "pmx-4ex-sa"\n')
    [diag] = config.parse(path.read_text(), str(path)).diagnostics
    assert diag.code == "G103" and diag.span.line == 2 and "for arcus" in diag.message
