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


# -- how the suite is spread over the workers (issue 26) ------------------------------------------
# pyproject runs `-n auto --dist loadfile --no-loadscope-reorder`: xdist hands the work out in
# units, in the order collected here, each worker taking the next unit when it is nearly idle. A
# file's tests are one unit (its module fixtures, an editor or a language server, start once),
# except in the files of SPREAD, whose tests are independent and slow: each of their tests is a unit
# of its own, so both cores share them (`pytest_xdist_make_scheduler`; xdist's own `loadgroup`
# cannot be used for this: with pytest 9 its group names never reach the scheduler). The units that
# take longest go first (SLOW_FIRST), so that the last units handed out are short and no worker is
# left running a long test while the other has nothing to do.

SPREAD = frozenset({  # paths relative to tests/
    "test_codegen_random.py",  # one random program per test; a print loop's (mcode seed 20) is most of it
    "test_cross.py",  # every sample and golden program to every other dialect, each validated
    "link/test_device_sim.py",  # each sample on a virtual device over a socket: 20 tests of up to 7 s
    "x150/test_x150_generated.py",  # 60 generated programs in 3 shards, each compiled twice and validated
    "arcus/test_structure.py",  # 200 random programs in 4 shards through the structurer, each validated
})
# Test-id prefixes (relative to tests/), slowest first; the rest keep their collected order after
# them. Measured (wall seconds of the unit, `--durations`, 2 workers, load 3-8, 2026-11-27 12:17):
# refine it from a `--durations=0` run when a slow test is added.
SLOW_FIRST = (
    "lint/test_precommit.py",  # 213 s: pre-commit builds the hook's environment (pip), once for the file
    "x150/test_x150_generated.py",  # 187 s: 60 generated programs compiled twice, each validated
    "arcus/test_structure.py",  # 134 s: random programs through the structurer, each validated
    "editors/test_vscode_codeserver.py",  # a real VS Code in a browser, started once for the file (CI)
    "test_codegen_random.py::test_random_programs_validate_or_refuse_at_a_line[mcode-20]",  # 69 s
    "link/test_device_sim.py",  # 250 s in 20 tests (SPREAD)
    "test_limits.py",  # 54 s
    "test_no_cycles.py",  # 49 s
    "lsp/test_formatting_equals_fmt.py",  # 48 s
    "opt/test_levels.py",  # 46 s
    "lsp/test_features.py",  # 42 s
    "lsp/test_neovim.py",  # 40 s
    "lsp/test_fuzz_features.py",  # 40 s
    "ir/test_ir_read.py",  # 34 s
    "test_cross.py::test_cross_compilation_is_right_or_refuses[x150-mcode-nesting",  # 14 s and 11 s
    "editors/test_neovim_completion.py",  # 28 s
    "opt/test_random.py",  # 27 s
)


def _slow_rank(relative: str) -> int:
    for rank, prefix in enumerate(SLOW_FIRST):
        if relative.startswith(prefix):
            return rank
    return len(SLOW_FIRST)


def pytest_collection_modifyitems(config, items) -> None:
    """The slow units first (SLOW_FIRST), each file's tests still in their order."""
    tests = Path(__file__).resolve().parent
    ranked = []
    for index, item in enumerate(items):
        path = Path(item.path)
        relative = path.relative_to(tests).as_posix() if path.is_relative_to(tests) else path.as_posix()
        ranked.append((_slow_rank(f"{relative}::{item.nodeid.partition('::')[2]}"), index, item))
    items[:] = [item for _, _, item in sorted(ranked, key=lambda entry: entry[:2])]


def work_unit(nodeid: str) -> str:
    """The unit of work a test belongs to: its file, or the test itself in a SPREAD file."""
    path = nodeid.split("::", 1)[0]  # relative to the root directory, where pyproject.toml is
    return nodeid if path.removeprefix("tests/") in SPREAD else path


def pytest_xdist_make_scheduler(config, log):
    """`--dist loadfile`, except that each test of a SPREAD file is a unit of its own."""
    if config.getvalue("dist") != "loadfile":
        return None  # another --dist given on the command line: xdist's own
    from xdist.scheduler import LoadFileScheduling

    class FileOrTestScheduling(LoadFileScheduling):
        def _split_scope(self, nodeid: str) -> str:
            return work_unit(nodeid)

    return FileOrTestScheduling(config, log)


@pytest.fixture(autouse=True, scope="session")
def _no_reconnect_pause_on_socket_ports():
    """pyserial's socket:// port sleeps 0.3 s when it closes ("in case of quick reconnects, give
    the server some time"), for network serial servers slow to accept again. The virtual devices
    the link tests talk to (tests/link/linkhelpers.py, in this process) accept at once, and a test
    of a download closes its port up to twenty times: 6 s of sleep in one test. The pause is skipped
    here; mcc itself keeps pyserial's behaviour with real servers."""
    try:
        from serial.urlhandler import protocol_socket
    except ImportError:
        yield
        return
    original = protocol_socket.time
    protocol_socket.time = type("NoPause", (), {"sleep": staticmethod(lambda seconds: None)})
    try:
        yield
    finally:
        protocol_socket.time = original
