"""A check the profile turns off is skipped by its needs, and one it makes an error reports errors
(docs/decisions/0021: a check's applicability is declared, not tested inside it)."""

from __future__ import annotations

from pathlib import Path

import pytest

from mcc.compiler import checks, driver, profiles

LONG_COMMENT = "VA Q1\nQ1=2 ' a comment that makes the line longer than sixty-four chars\n"
APOSTROPHE = "GOSUB 1 '***Pen Up\nEND\nSUB 1\nDO1=0\nENDSUB\n"


def profile_file(tmp_path: Path, base: str, body: str) -> profiles.Profile:
    path = tmp_path / "mine.toml"
    path.write_text(f'extends = "{base}"\nname = "mine"\n' + body, encoding="utf-8")
    return profiles.load(str(path))


@pytest.mark.parametrize("policy,expected", [("warn", ["warning"]), ("error", ["error"]), ("ignore", [])])
def test_comment_overflow_follows_the_profile(tmp_path, policy, expected):
    """lexium-mcode.txt L626: a line holds 64 characters; whether a comment past them is reported
    is the profile's `mcode.comment_line_policy`."""
    prof = profile_file(tmp_path, "lmd-c", f'[mcode]\ncomment_line_policy = "{policy}"\n')
    result = driver.check_file("p.mxt", "mcode", prof, text=LONG_COMMENT)
    assert [d.severity.value for d in result.diagnostics if d.code == "M110"] == expected


@pytest.mark.parametrize("policy,expected", [("warn", ["warning"]), ("error", ["error"]), ("ignore", [])])
def test_apostrophe_comments_follow_the_profile(tmp_path, policy, expected):
    """arcus-pmx-4ex-sa.txt L1721: the comment is ';'; "'" (L1201, the DXF converter's) is reported
    as the profile's `arcus.apostrophe_comments` says."""
    prof = profile_file(tmp_path, "pmx-4ex-sa", f'[arcus]\napostrophe_comments = "{policy}"\n')
    result = driver.check_file("p.prg", "arcus", prof, text=APOSTROPHE)
    assert [d.severity.value for d in result.diagnostics if d.code == "A127"] == expected


def test_a_check_whose_needs_are_missing_is_not_run(monkeypatch):
    """lexium-mcode.txt L2779: M106 is about branch targets; a file without any is not looked at."""
    ran = []
    checks.load("mcode")
    found = checks.CHECKS["M106"]
    monkeypatch.setitem(checks.CHECKS, "M106", checks.Check(found.code, found.dialect, ran.append, found.needs,
                                                            found.also))
    driver.check_file("p.mxt", "mcode", text="VA Q1\nQ1=1\n")
    assert ran == []
    driver.check_file("p.mxt", "mcode", text="PG 100\nLB G1\n  BR G1\nPG\n")
    assert len(ran) == 1
