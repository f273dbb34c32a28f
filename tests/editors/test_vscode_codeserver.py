"""A real VS Code: code-server 4.100.3 (VS Code 1.100 served to a browser) in Debian's headless
Chromium, driven by Playwright, with the extension's .vsix installed the way a user installs it. A
workspace holds one sample of each dialect and a `.venv/bin/mcc` (this project's), and no mcc.path
setting: the extension must find mcc in the workspace's virtual environment. The tests read what a
person would see: the Problems panel, the hover, the quick-fix menu, the compiled file, the
simulation's plot and the download's terminal (against `mcc device`, the virtual device).

Needs code-server, Chromium and Playwright (`bash editors/vscode/tests/codeserver/install.sh`) and the
.vsix (`cd editors/vscode && npm ci && npm run ci`); `.ci/run` does both. Without them the tests skip
with that message, except under CI=true, where they fail.
"""

from __future__ import annotations

import json
import os
import re
import shutil
import signal
import subprocess
import time
from dataclasses import dataclass
from pathlib import Path

import pytest

from codeserver_tools import CHROMIUM, CHROMIUM_ARGS, CODE_SERVER, MCC, NODE, ROOT, VSIX, missing_tools

# The pictures in docs/EDITORS.md: written there with MCC_VSCODE_SCREENSHOTS=1, else beside the workspace.
DOC_IMAGES = ROOT / "docs" / "images"
INSTALL = ("bash editors/vscode/tests/codeserver/install.sh (code-server, Chromium, Playwright), then "
           "cd editors/vscode && npm ci && npm run ci (the .vsix)")
WAIT = 45_000  # ms: the longest any one step may take (the first analysis starts the server)




def _require_tools() -> None:
    missing = missing_tools()
    if missing:
        message = f"the VS Code test needs {', '.join(missing)}: run {INSTALL}"
        if os.environ.get("CI"):
            pytest.fail(message + " (.ci/run must install them)", pytrace=False)
        pytest.skip(message)


@dataclass(frozen=True)
class Sample:
    """A program of the project's samples and what the editor must show for it."""

    file: str
    hover_at: str      # hover over the first occurrence of this text
    hover: str         # ... shows this (from the command catalog)


SAMPLES = [
    Sample("samples/mcode/analog_speed.mxt", "SL R3", "Slew"),
    Sample("samples/x150/01_feed_punch_cell.x150", "2T0.2", "Time delay"),
    Sample("samples/arcus/sync_camera_trigger.prg", "WHILE V5=0", "WHILE"),
]


def _first_warning(sample: Sample) -> tuple[str, int]:
    """The code and line of the first warning `mcc lint` reports in SAMPLE: the editor must show it."""
    lint = subprocess.run([str(MCC), "lint", "--format", "json", str(ROOT / sample.file)], capture_output=True,
                          text=True, timeout=60, check=False)
    found = [d for f in json.loads(lint.stdout)["files"] for d in f["diagnostics"] if d["severity"] == "warning"]
    assert found, f"{sample.file} has no warning for the editor to show: {lint.stdout}"
    return found[0]["code"], found[0]["line"]


def _position(sample: Sample) -> tuple[int, int]:
    for number, line in enumerate((ROOT / sample.file).read_text(encoding="utf-8").splitlines(), start=1):
        if sample.hover_at in line:
            return number, line.index(sample.hover_at) + 1
    raise AssertionError(f"{sample.hover_at!r} is not in {sample.file}")


def _wait_for_line(stream, pattern: str, timeout: float) -> re.Match:
    """Read STREAM (a process's output) until a line matches PATTERN."""
    deadline = time.monotonic() + timeout
    seen = []
    while time.monotonic() < deadline:
        line = stream.readline()
        if not line:
            break
        seen.append(line)
        match = re.search(pattern, line)
        if match:
            return match
    raise AssertionError(f"no line matching {pattern!r} in:\n{''.join(seen)}")


class Editor:
    """The workbench in the browser page, used through the keyboard and the command palette."""

    def __init__(self, page, workspace: Path, user: Path):
        self.page = page
        self.workspace = workspace
        self.user = user  # code-server's user-data-dir: settings and logs

    def screenshot(self, name: str) -> Path:
        folder = DOC_IMAGES if os.environ.get("MCC_VSCODE_SCREENSHOTS") else self.user.parent
        folder.mkdir(parents=True, exist_ok=True)
        self.page.screenshot(path=str(folder / name))
        assert (folder / name).stat().st_size > 10_000  # a picture, not a blank page
        return folder / name

    def command(self, title: str) -> None:
        """Run a command by its title from the command palette (F1)."""
        self.page.keyboard.press("Escape")
        self.page.keyboard.press("F1")
        box = self.page.locator(".quick-input-widget input")
        box.wait_for(state="visible", timeout=WAIT)
        box.fill(">" + title)
        # exactly this command (its row is labelled "TITLE" or "TITLE, KEYBINDING"), not the first match
        row = self.page.locator(".quick-input-list").get_by_role("option", name=re.compile(f"^{re.escape(title)}(,|$)"))
        row.click(timeout=WAIT)

    def open(self, name: str) -> None:
        """Open a workspace file through Quick Open (Ctrl+P) and wait for its editor tab."""
        self.page.keyboard.press("Escape")
        self.page.keyboard.press("Control+P")
        box = self.page.locator(".quick-input-widget input")
        box.wait_for(state="visible", timeout=WAIT)
        box.fill(name)
        self.page.locator(".quick-input-list .monaco-list-row", has_text=name).first.click(timeout=WAIT)
        self.page.locator(".tab.active", has_text=name).wait_for(timeout=WAIT)

    def goto(self, line: int, column: int) -> None:
        self.page.keyboard.press("Escape")
        box = self.page.locator(".quick-input-widget input")
        # a quick input still closing would take the line text (seen under load)
        box.wait_for(state="hidden", timeout=WAIT)
        self.page.keyboard.press("Control+G")
        box.wait_for(state="visible", timeout=WAIT)
        box.fill(f":{line}:{column}")
        # Enter only once the widget has read the text (it offers to go to the line), or it goes nowhere
        self.page.locator(".quick-input-widget", has_text=f"line {line}").first.wait_for(timeout=WAIT)
        self.page.keyboard.press("Enter")
        # the status bar shows where the cursor went (the cursor itself blinks: hidden half the time)
        self.page.locator(".statusbar-item", has_text=f"Ln {line}, Col {column}").first.wait_for(timeout=WAIT)
        self.page.locator(".monaco-editor textarea.inputarea").first.focus()

    def problems(self, code: str, line: int) -> str:
        """The Problems panel's row for CODE on LINE, waited for (the server analyses on open)."""
        self.command("Problems: Focus on Problems View")
        # the row reads "message mcc CODE [Ln L, Col C]" (the parentheses are drawn by CSS)
        row = self.page.locator(".markers-panel .monaco-list-row", has_text=code).filter(
            has_text=f"[Ln {line}, Col")
        row.first.wait_for(timeout=WAIT)
        return row.first.inner_text()


@pytest.fixture
def editor(workbench, request):
    """The workbench; when the test fails, a screenshot and the "mcc" output are left beside it."""
    yield workbench
    report = getattr(request.node, "call_report", None)
    if report is not None and report.failed:
        shot = workbench.user.parent / f"{request.node.name}.png"
        workbench.page.screenshot(path=str(shot))
        logs = sorted(workbench.user.glob("logs/**/*mcc*.log"))
        tail = "".join(log.read_text(encoding="utf-8", errors="replace")[-3000:] for log in logs)
        print(f"screenshot of the failure: {shot}\nthe extension's output:\n{tail}")


@pytest.fixture(scope="module")
def workbench(tmp_path_factory):
    _require_tools()
    from playwright.sync_api import sync_playwright

    base = tmp_path_factory.mktemp("vscode")
    workspace = base / "workspace"
    (workspace / ".venv" / "bin").mkdir(parents=True)
    (workspace / ".venv" / "bin" / "mcc").symlink_to(MCC)   # found by the extension, not configured
    for sample in SAMPLES:
        shutil.copy(ROOT / sample.file, workspace)
    env = {**os.environ, "XDG_CONFIG_HOME": str(base / "config"), "XDG_DATA_HOME": str(base / "data"),
           "VIRTUAL_ENV": "", "PATH": f"{Path(NODE).parent}:/usr/bin:/bin"}  # no mcc on PATH: only the workspace's venv has it
    processes = []
    try:
        device = subprocess.Popen([str(MCC), "device", "--dialect", "mcode"], stdout=subprocess.PIPE,
                                  stderr=subprocess.STDOUT, text=True, start_new_session=True)
        processes.append(device)
        port = _wait_for_line(device.stdout, r"socket://127\.0\.0\.1:\d+", 30).group(0)
        (workspace / ".vscode").mkdir()
        (workspace / ".vscode" / "settings.json").write_text(json.dumps({"mcc.port": port}), encoding="utf-8")
        user = base / "user-data"
        (user / "User").mkdir(parents=True)
        (user / "User" / "settings.json").write_text(json.dumps({
            "security.workspace.trust.enabled": False, "workbench.startupEditor": "none",
            "telemetry.telemetryLevel": "off", "update.mode": "none", "extensions.autoCheckUpdates": False,
            "workbench.tips.enabled": False, "terminal.integrated.gpuAcceleration": "off",
            "workbench.editor.enablePreview": False, "editor.stickyScroll.enabled": False,
            "mcc.trace.server": "messages",
        }), encoding="utf-8")
        options = ["--user-data-dir", str(user), "--extensions-dir", str(base / "extensions")]
        installed = subprocess.run([NODE, str(CODE_SERVER), *options, "--install-extension", str(VSIX)],
                                   env=env, capture_output=True, text=True, timeout=120, check=False)
        assert "successfully installed" in installed.stdout, installed.stdout + installed.stderr
        server = subprocess.Popen(
            [NODE, str(CODE_SERVER), *options, "--auth", "none", "--bind-addr", "127.0.0.1:0",
             "--disable-telemetry", "--disable-update-check", "--disable-workspace-trust",
             "--disable-getting-started-override", str(workspace)],
            env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, start_new_session=True)
        processes.append(server)
        url = _wait_for_line(server.stdout, r"http://127\.0\.0\.1:\d+", 60).group(0)
        with sync_playwright() as playwright:
            browser = playwright.chromium.launch(executable_path=CHROMIUM, args=CHROMIUM_ARGS, headless=True)
            page = browser.new_page(viewport={"width": 1400, "height": 860})
            page.goto(f"{url}/?folder={workspace}")
            page.locator(".monaco-workbench").wait_for(timeout=WAIT)
            page.locator(".explorer-folders-view").wait_for(timeout=WAIT)
            try:
                yield Editor(page, workspace, user)
            finally:
                browser.close()
    finally:
        for process in processes:
            if process.poll() is None:
                os.killpg(process.pid, signal.SIGTERM)
                try:
                    process.wait(timeout=10)
                except subprocess.TimeoutExpired:
                    os.killpg(process.pid, signal.SIGKILL)


@pytest.mark.parametrize("sample", SAMPLES, ids=["mcode", "x150", "arcus"])
def test_diagnostics_hover_and_quick_fix(editor, sample):
    """Each dialect's sample shows its first lint warning (as `mcc lint` reports it) in the Problems
    panel, a hover from the command catalog, and the finding's quick fixes (noqa, Explain), all from
    `mcc lsp` started from the workspace's .venv."""
    name = Path(sample.file).name
    code, diagnostic_line = _first_warning(sample)
    editor.open(name)
    row = editor.problems(code, diagnostic_line)
    assert name in editor.page.locator(".markers-panel").inner_text()
    assert "mcc" in row, row

    line, column = _position(sample)
    editor.page.mouse.move(1, 1)  # away from the text: a mouse hover would replace the keyboard's
    editor.goto(line, column + 1)
    hover = editor.page.locator(".monaco-hover-content:visible", has_text=sample.hover)
    for attempt in range(5):  # a repaint (new diagnostics, colours) may close a hover just opened
        editor.command("Show or Focus Hover")
        try:
            hover.first.wait_for(timeout=WAIT // 5)
            break
        except Exception:
            if attempt == 4:
                raise
    if sample.file.endswith(".mxt"):  # once the hover has faded in
        time.sleep(0.6)
        editor.screenshot("vscode.png")

    editor.goto(diagnostic_line, 1)
    editor.command("Quick Fix...")
    menu = editor.page.locator(".action-widget")
    menu.wait_for(timeout=WAIT)
    fix = menu.locator(".monaco-list-row", has_text=f"Silence {code} on this line (noqa)")
    fix.first.wait_for(timeout=WAIT)
    assert "Explain" in menu.inner_text(), menu.inner_text()
    editor.page.keyboard.press("Escape")


def test_quick_fix_applies(editor):
    """Applying the MCode M309 fix (S, and a comment line so that S's line end is sent, after the
    final PG: lexium-mcode.txt L5269) edits the document in the editor and the finding goes away."""
    editor.open("analog_speed.mxt")
    editor.goto(37, 1)
    editor.command("Quick Fix...")
    fix = editor.page.locator(".action-widget .monaco-list-row", has_text="add S and a comment line")
    fix.first.wait_for(timeout=WAIT)
    focused = editor.page.locator(".action-widget .monaco-list-row.focused")
    for _ in range(10):  # the menu takes the keyboard (a pointer block covers it from clicks)
        if "add S and a comment line" in focused.inner_text():
            break
        editor.page.keyboard.press("ArrowDown")
    editor.page.keyboard.press("Enter")
    editor.page.locator(".monaco-editor .view-line", has_text="it ends the S").wait_for(timeout=WAIT)
    editor.command("File: Save")
    program = editor.workspace / "analog_speed.mxt"
    deadline = time.monotonic() + WAIT / 1000
    while program.read_text(encoding="utf-8").splitlines()[37:38] != ["S"] and time.monotonic() < deadline:
        time.sleep(0.2)
    assert program.read_text(encoding="utf-8").splitlines()[36:38] == ["PG", "S"], program.read_text()
    editor.command("Problems: Focus on Problems View")
    rows = editor.page.locator(".markers-panel .monaco-list-row", has_text="M309")
    rows.first.wait_for(state="detached", timeout=WAIT)


def test_simulate_shows_the_plot(editor):
    """mcc: Simulate runs `mcc sim --plot` and shows the plot and the run's report in a panel."""
    editor.command("View: Close All Editor Groups")  # a tidy window for the picture in docs/EDITORS.md
    if editor.page.locator(".part.panel").is_visible():
        editor.command("View: Toggle Panel Visibility")
    editor.open("sync_camera_trigger.prg")
    editor.command("mcc: Simulate and plot")
    editor.page.locator(".tab", has_text="Simulation: sync_camera_trigger.prg").wait_for(timeout=WAIT)
    frame = editor.page.frame_locator("iframe.webview.ready").frame_locator("#active-frame")
    plot = frame.locator("img#plot")
    plot.wait_for(timeout=WAIT)
    deadline = time.monotonic() + 20
    while plot.evaluate("img => img.naturalWidth") == 0 and time.monotonic() < deadline:
        time.sleep(0.2)
    assert plot.evaluate("img => img.naturalWidth") > 100
    assert frame.locator("#report").inner_text().strip()
    editor.screenshot("vscode-simulate.png")


def test_compile_writes_the_validated_program(editor):
    """mcc: Compile runs `mcc compile --verify` and opens the device-ready program from build/."""
    editor.open("01_feed_punch_cell.x150")
    editor.command("mcc: Compile (validated by simulation)")
    editor.page.locator(".notification-toast", has_text="compiled and validated").wait_for(timeout=WAIT)
    output = editor.workspace / "build" / "01_feed_punch_cell.x150"
    assert output.is_file()
    editor.page.locator(".tab", has_text="01_feed_punch_cell.x150").nth(1).wait_for(timeout=WAIT)


def test_download_runs_in_a_terminal(editor):
    """mcc: Download runs `mcc download` on the configured port (a virtual MCode device) in a
    terminal, which stays open with the result after mcc exits."""
    editor.open("analog_speed.mxt")
    editor.command("mcc: Download to the device")
    terminal = editor.page.locator(".terminal-wrapper.active .xterm-rows")
    terminal.wait_for(timeout=WAIT)
    terminal.filter(has_text="[mcc exited with code 0]").wait_for(timeout=WAIT)  # and stays open
    assert "downloaded and verified" in terminal.inner_text()


def test_trace_setting_logs_the_messages(editor):
    """mcc.trace.server (set to "messages" in the user settings) logs each LSP message in the "mcc"
    output, where a user reporting a problem finds what the editor and the server said."""
    logs = "".join(log.read_text(encoding="utf-8", errors="replace")
                   for log in editor.user.glob("logs/**/*mcc*.log"))
    assert "Sending request 'textDocument/hover" in logs, logs[-2000:]
    assert "Received notification 'textDocument/publishDiagnostics'" in logs, logs[-2000:]


def test_upload_asks_for_the_file_and_writes_it(editor):
    """mcc: Upload reads the program back from the device (the virtual one, holding what Download put
    there) into the file chosen in the save dialog, a source `mcc check` accepts."""
    editor.open("analog_speed.mxt")
    editor.command("mcc: Upload the program from the device")
    box = editor.page.locator(".quick-input-widget input")  # code-server's save dialog
    box.wait_for(state="visible", timeout=WAIT)
    target = editor.workspace / "uploaded.mxt"
    box.fill(str(target))
    editor.page.keyboard.press("Enter")
    terminal = editor.page.locator(".terminal-wrapper.active .xterm-rows")
    terminal.filter(has_text="mcc upload").filter(has_text="[mcc exited with code 0]").wait_for(timeout=WAIT)
    assert "LB A1" in target.read_text(encoding="utf-8")
