"""noqa comments in each dialect's comment syntax; unused and unknown suppressions are reported."""

from __future__ import annotations

from helpers import codes, lint
from mcc.compiler.config import Layer, Selection, Settings
from mcc.compiler.lint import fixes, suppress
from mcc.compiler.span import SourceFile

MOVE_READ = "PG 1\nLB G1\n  MA 100\n  PR P{comment}\n  H\n  E\nPG\nS\n' keep\n"


def test_apostrophe_and_backtick_suppress_the_named_code() -> None:
    assert "M301" in codes(MOVE_READ.format(comment=""))
    assert "M301" not in codes(MOVE_READ.format(comment="   ' noqa: M301"))
    assert "M301" not in codes(MOVE_READ.format(comment="   `noqa:M301"))
    assert "M301" not in codes(MOVE_READ.format(comment="   ` NOQA: m301, M305"))


def test_bare_noqa_suppresses_everything_on_the_line() -> None:
    found = codes(MOVE_READ.format(comment=" ' noqa"))
    assert "M301" not in found and "G101" not in found


def test_other_codes_are_not_suppressed() -> None:
    found = codes(MOVE_READ.format(comment=" ' noqa: M305"))
    assert "M301" in found
    assert "G101" in found  # M305 is not reported on that line


def test_noqa_inside_a_string_is_not_a_comment() -> None:
    text = 'PG 1\nLB G1\n  MA 100\n  PR P,"\' noqa"\n  H\n  E\nPG\nS\n\' keep\n'
    assert "M301" in codes(text)


def test_noqa_only_covers_its_own_line() -> None:
    text = "PG 1\nLB G1 ' noqa\n  MA 100\n  PR P\n  H\n  E\nPG\nS\n' keep\n"
    found = codes(text)
    assert "M301" in found and "G101" in found


def test_syntax_errors_cannot_be_suppressed() -> None:
    assert "M001" in codes("MA (1 ' noqa: M001\n")


def test_check_diagnostics_can_be_suppressed() -> None:
    assert "M101" in codes("MX 1\n")
    assert codes("MX 1 ' noqa: M101\n") == []


def test_unused_suppression_fix_keeps_used_codes_and_other_text() -> None:
    text = MOVE_READ.format(comment="   ' check this  noqa: M301, M305")
    diag = next(d for d in lint(text) if d.code == "G101")
    assert "M305" in diag.message and diag.fix.safe
    fixed, _ = fixes.apply(text, [diag.fix])
    assert "  PR P   ' check this  noqa: M301\n" in fixed


def test_unused_suppression_fix_removes_a_comment_that_is_only_noqa() -> None:
    text = "PG 1\nLB G1\n  MA 100   ' noqa: M301\n  H\n  E\nPG\nS\n' keep\n"
    diag = next(d for d in lint(text) if d.code == "G101")
    fixed, _ = fixes.apply(text, [diag.fix])
    assert "  MA 100\n" in fixed


def test_unknown_code_is_reported_not_unused() -> None:
    text = "PG 1\nLB G1\n  MA 100   ' noqa: M3O1\n  H\n  E\nPG\nS\n' keep\n"
    found = codes(text)
    assert "G104" in found and "G101" not in found


def test_unused_suppression_can_be_ignored() -> None:
    settings = Settings(selection=Selection((Layer(select=("ALL",), ignore=("G101",)),)))
    assert "G101" not in codes(MOVE_READ.format(comment=" ' noqa: M305"), settings=settings)


def test_suppressing_a_disabled_code_is_unused() -> None:
    settings = Settings(selection=Selection((Layer(select=("ALL",), ignore=("M301",)),)))
    assert "G101" in codes(MOVE_READ.format(comment=" ' noqa: M301"), settings=settings)


def test_directives_in_arcus_and_x150_comment_syntax() -> None:
    for dialect in ("arcus", "x150"):
        source = SourceFile("f", 'X1000 ; noqa: A301, X302\n"text ; noqa" ; plain\n; noqa\n')
        found = suppress.find_directives(source, dialect)
        assert sorted(found) == [1, 3]
        assert list(found[1].codes) == ["A301", "X302"] and found[3].bare
