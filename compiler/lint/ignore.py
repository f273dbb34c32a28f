"""Which files `mcc lint` and `mcc fmt` leave alone: the configuration's `exclude` and `.gitignore`.

Both use git's own pattern language (gitwildmatch), matched by the `pathspec` library rather than
by hand: `build` skips every file or directory named build, `/build` only the one next to the
pattern's file, `build/` only directories, `vendor/*.mxt` files directly in vendor, `**/gen/*`
any depth, `!keep.mxt` takes a file back. `exclude` patterns are relative to the directory of the
configuration file that sets them (docs/CONFIGURATION.md).

`.gitignore` is read as git reads it, and only inside a git work tree (a directory with `.git`
above the file, as ruff does): every `.gitignore` from the work tree's root down to the file's
directory, the deeper one deciding, plus `.git/info/exclude`. A file inside an ignored directory
is ignored whatever the patterns say about the file itself (git does not look inside it either).
"""

from __future__ import annotations

import os
from functools import lru_cache
from pathlib import Path

import pathspec


@lru_cache(maxsize=None)
def spec(patterns: tuple[str, ...]) -> pathspec.GitIgnoreSpec:
    return pathspec.GitIgnoreSpec.from_lines(patterns)


def matches(patterns: tuple[str, ...], rel: str, is_dir: bool = False) -> bool:
    """Whether `rel` (a POSIX path relative to the patterns' directory) is excluded by them."""
    if not patterns:
        return False
    compiled = spec(patterns)
    parts = rel.strip("/").split("/")
    for n in range(1, len(parts)):  # an excluded directory excludes everything inside it
        if compiled.match_file("/".join(parts[:n]) + "/"):
            return True
    return compiled.match_file(rel.strip("/") + ("/" if is_dir else ""))


@lru_cache(maxsize=None)
def work_tree(directory: str) -> str | None:
    """The root of the git work tree holding `directory` (absolute), or None outside one."""
    current = Path(directory)
    for folder in (current, *current.parents):
        if (folder / ".git").exists():
            return str(folder)
    return None


@lru_cache(maxsize=None)
def patterns_in(path: str) -> pathspec.GitIgnoreSpec | None:
    """The patterns of one ignore file (None when it does not exist or cannot be read)."""
    try:
        with open(path, encoding="utf-8", errors="replace") as handle:
            return pathspec.GitIgnoreSpec.from_lines(handle.read().splitlines())
    except OSError:
        return None


def gitignored(path: str, is_dir: bool | None = None, within: str | None = None) -> bool:
    """Whether git ignores `path` (a file or directory) by a `.gitignore` of its work tree.

    `within` is the directory a search started from: it and its parents are not judged (a
    directory named on the command line is searched even when git ignores it, as ruff does;
    `--force-exclude` judges it by itself)."""
    full = os.path.abspath(path)
    if is_dir is None:
        is_dir = os.path.isdir(full)
    root = work_tree(full if is_dir else os.path.dirname(full))
    if root is None or full == root:
        return False
    rel = Path(full).relative_to(root).parts
    if ".git" in rel:
        return True
    skip = 0
    if within is not None:
        try:
            skip = len(Path(os.path.abspath(within)).relative_to(root).parts)
        except ValueError:
            skip = 0
    # every directory between the root and the path, then the path itself: the first ignored one wins
    for n in range(skip + 1, len(rel) + 1):
        last = n == len(rel)
        if decided(root, rel[:n], is_dir or not last, skip):
            return True
    return False


def decided(root: str, parts: tuple[str, ...], is_dir: bool, exempt: int = 0) -> bool:
    """Whether the ignore files from `root` down to the parent of `parts` ignore it: the deepest
    file with a matching pattern decides, as in git; `.git/info/exclude` comes below them all.
    The first `exempt` directories of `parts` are not judged: a pattern that matches one of them
    (and so everything below it) does not count."""
    candidates = [(os.path.join(root, ".git", "info", "exclude"), ())]
    for depth in range(len(parts)):
        candidates.append((os.path.join(root, *parts[:depth], ".gitignore"), parts[:depth]))
    for ignore_file, base in reversed(candidates):
        compiled = patterns_in(ignore_file)
        if compiled is None:
            continue
        rel = "/".join(parts[len(base):]) + ("/" if is_dir else "")
        spared = ["/".join(parts[len(base):k]) + "/" for k in range(len(base) + 1, exempt + 1)]
        include = verdict(compiled, rel, spared)
        if include is not None:
            return include
    return False


def verdict(compiled: pathspec.GitIgnoreSpec, rel: str, spared: list[str]) -> bool | None:
    """True (ignored), False (taken back by `!`) or None (no pattern speaks of `rel`)."""
    if not spared:
        result = compiled.check_file(rel)
        return None if result.include is None else bool(result.include)
    include = None
    for pattern in compiled.patterns:
        if pattern.include is None or pattern.match_file(rel) is None:
            continue
        if any(pattern.match_file(d) is not None for d in spared):
            continue
        include = bool(pattern.include)
    return include
