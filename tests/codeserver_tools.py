"""Where the tests that drive a real VS Code (code-server under headless Chromium) find their tools,
and which are missing: one definition for the editor test (tests/editors/test_vscode_codeserver.py)
and the debugging test (tests/debug/test_debug_vscode_editor.py). .ci/run installs them with
editors/vscode/tests/codeserver/install.sh."""

from __future__ import annotations

import os
import shutil
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
EXTENSION = ROOT / "editors" / "vscode"
VSIX = EXTENSION / "mcc-motion.vsix"
INSTALL_SCRIPT = EXTENSION / "tests" / "codeserver" / "install.sh"
CODE_SERVER = Path(os.environ.get(
    "MCC_CODE_SERVER", EXTENSION / "tests" / "codeserver" / "node_modules" / "code-server" / "out" / "node" / "entry.js"))
# install.sh puts Node.js 20 (code-server's) in node20/ where the machine's node is another version
NODE20 = sorted((EXTENSION / "tests" / "codeserver" / "node20" / "node_modules").glob("node-linux-*/bin/node"))
NODE = str(NODE20[0]) if NODE20 else shutil.which("node")
CHROMIUM = shutil.which("chromium") or "/usr/bin/chromium"
# The flags the machine needs: without the background-networking ones Chromium keeps trying hosts
# this closed network refuses.
CHROMIUM_ARGS = ["--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run", "--disable-sync",
                 "--disable-background-networking", "--disable-component-update"]
MCC = Path(sys.executable).parent / "mcc"


def missing_tools() -> list[str]:
    """The tools a code-server test needs that this machine lacks, named for the message."""
    missing = []
    if NODE is None:
        missing.append("node")
    if not CODE_SERVER.is_file():
        missing.append(f"code-server ({CODE_SERVER})")
    if not Path(CHROMIUM).is_file():
        missing.append("chromium")
    try:
        import playwright.sync_api  # noqa: F401
    except ImportError:
        missing.append("playwright (Python)")
    if not VSIX.is_file():
        missing.append(f"the extension package {VSIX.relative_to(ROOT)} (npm run ci)")
    if not MCC.is_file():
        missing.append(f"mcc in this environment ({MCC})")
    return missing
