"""The extension's package (`editors/vscode/mcc-motion.vsix`, built by `npm run ci`, which .ci/run
runs): what a user installs holds the bundle, the grammars and the icon and no node_modules, and
every command the code registers is declared, so that the Command Palette lists it."""

from __future__ import annotations

import json
import os
import re
import zipfile
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
EXTENSION = ROOT / "editors" / "vscode"
VSIX = EXTENSION / "mcc-motion.vsix"


@pytest.fixture(scope="module")
def vsix() -> zipfile.ZipFile:
    if not VSIX.is_file():
        message = f"{VSIX.relative_to(ROOT)} is not built: run cd editors/vscode && npm ci && npm run ci"
        if os.environ.get("CI"):
            pytest.fail(message + " (.ci/run must build it)", pytrace=False)
        pytest.skip(message)
    with zipfile.ZipFile(VSIX) as archive:
        yield archive


def test_the_package_holds_the_bundle_and_nothing_it_does_not_need(vsix):
    names = set(vsix.namelist())
    manifest = json.loads(vsix.read("extension/package.json"))
    for needed in ["extension/out/extension.js", "extension/" + manifest["icon"],
                   *(f"extension/{g['path'].removeprefix('./')}" for g in manifest["contributes"]["grammars"])]:
        assert needed in names, needed
    assert not [n for n in names if "node_modules" in n or n.endswith(".ts") or "/tests/" in n]
    bundle = vsix.read("extension/out/extension.js").decode("utf-8")
    assert "vscode-languageclient" not in re.findall(r'require\("([^"]+)"\)', bundle)  # bundled, not required
    assert vsix.read("extension/" + manifest["icon"])[:8] == b"\x89PNG\r\n\x1a\n"


def test_every_registered_command_is_declared(vsix):
    manifest = json.loads(vsix.read("extension/package.json"))
    declared = {c["command"] for c in manifest["contributes"]["commands"]}
    source = "".join(p.read_text(encoding="utf-8") for p in (EXTENSION / "src").glob("*.ts"))
    registered = set(re.findall(r'registerCommand\(\s*"([^"]+)"', source))
    assert registered == declared, (registered, declared)
    assert {"mcc.restart", "mcc.compile", "mcc.simulate", "mcc.download", "mcc.upload"} <= declared


def test_trace_and_log_level_settings_are_declared(vsix):
    properties = json.loads(vsix.read("extension/package.json"))["contributes"]["configuration"]["properties"]
    assert properties["mcc.trace.server"]["enum"] == ["off", "messages", "verbose"]
    assert properties["mcc.logLevel"]["enum"] == ["info", "debug"]
