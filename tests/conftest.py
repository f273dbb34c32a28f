"""Shared helpers for mcc's tests. Tests never read ../shared/: fixtures live in tests/ and samples/."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest
from hypothesis import settings

# With CI set, the property tests draw the same examples on every run, so a landing never fails on
# an example nobody has seen; local runs explore new examples and keep any failure in .hypothesis/.
settings.register_profile("ci", derandomize=True, print_blob=True)
if os.environ.get("CI"):
    settings.load_profile("ci")

ROOT = Path(__file__).resolve().parent.parent
SAMPLES = ROOT / "samples"
GOLDEN = Path(__file__).resolve().parent / "golden"
EXTENSIONS = {"mcode": ".mxt", "arcus": ".prg", "x150": ".x150"}


def run_mcc(*args: str, input: str | None = None, cwd: Path | None = None) -> subprocess.CompletedProcess:
    """Run the installed `mcc` command the way a user does."""
    exe = Path(sys.executable).parent / "mcc"
    cmd = [str(exe)] if exe.exists() else [sys.executable, "-m", "mcc"]
    env = {**os.environ, "NO_COLOR": "1"}
    return subprocess.run(cmd + list(args), capture_output=True, text=True, input=input, cwd=cwd, env=env,
                          timeout=120)


def implemented(dialect: str, part: str = "frontend") -> bool:
    """Whether a dialect's frontend (or backend) exists yet; the shared tests cover every one that does."""
    import importlib.util

    from mcc.compiler import dialects

    info = dialects.get(dialect)
    return importlib.util.find_spec(info.frontend if part == "frontend" else info.backend) is not None


def dialects_with(part: str = "frontend") -> list[str]:
    return [d for d in EXTENSIONS if implemented(d, part) and implemented(d, "frontend")]


def sample_files(dialect: str) -> list[Path]:
    return sorted((SAMPLES / dialect).glob(f"*{EXTENSIONS[dialect]}"))


@pytest.fixture
def mcc():
    return run_mcc


@pytest.hookimpl(hookwrapper=True)
def pytest_runtest_makereport(item, call):
    """Keep each test's outcome on its item, so that a failing editor test can leave a screenshot
    and the extension's log behind (tests/editors/test_vscode_codeserver.py's `editor` fixture).
    It lives here, not in a tests/editors/conftest.py: a second module named `conftest` would
    shadow this one for the tests that import from it."""
    outcome = yield
    report = outcome.get_result()
    if report.when == "call":
        item.call_report = report
