// Which `mcc` to run. Most users install mcc into the project's virtual environment and open the
// project folder without activating it, so the workspace's .venv/ or venv/ is searched before PATH,
// as the Python extension and ruff's do. No vscode import: the unit tests run it under plain Node.
import * as fs from "fs";
import * as path from "path";

/** The virtual environments searched in each workspace folder, in order. */
export const VENV_DIRS = [".venv", "venv"];

/** Where a virtual environment keeps the mcc script on this platform. */
export function scriptsIn(venv: string, platform: NodeJS.Platform): string[] {
  return platform === "win32"
    ? [path.win32.join(venv, "Scripts", "mcc.exe")]
    : [path.posix.join(venv, "bin", "mcc")];
}

export interface Located {
  /** The command to run: an absolute path, or "mcc" (looked up on PATH when run). */
  command: string;
  /** How it was found, for the log: "setting", "workspace venv", "VIRTUAL_ENV" or "PATH". */
  source: string;
}

/**
 * The mcc command: the `mcc.path` setting when the user changed it from "mcc" (a relative path is
 * taken from the first workspace folder); else the first workspace folder's .venv/ or venv/ that
 * has mcc; else the activated environment (VIRTUAL_ENV); else plain "mcc" from PATH.
 */
export function locateMcc(
  setting: string,
  folders: string[],
  env: NodeJS.ProcessEnv = process.env,
  platform: NodeJS.Platform = process.platform,
  exists: (file: string) => boolean = isFile,
): Located {
  const join = platform === "win32" ? path.win32 : path.posix;
  const configured = setting.trim();
  if (configured !== "" && configured !== "mcc") {
    const isPath = configured.includes("/") || configured.includes("\\");
    const command =
      isPath && !join.isAbsolute(configured) && folders.length > 0
        ? join.resolve(folders[0], configured)
        : configured;
    return { command, source: "setting" };
  }
  for (const folder of folders) {
    for (const dir of VENV_DIRS) {
      for (const script of scriptsIn(join.join(folder, dir), platform)) {
        if (exists(script)) {
          return { command: script, source: "workspace venv" };
        }
      }
    }
  }
  const active = env.VIRTUAL_ENV;
  if (active) {
    for (const script of scriptsIn(active, platform)) {
      if (exists(script)) {
        return { command: script, source: "VIRTUAL_ENV" };
      }
    }
  }
  return { command: "mcc", source: "PATH" };
}

function isFile(file: string): boolean {
  try {
    return fs.statSync(file).isFile();
  } catch {
    return false;
  }
}
