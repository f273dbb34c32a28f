"""`mcc debug` driven end to end by a real DAP client: DebugClient from Microsoft's
@vscode/debugadapter-testsupport (npm), the client VS Code's own debug adapters are tested with.
tests/debug/e2e/session.test.mjs runs the issue's session on a program of each dialect (a
breakpoint in a loop, the position and a variable, step into a subroutine or X150 sequence, an
input changed, on to the end) under `node --test`.

nvim-dap, the client the issue names, cannot be installed here: it is a Lua plugin published only
on GitHub (no npm, PyPI or Debian package), and Debian 12's Neovim (0.7.2) is older than the one
it needs (docs/EDITORS.md, "Debugging"). `.ci/run` installs the npm package (`npm ci` in
tests/debug/e2e); on a machine without it, this test is skipped, except under CI, where it fails.
"""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

E2E = Path(__file__).parent / "e2e"
NODE = shutil.which("node")
INSTALLED = (E2E / "node_modules" / "@vscode" / "debugadapter-testsupport").is_dir()
MISSING = None if NODE and INSTALLED else (
    "node and the DAP test client are not installed: run `npm ci` in tests/debug/e2e (.ci/run does)")

pytestmark = pytest.mark.skipif(MISSING is not None and not os.environ.get("CI"), reason=MISSING or "")


def test_vscode_debug_client_runs_the_session_in_each_dialect():
    assert MISSING is None, MISSING
    mcc = Path(sys.executable).with_name("mcc")
    from test_debug_protocol import PROGRAMS, other_branch

    flipped = {p.file: other_branch(p) for p in PROGRAMS.values()}
    env = {**os.environ, "MCC": str(mcc), "MCC_FLIPPED_BRANCH": json.dumps(flipped)}
    done = subprocess.run([NODE, "--test", "session.test.mjs"], cwd=E2E, env=env, capture_output=True,
                          text=True, timeout=300)
    assert done.returncode == 0, done.stdout[-4000:] + done.stderr[-2000:]
    assert "# pass 3" in done.stdout and "# fail 0" in done.stdout
