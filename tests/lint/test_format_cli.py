"""`mcc fmt` end to end: writes only on change, --check and --diff, the meaning-preserving
safety net, dialects without a formatter."""

from __future__ import annotations

from pathlib import Path

from conftest import run_mcc
from mcc.compiler.config import Settings
from mcc.compiler.lint import formatting

MESSY = "pg 1\n lb G1\nma 100   ` go\n  h\npg\n"
TIDY = "PG 1\nLB G1\n  MA 100                ` go\n  H\nPG\n"


def test_fmt_rewrites_files_in_place(tmp_path: Path) -> None:
    (tmp_path / "a.mxt").write_text(MESSY)
    (tmp_path / "b.mxt").write_text(TIDY)
    result = run_mcc("fmt", ".", cwd=tmp_path)
    assert result.returncode == 0
    assert (tmp_path / "a.mxt").read_text() == TIDY
    assert "1 file reformatted, 1 file left unchanged" in result.stdout


def test_check_lists_files_and_fails_without_writing(tmp_path: Path) -> None:
    (tmp_path / "a.mxt").write_text(MESSY)
    result = run_mcc("fmt", "--check", "a.mxt", cwd=tmp_path)
    assert result.returncode == 1
    assert "Would reformat: a.mxt" in result.stdout
    assert (tmp_path / "a.mxt").read_text() == MESSY
    (tmp_path / "a.mxt").write_text(TIDY)
    assert run_mcc("fmt", "--check", "a.mxt", cwd=tmp_path).returncode == 0


def test_diff_shows_the_change(tmp_path: Path) -> None:
    (tmp_path / "a.mxt").write_text(MESSY)
    result = run_mcc("fmt", "--diff", "a.mxt", cwd=tmp_path)
    assert result.returncode == 1
    assert "--- a/a.mxt\n+++ b/a.mxt\n" in result.stdout and "-ma 100   ` go\n" in result.stdout
    assert "+  MA 100                ` go\n" in result.stdout
    assert (tmp_path / "a.mxt").read_text() == MESSY


def test_unchanged_files_are_not_touched(tmp_path: Path) -> None:
    path = tmp_path / "a.mxt"
    path.write_text(TIDY)
    stamp = path.stat().st_mtime_ns - 10**9
    import os

    os.utime(path, ns=(stamp, stamp))
    run_mcc("fmt", str(path))
    assert path.stat().st_mtime_ns == stamp


def test_crlf_files_stay_crlf(tmp_path: Path) -> None:
    path = tmp_path / "a.mxt"
    path.write_bytes(MESSY.replace("\n", "\r\n").encode())
    run_mcc("fmt", str(path))
    assert path.read_bytes() == TIDY.replace("\n", "\r\n").encode()


def test_a_formatter_that_would_change_meaning_is_refused(tmp_path: Path, monkeypatch) -> None:
    path = tmp_path / "a.mxt"
    path.write_text(MESSY)
    module = formatting.formatter("mcode")
    monkeypatch.setattr(module, "format_text", lambda text, p, prof, strict=False: text.replace("100", "101"))
    outcome = formatting.format_file(str(path), Settings())
    assert "would change the program" in outcome.error and not outcome.written
    assert path.read_text() == MESSY


def test_parallel_fmt(tmp_path: Path) -> None:
    for i in range(25):
        (tmp_path / f"p{i}.mxt").write_text(MESSY)
    result = run_mcc("fmt", "-j", "2", ".", cwd=tmp_path)
    assert result.returncode == 0 and "25 files reformatted" in result.stdout
    assert all(p.read_text() == TIDY for p in tmp_path.glob("*.mxt"))


def test_dialects_without_a_formatter_are_reported_and_left_alone(tmp_path: Path) -> None:
    missing = [d for d in ("arcus", "x150") if formatting.formatter(d) is None]
    if not missing:
        return  # every dialect has a formatter now
    ext = {"arcus": ".prg", "x150": ".x150"}[missing[0]]
    (tmp_path / f"p{ext}").write_text("anything\n")
    result = run_mcc("fmt", ".", cwd=tmp_path)
    assert result.returncode == 0
    assert f"no {missing[0]} formatter yet" in result.stderr
    assert (tmp_path / f"p{ext}").read_text() == "anything\n"
