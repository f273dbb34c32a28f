"""The VS Code extension's debugger contribution (editors/vscode/package.json) matches the adapter:
the launch attributes it offers are the ones `mcc debug` reads, breakpoints are allowed in the
three languages, and there is a launch.json snippet for each dialect."""

from __future__ import annotations

import json
import re
from pathlib import Path

from mcc.compiler import dialects

ROOT = Path(__file__).resolve().parents[2]
PACKAGE = json.loads((ROOT / "editors" / "vscode" / "package.json").read_text(encoding="utf-8"))


def debugger() -> dict:
    found = [d for d in PACKAGE["contributes"]["debuggers"] if d["type"] == "mcc"]
    assert len(found) == 1
    return found[0]


def test_launch_attributes_are_the_ones_the_adapter_reads():
    offered = set(debugger()["configurationAttributes"]["launch"]["properties"])
    launch = (ROOT / "debug" / "launch.py").read_text(encoding="utf-8")
    read = set(re.findall(r'args(?:\.get\(|\[)"(\w+)"', launch))
    server = (ROOT / "debug" / "server.py").read_text(encoding="utf-8")
    read |= set(re.findall(r'args\.get\("(\w+)"', server.split("def on_launch")[1].split("def on_")[0]))
    assert offered == read - {"noDebug"}  # noDebug: set by VS Code itself (Run Without Debugging)


def test_breakpoints_and_a_snippet_for_each_dialect():
    languages = {lang["id"] for lang in PACKAGE["contributes"]["languages"]}
    assert languages == set(dialects.names())
    assert {b["language"] for b in PACKAGE["contributes"]["breakpoints"]} == languages
    assert set(debugger()["languages"]) == languages
    extensions = {d.name: d.extensions for d in (dialects.get(n) for n in dialects.names())}
    snippets = debugger()["configurationSnippets"]
    for name, exts in extensions.items():
        assert any(any(s["body"]["program"].endswith(ext + '"') for ext in exts) for s in snippets), name
    assert "onDebugResolve:mcc" in PACKAGE["activationEvents"]


def test_the_extension_registers_the_adapter():
    source = (ROOT / "editors" / "vscode" / "src" / "debug.ts").read_text(encoding="utf-8")
    assert 'registerDebugAdapterDescriptorFactory("mcc"' in source and '["debug"]' in source
    assert "registerDebugger(context" in (ROOT / "editors" / "vscode" / "src" / "extension.ts").read_text()
