// The mcc command lines behind the extension's commands. Kept free of the vscode module so that the
// unit tests (tests/unit/) check them under plain Node; src/commands.ts runs them.
import * as path from "path";

export type Dialect = "mcode" | "x150" | "arcus";

/** The file extension mcc writes for each dialect (the first of the extensions package.json maps). */
export const EXTENSION_OF: Record<Dialect, string> = { mcode: ".mxt", x150: ".x150", arcus: ".prg" };

export function isDialect(value: string | undefined): value is Dialect {
  return value === "mcode" || value === "x150" || value === "arcus";
}

/**
 * Where "mcc: Compile" writes FILE's device-ready program: OUTDIR (relative to the workspace folder
 * unless absolute) with FILE's name and the target dialect's extension. The source is never the
 * output (mcc refuses that anyway): a same-named file lands in OUTDIR, never beside the source.
 */
export function compileOutput(file: string, target: Dialect, outDir: string, folder: string): string {
  const dir = path.isAbsolute(outDir) ? outDir : path.join(folder, outDir || "build");
  return path.join(dir, path.parse(file).name + EXTENSION_OF[target]);
}

/** `mcc compile`, always validated: --verify simulates source and output and refuses a difference. */
export function compileArgs(file: string, output: string, target: Dialect | undefined): string[] {
  const args = ["compile", file, "--verify", "--format", "json", "-o", output];
  return target ? [...args, "--target", target] : args;
}

/** `mcc sim` drawing its plot to PLOT; EXTRA is the mcc.simulate.args setting (e.g. --inputs). */
export function simulateArgs(file: string, plot: string, extra: string[]): string[] {
  return ["sim", file, "--plot", plot, ...extra];
}

/** `mcc download` to the configured port; EXTRA is mcc.download.args (e.g. --save, --run). */
export function downloadArgs(file: string, port: string, extra: string[]): string[] {
  return ["download", file, "--port", port, ...extra];
}

/** `mcc upload` of the device's program into OUTPUT; EXTRA is mcc.upload.args. */
export function uploadArgs(dialect: Dialect, output: string, port: string, extra: string[]): string[] {
  return ["upload", "--port", port, "--dialect", dialect, "-o", output, ...extra];
}

export interface CompileDiagnostic {
  code: string;
  severity: string;
  message: string;
  line: number;
  column: number;
}

export interface CompileResult {
  ok: boolean;
  diagnostics: CompileDiagnostic[];
  lines?: number;
}

/** What `mcc compile --format json` reported about the (single) file. */
export function parseCompile(stdout: string): CompileResult {
  const report = JSON.parse(stdout) as {
    files?: { diagnostics?: CompileDiagnostic[]; stats?: { lines?: number } }[];
  };
  const file = report.files?.[0];
  const diagnostics = file?.diagnostics ?? [];
  return {
    ok: !diagnostics.some((d) => d.severity === "error"),
    diagnostics,
    lines: file?.stats?.lines,
  };
}

/** One diagnostic as a line of the "mcc" output channel (file:line:column, as the CLI prints). */
export function formatDiagnostic(file: string, d: CompileDiagnostic): string {
  return `${file}:${d.line}:${d.column}: ${d.severity}[${d.code}] ${d.message}`;
}
