// The commands that run mcc on the active program: compile (always validated), simulate (the plot
// in a panel), download and upload (in a terminal, where the device's replies and the progress
// show as they come and a wrong port can be corrected and the command run again).
import { ChildProcess, execFile, spawn } from "child_process";
import * as fs from "fs";
import * as path from "path";
import * as vscode from "vscode";
import {
  Dialect,
  EXTENSION_OF,
  compileArgs,
  compileOutput,
  downloadArgs,
  formatDiagnostic,
  isDialect,
  parseCompile,
  simulateArgs,
  uploadArgs,
} from "./cli";

export interface Runner {
  /** The mcc command to run (see locate.ts). */
  command(): string;
  output: vscode.OutputChannel;
  storage: vscode.Uri;
}

interface Run {
  code: number;
  stdout: string;
  stderr: string;
}

function run(command: string, args: string[], cwd: string): Promise<Run> {
  return new Promise((resolve) => {
    execFile(command, args, { cwd, maxBuffer: 64 * 1024 * 1024 }, (error, stdout, stderr) => {
      const code = error ? (typeof error.code === "number" ? error.code : -1) : 0;
      const why = error && typeof error.code !== "number" ? `${error.message}\n` : "";
      resolve({ code, stdout, stderr: why + stderr });
    });
  });
}

/** The active editor's program, saved: mcc reads the file, so unsaved text would not be what runs. */
async function activeProgram(): Promise<{ document: vscode.TextDocument; dialect: Dialect } | undefined> {
  const document = vscode.window.activeTextEditor?.document;
  if (!document || !isDialect(document.languageId)) {
    void vscode.window.showWarningMessage("mcc: open an MCode, X150 or Arcus program first.");
    return undefined;
  }
  if (document.isUntitled) {
    void vscode.window.showWarningMessage("mcc: save the program to a file first (mcc runs on files).");
    return undefined;
  }
  if (document.isDirty && !(await document.save())) {
    return undefined;
  }
  return { document, dialect: document.languageId };
}

function folderOf(uri: vscode.Uri): string {
  return vscode.workspace.getWorkspaceFolder(uri)?.uri.fsPath ?? path.dirname(uri.fsPath);
}

function config(uri?: vscode.Uri): vscode.WorkspaceConfiguration {
  return vscode.workspace.getConfiguration("mcc", uri);
}

/** The port for download and upload: mcc.port, else asked for (and offered to be kept). */
async function port(uri?: vscode.Uri): Promise<string | undefined> {
  const configured = config(uri).get<string>("port", "").trim();
  if (configured) {
    return configured;
  }
  const typed = await vscode.window.showInputBox({
    title: "mcc: serial port of the device",
    prompt: "A pyserial URL: /dev/ttyUSB0, COM3, socket://HOST:PORT, rfc2217://HOST:PORT",
    placeHolder: "COM3",
    ignoreFocusOut: true,
  });
  if (!typed?.trim()) {
    return undefined;
  }
  void config(uri).update("port", typed.trim(), vscode.ConfigurationTarget.Workspace);
  return typed.trim();
}

export function registerCommands(context: vscode.ExtensionContext, runner: Runner): void {
  const compileProblems = vscode.languages.createDiagnosticCollection("mcc compile");
  let panel: vscode.WebviewPanel | undefined;
  context.subscriptions.push(
    compileProblems,
    vscode.workspace.onDidChangeTextDocument((event) => compileProblems.delete(event.document.uri)),
    vscode.commands.registerCommand("mcc.compile", async () => {
      const program = await activeProgram();
      if (program) {
        await compile(runner, program.document, program.dialect, compileProblems);
      }
    }),
    vscode.commands.registerCommand("mcc.simulate", async () => {
      const program = await activeProgram();
      if (program) {
        panel = await simulate(runner, program.document, panel, (closed) => {
          if (panel === closed) {
            panel = undefined;
          }
        });
      }
    }),
    vscode.commands.registerCommand("mcc.download", async () => {
      const program = await activeProgram();
      const url = program && (await port(program.document.uri));
      if (program && url) {
        const extra = config(program.document.uri).get<string[]>("download.args", []);
        terminal(runner, "mcc download", downloadArgs(program.document.uri.fsPath, url, extra), folderOf(program.document.uri));
      }
    }),
    vscode.commands.registerCommand("mcc.upload", async () => {
      await upload(runner);
    }),
  );
}

async function compile(
  runner: Runner,
  document: vscode.TextDocument,
  dialect: Dialect,
  problems: vscode.DiagnosticCollection,
): Promise<void> {
  const settings = config(document.uri);
  const configured = settings.get<string>("compile.target", "");
  const target = isDialect(configured) ? configured : dialect;
  const folder = folderOf(document.uri);
  const output = compileOutput(document.uri.fsPath, target, settings.get<string>("compile.outputDirectory", "build"), folder);
  fs.mkdirSync(path.dirname(output), { recursive: true });
  const args = compileArgs(document.uri.fsPath, output, isDialect(configured) ? configured : undefined);
  runner.output.appendLine(`> ${runner.command()} ${args.join(" ")}`);
  const result = await vscode.window.withProgress(
    { location: vscode.ProgressLocation.Notification, title: "mcc: compiling and validating…" },
    () => run(runner.command(), args, folder),
  );
  let report;
  try {
    report = parseCompile(result.stdout);
  } catch {
    runner.output.appendLine(result.stderr || result.stdout);
    runner.output.show(true);
    void vscode.window.showErrorMessage(`mcc compile failed (exit ${result.code}): see the mcc output.`);
    return;
  }
  const relative = vscode.workspace.asRelativePath(document.uri);
  for (const d of report.diagnostics) {
    runner.output.appendLine(formatDiagnostic(relative, d));
  }
  // The language server already shows what `mcc check` finds in the program's own dialect: only
  // what compiling adds is shown again (errors that stopped it, findings about another target).
  const added = report.diagnostics.filter((d) => d.severity === "error" || target !== dialect);
  problems.set(
    document.uri,
    added.map((d) => {
      const line = Math.max(0, d.line - 1);
      const range = new vscode.Range(line, Math.max(0, d.column - 1), line, Number.MAX_SAFE_INTEGER);
      const severity =
        d.severity === "error"
          ? vscode.DiagnosticSeverity.Error
          : d.severity === "warning"
            ? vscode.DiagnosticSeverity.Warning
            : vscode.DiagnosticSeverity.Information;
      const diagnostic = new vscode.Diagnostic(range, d.message, severity);
      diagnostic.code = d.code;
      diagnostic.source = "mcc compile";
      return diagnostic;
    }),
  );
  if (!report.ok || result.code !== 0) {
    const first = report.diagnostics.find((d) => d.severity === "error");
    void vscode.window.showErrorMessage(
      `mcc: ${relative} was not compiled` + (first ? ` — line ${first.line}: ${first.message}` : `: ${result.stderr.trim()}`),
    );
    return;
  }
  const written = vscode.workspace.asRelativePath(output);
  runner.output.appendLine(`compiled and validated: ${written} (${report.lines ?? "?"} lines)`);
  const shown = await vscode.workspace.openTextDocument(output);
  await vscode.window.showTextDocument(shown, { viewColumn: vscode.ViewColumn.Beside, preview: true });
  void vscode.window.showInformationMessage(`mcc: compiled and validated ${relative} → ${written}`);
}

async function simulate(
  runner: Runner,
  document: vscode.TextDocument,
  existing: vscode.WebviewPanel | undefined,
  onClose: (panel: vscode.WebviewPanel) => void,
): Promise<vscode.WebviewPanel | undefined> {
  const dir = vscode.Uri.joinPath(runner.storage, "plots");
  fs.mkdirSync(dir.fsPath, { recursive: true });
  const name = path.parse(document.uri.fsPath).name;
  const plot = vscode.Uri.joinPath(dir, `${name}.png`);
  fs.rmSync(plot.fsPath, { force: true });
  const extra = config(document.uri).get<string[]>("simulate.args", []);
  const args = simulateArgs(document.uri.fsPath, plot.fsPath, extra);
  runner.output.appendLine(`> ${runner.command()} ${args.join(" ")}`);
  const result = await vscode.window.withProgress(
    { location: vscode.ProgressLocation.Notification, title: "mcc: simulating…" },
    () => run(runner.command(), args, folderOf(document.uri)),
  );
  runner.output.appendLine(result.stdout + result.stderr);
  const drawn = fs.existsSync(plot.fsPath);
  if (result.code !== 0 && !drawn) {
    runner.output.show(true);
    void vscode.window.showErrorMessage(
      `mcc sim failed (exit ${result.code}): ${(result.stderr || result.stdout).trim().split("\n").pop()}`,
    );
    return existing;
  }
  const panel =
    existing ??
    vscode.window.createWebviewPanel("mcc.simulation", "", vscode.ViewColumn.Beside, {
      localResourceRoots: [dir],
      enableScripts: false,
    });
  if (!existing) {
    panel.onDidDispose(() => onClose(panel));
  }
  panel.title = `Simulation: ${path.basename(document.uri.fsPath)}`;
  const image = drawn ? `${panel.webview.asWebviewUri(plot)}?t=${Date.now()}` : undefined;
  panel.webview.html = simulationPage(panel.webview.cspSource, path.basename(document.uri.fsPath), image, result.stdout + result.stderr);
  panel.reveal(vscode.ViewColumn.Beside, true);
  return panel;
}

function escape(text: string): string {
  return text.replace(/&/g, "&amp;").replace(/</g, "&lt;").replace(/>/g, "&gt;");
}

function simulationPage(csp: string, file: string, image: string | undefined, report: string): string {
  const picture = image
    ? `<img id="plot" src="${image}" alt="position and speed of each axis over time">`
    : `<p>No plot: the simulator drew none (install the plot extra: pip install "mcc[plot]").</p>`;
  return `<!DOCTYPE html>
<html lang="en"><head><meta charset="UTF-8">
<meta http-equiv="Content-Security-Policy" content="default-src 'none'; img-src ${csp}; style-src 'unsafe-inline';">
<title>Simulation of ${escape(file)}</title>
<style>img { max-width: 100%; background: white; } pre { white-space: pre-wrap; }</style>
</head><body>
<h2>Simulation of ${escape(file)}</h2>
${picture}
<pre id="report">${escape(report)}</pre>
</body></html>`;
}

/**
 * Runs mcc in a terminal of its own: its output shows as it comes, and the terminal stays open after
 * mcc exits (a terminal started on a program closes when the program ends, taking the result with it).
 */
function terminal(runner: Runner, name: string, args: string[], cwd: string): void {
  runner.output.appendLine(`> ${runner.command()} ${args.join(" ")}`);
  const write = new vscode.EventEmitter<string>();
  let child: ChildProcess | undefined;
  const show = (text: string) => write.fire(text.replace(/\r?\n/g, "\r\n"));
  const pty: vscode.Pseudoterminal = {
    onDidWrite: write.event,
    open: () => {
      show(`> mcc ${args.join(" ")}\n`);
      child = spawn(runner.command(), args, { cwd });
      child.stdout?.on("data", (data: Buffer) => show(data.toString()));
      child.stderr?.on("data", (data: Buffer) => show(data.toString()));
      child.on("error", (error) => show(`\ncould not run ${runner.command()}: ${error.message}\n`));
      child.on("close", (code) => show(`\n[mcc exited with code ${code ?? "?"}]\n`));
    },
    close: () => child?.kill(),
    handleInput: (data: string) => child?.stdin?.write(data === "\r" ? "\n" : data),
  };
  vscode.window.createTerminal({ name, pty }).show();
}

async function upload(runner: Runner): Promise<void> {
  const active = vscode.window.activeTextEditor?.document;
  const languageId = active?.languageId;
  const dialect = isDialect(languageId)
    ? languageId
    : ((await vscode.window.showQuickPick(["mcode", "x150", "arcus"], {
        title: "mcc: the device's dialect",
      })) as Dialect | undefined);
  if (!dialect) {
    return;
  }
  const url = await port(active?.uri);
  if (!url) {
    return;
  }
  const folder = vscode.workspace.workspaceFolders?.[0]?.uri;
  const target = await vscode.window.showSaveDialog({
    title: "mcc: write the device's program to",
    defaultUri: folder ? vscode.Uri.joinPath(folder, `uploaded${EXTENSION_OF[dialect]}`) : undefined,
    filters: { [dialect]: [EXTENSION_OF[dialect].slice(1)] },
  });
  if (!target) {
    return;
  }
  const extra = config(active?.uri).get<string[]>("upload.args", []);
  terminal(runner, "mcc upload", uploadArgs(dialect, target.fsPath, url, extra), folder?.fsPath ?? path.dirname(target.fsPath));
}
