// The mcc extension: starts `mcc lsp` (the language server of the mcc package) for Lexium MCode,
// Parker X150 and Arcus PMX-4EX-SA files, and adds commands that run mcc on the active program
// (commands.ts). Everything the editor shows about a program comes from the server; this file
// finds mcc (locate.ts), starts the server and restarts it when its settings change.
import * as vscode from "vscode";
import { LanguageClient, LanguageClientOptions, ServerOptions } from "vscode-languageclient/node";
import { registerCommands } from "./commands";
import { locateMcc } from "./locate";

let client: LanguageClient | undefined;
let output: vscode.OutputChannel;

function mcc(): string {
  const folders = (vscode.workspace.workspaceFolders ?? []).map((folder) => folder.uri.fsPath);
  return locateMcc(vscode.workspace.getConfiguration("mcc").get<string>("path", "mcc"), folders).command;
}

function serverOptions(): ServerOptions {
  const config = vscode.workspace.getConfiguration("mcc");
  const folders = (vscode.workspace.workspaceFolders ?? []).map((folder) => folder.uri.fsPath);
  const found = locateMcc(config.get<string>("path", "mcc"), folders);
  const args = [...config.get<string[]>("args", ["lsp"])];
  if (config.get<string>("logLevel", "info") === "debug" && !args.includes("--verbose") && !args.includes("-v")) {
    args.push("--verbose");
  }
  output.appendLine(`starting ${found.command} ${args.join(" ")} (mcc from ${found.source})`);
  // No transport: the client then passes no --stdio flag (mcc lsp speaks stdio by default and
  // rejects options it does not know), and talks over the process's stdin and stdout.
  return { command: found.command, args };
}

function clientOptions(): LanguageClientOptions {
  const config = vscode.workspace.getConfiguration("mcc");
  return {
    documentSelector: [
      { scheme: "file", language: "mcode" },
      { scheme: "file", language: "x150" },
      { scheme: "file", language: "arcus" },
      { scheme: "untitled", language: "mcode" },
      { scheme: "untitled", language: "x150" },
      { scheme: "untitled", language: "arcus" },
    ],
    outputChannel: output,
    synchronize: {
      // the project's configuration: the server reads it again when it changes
      fileEvents: vscode.workspace.createFileSystemWatcher("**/{mcc.toml,pyproject.toml}"),
    },
    initializationOptions: { debounce: config.get<number>("debounce", 0) },
  };
}

async function start(): Promise<void> {
  // The client reads the mcc.trace.server setting itself (its id is "mcc").
  client = new LanguageClient("mcc", "mcc", serverOptions(), clientOptions());
  try {
    await client.start();
  } catch (error) {
    void vscode.window.showErrorMessage(
      `mcc: could not start "${mcc()} lsp" (install it in the workspace's .venv with ` +
        `pip install "mcc[lsp]", or set mcc.path): ${error}`,
    );
  }
}

async function restart(): Promise<void> {
  const running = client;
  client = undefined;
  try {
    await running?.stop();
  } catch (error) {
    output.appendLine(`stopping the server: ${error}`);
  }
  await start();
}

export async function activate(context: vscode.ExtensionContext): Promise<void> {
  output = vscode.window.createOutputChannel("mcc");
  context.subscriptions.push(
    output,
    vscode.workspace.onDidChangeConfiguration(async (event) => {
      // mcc.trace.server is read by the running client; the compile, simulate and device settings
      // are read by each command; everything else changes how the server is started.
      const server = ["mcc.path", "mcc.args", "mcc.debounce", "mcc.logLevel"];
      if (server.some((key) => event.affectsConfiguration(key))) {
        await restart();
      }
    }),
    vscode.workspace.onDidChangeWorkspaceFolders(restart),
    vscode.commands.registerCommand("mcc.restart", restart),
  );
  registerCommands(context, { command: mcc, output, storage: context.globalStorageUri });
  await start();
}

export async function deactivate(): Promise<void> {
  await client?.stop();
}
