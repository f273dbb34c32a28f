"""`mcc debug` in a real VS Code: code-server (VS Code served to a browser) in Debian's headless
Chromium, driven by Playwright, with the extension's .vsix installed. The user's steps: open the
MCode fixture, F9 on the loop's line, F5 (the workspace's launch.json names the program), F10 over
the increment, F11 into the subroutine; the editor then shows the stopped line, the call stack by
routine and line with the virtual time, the program's variables and axis 1's position and settings.
F5 again runs to the end and the Debug Console shows how the run ended.

Needs what the VS Code editor test needs (editors/vscode/tests/codeserver/install.sh: code-server,
Chromium, Playwright; and the .vsix from `npm run ci` in editors/vscode): skipped without them,
except under CI=true where the install script is part of the tree (.ci/run runs it), which fails.
With MCC_VSCODE_SCREENSHOTS=1 the picture is written to docs/images/vscode-debug.png.
"""

from __future__ import annotations

import json
import os
import re
import shutil
import signal
import subprocess
import time
from pathlib import Path

import pytest

from codeserver_tools import (CHROMIUM, CHROMIUM_ARGS, CODE_SERVER, INSTALL_SCRIPT, MCC, NODE,  # noqa: F401
                              ROOT, VSIX, missing_tools)

FIXTURE = Path(__file__).parent / "fixtures" / "loop.mxt"
WAIT = 45_000  # ms




def require_tools() -> None:
    absent = missing_tools()
    if absent:
        message = f"the VS Code debugging test needs {', '.join(absent)}"
        if os.environ.get("CI") and INSTALL_SCRIPT.is_file():
            pytest.fail(message + " (.ci/run runs editors/vscode/tests/codeserver/install.sh)", pytrace=False)
        pytest.skip(message)


def wait_for_url(stream, timeout: float = 60) -> str:
    deadline = time.monotonic() + timeout
    seen = []
    while time.monotonic() < deadline:
        line = stream.readline()
        if not line:
            break
        seen.append(line)
        found = re.search(r"http://127\.0\.0\.1:\d+", line)
        if found:
            return found.group(0)
    raise AssertionError("code-server did not say where it listens:\n" + "".join(seen))


def test_a_debugging_session_in_vscode(tmp_path):
    require_tools()
    from playwright.sync_api import sync_playwright

    workspace = tmp_path / "workspace"
    (workspace / ".vscode").mkdir(parents=True)
    shutil.copy(FIXTURE, workspace)
    (workspace / ".vscode" / "launch.json").write_text(json.dumps({"version": "0.2.0", "configurations": [
        {"type": "mcc", "request": "launch", "name": "Debug loop.mxt", "program": "${workspaceFolder}/loop.mxt"}]}))
    user = tmp_path / "user-data"
    (user / "User").mkdir(parents=True)
    (user / "User" / "settings.json").write_text(json.dumps({
        "security.workspace.trust.enabled": False, "workbench.startupEditor": "none",
        "telemetry.telemetryLevel": "off", "update.mode": "none", "extensions.autoCheckUpdates": False,
        "workbench.tips.enabled": False, "workbench.editor.enablePreview": False,
        "editor.stickyScroll.enabled": False, "mcc.path": str(MCC)}))
    env = {**os.environ, "XDG_CONFIG_HOME": str(tmp_path / "config"), "XDG_DATA_HOME": str(tmp_path / "data"),
           "PATH": f"{Path(NODE).parent}:/usr/bin:/bin"}
    options = ["--user-data-dir", str(user), "--extensions-dir", str(tmp_path / "extensions")]
    installed = subprocess.run([NODE, str(CODE_SERVER), *options, "--install-extension", str(VSIX)], env=env,
                               capture_output=True, text=True, timeout=120, check=False)
    assert "successfully installed" in installed.stdout, installed.stdout + installed.stderr
    server = subprocess.Popen(
        [NODE, str(CODE_SERVER), *options, "--auth", "none", "--bind-addr", "127.0.0.1:0", "--disable-telemetry",
         "--disable-update-check", "--disable-workspace-trust", "--disable-getting-started-override", str(workspace)],
        env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, start_new_session=True)
    try:
        url = wait_for_url(server.stdout)
        with sync_playwright() as playwright:
            browser = playwright.chromium.launch(executable_path=CHROMIUM, args=CHROMIUM_ARGS, headless=True)
            try:
                page = browser.new_page(viewport={"width": 1400, "height": 860})
                run_session(page, url, workspace)
            finally:
                browser.close()
    finally:
        os.killpg(server.pid, signal.SIGTERM)
        try:
            server.wait(timeout=10)
        except subprocess.TimeoutExpired:
            os.killpg(server.pid, signal.SIGKILL)


def shown(name: str, value: str) -> re.Pattern:
    """A row of the Variables view: name and value are separate elements ("Q1 =" and "0")."""
    return re.compile(rf"^\s*{re.escape(name)}\s*=\s*{re.escape(value)}")


def run_session(page, url: str, workspace: Path) -> None:
    page.goto(f"{url}/?folder={workspace}")
    page.locator(".monaco-workbench").wait_for(timeout=WAIT)
    page.locator(".explorer-folders-view").wait_for(timeout=WAIT)
    box = page.locator(".quick-input-widget input")
    page.keyboard.press("Control+P")
    box.wait_for(state="visible", timeout=WAIT)
    box.fill("loop.mxt")
    page.locator(".quick-input-list .monaco-list-row", has_text="loop.mxt").first.click(timeout=WAIT)
    page.locator(".tab.active", has_text="loop.mxt").wait_for(timeout=WAIT)
    # the quick open must have closed, or the go-to-line text goes into it as it closes
    box.wait_for(state="hidden", timeout=WAIT)
    page.keyboard.press("Control+G")
    box.wait_for(state="visible", timeout=WAIT)
    box.fill(":10:1")
    # Enter only once the widget has read the text (it offers to go to line 10), or it goes nowhere
    page.locator(".quick-input-widget", has_text="line 10").first.wait_for(timeout=WAIT)
    page.keyboard.press("Enter")
    # the status bar shows where the cursor went; the cursor itself blinks (hidden half the time)
    # and stays hidden while another part of the window has the focus, so the editor is given it
    page.locator(".statusbar-item", has_text="Ln 10, Col 1").first.wait_for(timeout=WAIT)
    page.locator(".monaco-editor textarea.inputarea").first.focus()
    page.keyboard.press("F9")  # a breakpoint on the loop's line
    page.locator(".codicon-debug-breakpoint").first.wait_for(timeout=WAIT)
    page.keyboard.press("F5")
    stack = page.locator(".debug-call-stack")
    stack.locator(".monaco-list-row", has_text=re.compile(r"A1 @ \d")).first.wait_for(timeout=WAIT)
    assert "10:1" in stack.inner_text()
    variables = page.locator(".debug-variables")
    variables.locator(".monaco-list-row", has_text=shown("Q1", "0")).first.wait_for(timeout=WAIT)

    page.keyboard.press("F10")  # over the increment, to the call
    stack.locator(".monaco-list-row", has_text="11:1").first.wait_for(timeout=WAIT)
    page.keyboard.press("F11")  # into the subroutine
    stack.locator(".monaco-list-row", has_text=re.compile(r"SB @ \d")).first.wait_for(timeout=WAIT)
    rows = stack.inner_text()
    assert "20:1" in rows and "11:1" in rows, rows
    variables.locator(".monaco-list-row", has_text=shown("Q1", "1")).first.wait_for(timeout=WAIT)
    variables.locator(".monaco-list-row", has_text="Axes").first.click(timeout=WAIT)
    axis = variables.locator(".monaco-list-row", has_text=shown("axis 1", "1000 steps"))
    axis.first.click(timeout=WAIT)
    variables.locator(".monaco-list-row", has_text=shown("position (steps)", "1000")).first.wait_for(timeout=WAIT)
    variables.locator(".monaco-list-row", has_text=shown("max_speed", "768000")).first.wait_for(timeout=WAIT)
    page.locator(".debug-top-stack-frame-line").first.wait_for(timeout=WAIT)  # the stopped line, marked

    # notifications from elsewhere (the language server starting) would cover the picture
    page.keyboard.press("F1")
    box.wait_for(state="visible", timeout=WAIT)
    box.fill(">Notifications: Clear All Notifications")
    page.keyboard.press("Enter")
    time.sleep(0.5)
    folder = ROOT / "docs" / "images" if os.environ.get("MCC_VSCODE_SCREENSHOTS") else workspace.parent
    folder.mkdir(parents=True, exist_ok=True)
    page.screenshot(path=str(folder / "vscode-debug.png"))
    assert (folder / "vscode-debug.png").stat().st_size > 10_000

    page.keyboard.press("F1")  # the loop's breakpoint would stop each round: remove it, then on to the end
    box.wait_for(state="visible", timeout=WAIT)
    box.fill(">Remove All Breakpoints")
    page.keyboard.press("Enter")
    page.locator(".codicon-debug-breakpoint").first.wait_for(state="detached", timeout=WAIT)
    page.keyboard.press("F5")
    console = page.locator(".repl")
    console.filter(has_text="stopped: end").first.wait_for(timeout=WAIT)
    assert "NO INPUT" in console.first.inner_text()
