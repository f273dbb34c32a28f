"""Which files `mcc lint` and `mcc fmt` work on: `.gitignore`, `exclude` (git's pattern language,
matched by pathspec) and `--force-exclude` for files named on the command line, run as a user runs
`mcc` (docs/LINT.md, "Files and directories"). Programs are MCode; "MX 1" is an unknown command
(an error), "VA Q1\\nPR Q1\\n" is clean (lexium-mcode.txt: VA declares a variable, PR prints)."""

from __future__ import annotations

from pathlib import Path

from conftest import run_mcc

BAD = "MX 1\n"
CLEAN = "VA Q1\nPR Q1\n"
MESSY = "va Q1\npr Q1\n"


def write(path: Path, text: str) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(text, encoding="utf-8")


def work_tree(tmp_path: Path) -> Path:
    """A git work tree as mcc recognises one (a `.git` directory at its root)."""
    (tmp_path / ".git").mkdir()
    return tmp_path


def linted(result) -> set[str]:
    return {line.split(":", 1)[0] for line in result.stdout.splitlines() if ": error[" in line}


def test_gitignore_skips_files_and_directories_in_a_work_tree(tmp_path: Path) -> None:
    root = work_tree(tmp_path)
    write(root / ".gitignore", "build/\n*.gen.mxt\n!keep.gen.mxt\n")
    write(root / "build" / "out.mxt", BAD)
    write(root / "src" / "a.gen.mxt", BAD)
    write(root / "src" / "keep.gen.mxt", BAD)
    write(root / "src" / "deep" / ".gitignore", "local.mxt\n")
    write(root / "src" / "deep" / "local.mxt", BAD)
    write(root / "src" / "ok.mxt", BAD)
    result = run_mcc("lint", ".", cwd=root)
    assert linted(result) == {"src/keep.gen.mxt", "src/ok.mxt"}, result.stdout
    assert "in 2 files" in result.stdout
    everything = run_mcc("lint", "--no-respect-gitignore", ".", cwd=root)
    assert len(linted(everything)) == 5, everything.stdout


def test_gitignore_counts_only_inside_a_git_work_tree(tmp_path: Path) -> None:
    write(tmp_path / ".gitignore", "*.mxt\n")
    write(tmp_path / "a.mxt", BAD)
    assert linted(run_mcc("lint", ".", cwd=tmp_path)) == {"a.mxt"}


def test_exclude_uses_gitignore_patterns_relative_to_the_configuration(tmp_path: Path) -> None:
    write(tmp_path / "mcc.toml", 'exclude = ["/top.mxt", "vendor/*.mxt", "gen", "!gen/keep.mxt"]\n')
    write(tmp_path / "top.mxt", BAD)
    write(tmp_path / "sub" / "top.mxt", BAD)  # "/top.mxt" is anchored at the configuration's directory
    write(tmp_path / "vendor" / "v.mxt", BAD)
    write(tmp_path / "vendor" / "inner" / "w.mxt", BAD)  # "*" does not cross "/"
    write(tmp_path / "a" / "gen" / "g.mxt", BAD)  # no slash: a name at any depth
    result = run_mcc("lint", ".", cwd=tmp_path)
    assert linted(result) == {"sub/top.mxt", "vendor/inner/w.mxt"}, result.stdout


def test_force_exclude_applies_exclude_to_files_named_on_the_command_line(tmp_path: Path) -> None:
    """pre-commit names every staged file: without --force-exclude an excluded file is linted."""
    write(tmp_path / "mcc.toml", 'exclude = ["vendor"]\n')
    write(tmp_path / "vendor" / "v.mxt", BAD)
    write(tmp_path / "ok.mxt", CLEAN)
    named = run_mcc("lint", "vendor/v.mxt", "ok.mxt", cwd=tmp_path)
    assert named.returncode == 1 and linted(named) == {"vendor/v.mxt"}
    forced = run_mcc("lint", "--force-exclude", "vendor/v.mxt", "ok.mxt", cwd=tmp_path)
    assert forced.returncode == 0 and "No problems found in 1 file." in forced.stdout, forced.stdout


def test_force_exclude_applies_gitignore_to_named_files_and_to_fmt(tmp_path: Path) -> None:
    root = work_tree(tmp_path)
    write(root / ".gitignore", "generated/\n")
    write(root / "generated" / "g.mxt", MESSY)
    assert run_mcc("fmt", "--force-exclude", "generated/g.mxt", cwd=root).returncode == 0
    assert (root / "generated" / "g.mxt").read_text() == MESSY  # left alone
    assert run_mcc("fmt", "generated/g.mxt", cwd=root).returncode == 0
    assert (root / "generated" / "g.mxt").read_text() == CLEAN  # named without the flag: formatted


def test_force_exclude_with_standard_input(tmp_path: Path) -> None:
    """An editor passes the buffer's name: an excluded file is neither reported nor reformatted."""
    write(tmp_path / "mcc.toml", 'exclude = ["vendor"]\n')
    args = ["-", "--stdin-filename", "vendor/v.mxt", "--force-exclude"]
    linted_stdin = run_mcc("lint", *args, input=BAD, cwd=tmp_path)
    assert linted_stdin.returncode == 0 and linted_stdin.stdout == ""
    formatted = run_mcc("fmt", *args, input=MESSY, cwd=tmp_path)
    assert formatted.returncode == 0 and formatted.stdout == MESSY
    reported = run_mcc("lint", "-", "--stdin-filename", "vendor/v.mxt", input=BAD, cwd=tmp_path)
    assert reported.returncode == 1 and "vendor/v.mxt:1:1: error[" in reported.stdout


def test_a_directory_named_on_the_command_line_is_searched_even_if_git_ignores_it(tmp_path: Path) -> None:
    """As ruff: a path given explicitly is worked on; what lies below it is still judged."""
    root = work_tree(tmp_path)
    write(root / ".gitignore", "build/\n*.tmp.mxt\n")
    write(root / "build" / "out.mxt", BAD)
    write(root / "build" / "x.tmp.mxt", BAD)
    assert linted(run_mcc("lint", "build", cwd=root)) == {"build/out.mxt"}
    forced = run_mcc("lint", "--force-exclude", "build", cwd=root)
    assert forced.returncode == 0 and linted(forced) == set()
