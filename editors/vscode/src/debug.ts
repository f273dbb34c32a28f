// The debugger: `mcc debug` speaks the Debug Adapter Protocol and runs the program on mcc's
// simulator (docs/EDITORS.md, "Debugging"). package.json contributes the debug type "mcc" with
// its launch.json attributes and snippets; this file starts the adapter with the mcc the rest of
// the extension runs, and fills in a launch configuration for the active program when there is
// no launch.json (F5 on an open program).
import * as vscode from "vscode";

const LANGUAGES = ["mcode", "x150", "arcus"];

class Adapter implements vscode.DebugAdapterDescriptorFactory {
  constructor(private readonly command: () => string) {}

  createDebugAdapterDescriptor(session: vscode.DebugSession): vscode.DebugAdapterDescriptor {
    const port = session.configuration.debugServer;
    if (typeof port === "number") {
      // `mcc debug --port N` started by hand (to watch its log): connect to it
      return new vscode.DebugAdapterServer(port);
    }
    return new vscode.DebugAdapterExecutable(this.command(), ["debug"]);
  }
}

class Configurations implements vscode.DebugConfigurationProvider {
  resolveDebugConfiguration(
    folder: vscode.WorkspaceFolder | undefined,
    config: vscode.DebugConfiguration,
  ): vscode.DebugConfiguration | undefined {
    if (!config.type && !config.request && !config.name) {
      const editor = vscode.window.activeTextEditor;
      if (editor === undefined || !LANGUAGES.includes(editor.document.languageId)) {
        return config; // VS Code then offers to create a launch.json
      }
      config.type = "mcc";
      config.name = "Debug the program on the simulator";
      config.request = "launch";
      config.program = "${file}";
      config.stopOnEntry = true;
    }
    if (!config.program) {
      void vscode.window.showErrorMessage('mcc: the launch configuration needs "program" (the file to debug)');
      return undefined;
    }
    if (!config.cwd && folder !== undefined) {
      config.cwd = folder.uri.fsPath; // what relative program and scenario paths are relative to
    }
    return config;
  }
}

/** Register the "mcc" debug type; `command` gives the mcc to run (as for the language server). */
export function registerDebugger(context: vscode.ExtensionContext, command: () => string): void {
  context.subscriptions.push(
    vscode.debug.registerDebugAdapterDescriptorFactory("mcc", new Adapter(command)),
    vscode.debug.registerDebugConfigurationProvider("mcc", new Configurations()),
  );
}
