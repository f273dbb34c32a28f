// The mcc extension: starts `mcc lsp` (the language server of the mcc package) for Lexium MCode,
// Parker X150 and Arcus PMX-4EX-SA files. Everything the editor shows comes from the server;
// this file only starts it and restarts it when its settings change.
import * as vscode from "vscode";
import {
  LanguageClient,
  LanguageClientOptions,
  ServerOptions,
  TransportKind,
} from "vscode-languageclient/node";
import { registerDebugger } from "./debug";

let client: LanguageClient | undefined;

function serverOptions(): ServerOptions {
  const config = vscode.workspace.getConfiguration("mcc");
  const command = config.get<string>("path", "mcc");
  const args = config.get<string[]>("args", ["lsp"]);
  return { command, args, transport: TransportKind.stdio };
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
    synchronize: {
      // the project's configuration: the server reads it again when it changes
      fileEvents: vscode.workspace.createFileSystemWatcher("**/{mcc.toml,pyproject.toml}"),
    },
    initializationOptions: { debounce: config.get<number>("debounce", 0) },
  };
}

async function start(): Promise<void> {
  client = new LanguageClient("mcc", "mcc", serverOptions(), clientOptions());
  try {
    await client.start();
  } catch (error) {
    void vscode.window.showErrorMessage(
      `mcc: could not start "${vscode.workspace.getConfiguration("mcc").get("path")} lsp" ` +
        `(install it with pip install "mcc[lsp]" or set mcc.path): ${error}`,
    );
  }
}

export async function activate(context: vscode.ExtensionContext): Promise<void> {
  context.subscriptions.push(
    vscode.workspace.onDidChangeConfiguration(async (event) => {
      if (event.affectsConfiguration("mcc")) {
        await client?.stop();
        await start();
      }
    }),
    vscode.commands.registerCommand("mcc.restart", async () => {
      await client?.stop();
      await start();
    }),
  );
  registerDebugger(context, () => vscode.workspace.getConfiguration("mcc").get<string>("path", "mcc"));
  await start();
}

export async function deactivate(): Promise<void> {
  await client?.stop();
}
