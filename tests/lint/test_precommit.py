"""The pre-commit hooks end to end, with the real `pre-commit` (from the `test` extra).

A temporary git repository holds a bad program (a lint error), a badly formatted one and a good
one. `pre-commit try-repo` runs mcc-lint from this repository at its HEAD commit; then the hooks
are installed into the temporary repository, run on chosen files (`pre-commit run`), and real
`git commit`s are made: the bad commit and the unformatted one are blocked, the good one goes
through. pre-commit builds the hook's environment from a local clone; pip fetches mcc's
dependencies (as `pip install` does in CI). `try-repo` builds a new environment on every call
(about 6 s of CPU each), so it runs once; the configured hooks' environment is built once and
shared by every later step (same repository and commit).
"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from conftest import ROOT
from mcc.compiler import dialects

yaml = pytest.importorskip("yaml")  # pre-commit's own dependency
PRE_COMMIT = Path(sys.executable).parent / "pre-commit"
BAD = "PG 1\nLB G1\n  MA 100\n  BR G9\n  E\nPG\nS\n' keep this line\n"  # M106: undefined label (error)
MESSY = "pg 1\nlb G1\nma 100\n   h\n e\npg\ns\n' keep this line\n"
GOOD = "PG 1\nLB G1\n  MA 100\n  H\n  E\nPG\nS\n' keep this line\n"
WARNS = "PG 1\nLB G1\n  MA 100\n  H\n  E\nPG\n"  # only a warning: M309, never saved (lexium-mcode.txt L5269)


def head_commit() -> str | None:
    if shutil.which("git") is None or not (ROOT / ".git").exists():
        return None
    result = subprocess.run(["git", "rev-parse", "HEAD"], cwd=ROOT, capture_output=True, text=True)
    return result.stdout.strip() if result.returncode == 0 else None


def hooks_at_head() -> bool:
    result = subprocess.run(["git", "cat-file", "-e", "HEAD:.pre-commit-hooks.yaml"], cwd=ROOT, capture_output=True)
    return result.returncode == 0


pytestmark = pytest.mark.skipif(not PRE_COMMIT.exists() or head_commit() is None,
                                reason="needs pre-commit (the test extra) and a git checkout of mcc")


def test_hook_file_patterns_match_the_dialect_extensions() -> None:
    import re

    hooks = yaml.safe_load((ROOT / ".pre-commit-hooks.yaml").read_text())
    assert {h["id"] for h in hooks} == {"mcc-lint", "mcc-format"}
    for hook in hooks:
        # --force-exclude: pre-commit names each staged file, and `exclude`/.gitignore must still count
        assert hook["language"] == "python" and hook["entry"] in ("mcc lint --force-exclude", "mcc fmt --force-exclude")
        pattern = re.compile(hook["files"])
        for ext in dialects.all_extensions():
            assert pattern.search(f"dir/program{ext}") and pattern.search(f"PROGRAM{ext.upper()}")
        assert not pattern.search("notes.txt") and not pattern.search("program.mxt.bak")


def git(*args: str, cwd: Path, env: dict) -> subprocess.CompletedProcess:
    return subprocess.run(["git", *args], cwd=cwd, env=env, capture_output=True, text=True, timeout=600)


@pytest.fixture
def project(tmp_path: Path):
    env = {**os.environ, "PRE_COMMIT_HOME": str(tmp_path / "pre-commit-home"), "PRE_COMMIT_COLOR": "never",
           "GIT_AUTHOR_NAME": "t", "GIT_AUTHOR_EMAIL": "t@example.com", "GIT_COMMITTER_NAME": "t",
           "GIT_COMMITTER_EMAIL": "t@example.com", "NO_COLOR": "1"}
    env.pop("GIT_DIR", None)
    env.pop("GIT_INDEX_FILE", None)
    repo = tmp_path / "project"
    repo.mkdir()
    git("init", "-q", cwd=repo, env=env)
    (repo / "bad.mxt").write_text(BAD)
    (repo / "messy.mxt").write_text(MESSY)
    (repo / "good.mxt").write_text(GOOD)
    (repo / "warns.mxt").write_text(WARNS)
    (repo / "mcc.toml").write_text('exclude = ["vendor"]\n')
    (repo / "vendor").mkdir()
    (repo / "vendor" / "theirs.mxt").write_text(BAD)
    return repo, env


def test_bad_commit_is_blocked_and_good_commit_passes(project) -> None:
    if not hooks_at_head():
        pytest.skip(".pre-commit-hooks.yaml is not committed yet")
    repo, env = project
    rev = head_commit()

    def pre_commit(*args: str) -> subprocess.CompletedProcess:
        return subprocess.run([str(PRE_COMMIT), *args], cwd=repo, env=env, capture_output=True, text=True,
                              timeout=900)

    # `try-repo`, how a user tries a hook before configuring it: pre-commit clones this repository at
    # HEAD and builds the hook's environment from that clone (a new one for every try-repo call)
    git("add", "bad.mxt", "good.mxt", cwd=repo, env=env)
    tried = pre_commit("try-repo", str(ROOT), "mcc-lint", "--ref", rev, "--files", "bad.mxt", "good.mxt")
    assert tried.returncode == 1, tried.stdout + tried.stderr
    assert "bad.mxt:4:6: error[M106] label G9 is not defined" in tried.stdout
    git("reset", "-q", cwd=repo, env=env)

    # the hooks as a project configures them: one environment, built once, for every run below
    config = {"repos": [{"repo": str(ROOT), "rev": rev, "hooks": [{"id": "mcc-lint"}, {"id": "mcc-format"}]}]}
    (repo / ".pre-commit-config.yaml").write_text(yaml.safe_dump(config))
    assert pre_commit("install").returncode == 0
    ran = pre_commit("run", "mcc-lint", "--files", "good.mxt")
    assert ran.returncode == 0, ran.stdout + ran.stderr
    ran = pre_commit("run", "mcc-lint", "--files", "warns.mxt")
    assert ran.returncode == 1 and "warning[M309]" in ran.stdout, ran.stdout + ran.stderr  # as ruff's hook
    ran = pre_commit("run", "mcc-lint", "--files", "vendor/theirs.mxt", "good.mxt")
    assert ran.returncode == 0, ran.stdout + ran.stderr  # excluded by mcc.toml, though named

    def commit(name: str) -> subprocess.CompletedProcess:
        git("add", name, cwd=repo, env=env)
        result = git("commit", "-q", "-m", f"add {name}", cwd=repo, env=env)
        git("reset", "-q", cwd=repo, env=env)
        return result

    blocked = commit("bad.mxt")
    assert blocked.returncode != 0 and "M106" in blocked.stdout + blocked.stderr
    unformatted = commit("messy.mxt")
    assert unformatted.returncode != 0 and "files were modified by this hook" in unformatted.stdout + unformatted.stderr
    assert (repo / "messy.mxt").read_text() == GOOD  # mcc fmt rewrote it
    passed = commit("good.mxt")
    assert passed.returncode == 0, passed.stdout + passed.stderr
    log = git("log", "--format=%s", cwd=repo, env=env).stdout.split("\n")
    assert log[0] == "add good.mxt" and "add bad.mxt" not in log
