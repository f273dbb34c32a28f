// Which mcc the extension runs: the setting, then the workspace's virtual environment, then the
// activated one, then PATH (src/locate.ts). The file system is faked: only listed files exist.
import { strict as assert } from "assert";
import { test } from "node:test";
import { locateMcc } from "../../src/locate";

function only(...files: string[]): (file: string) => boolean {
  return (file) => files.includes(file);
}

test("the workspace's .venv comes before PATH", () => {
  const found = locateMcc("mcc", ["/proj"], {}, "linux", only("/proj/.venv/bin/mcc"));
  assert.deepEqual(found, { command: "/proj/.venv/bin/mcc", source: "workspace venv" });
});

test("venv/ is searched when there is no .venv/", () => {
  const found = locateMcc("mcc", ["/proj"], {}, "linux", only("/proj/venv/bin/mcc"));
  assert.equal(found.command, "/proj/venv/bin/mcc");
});

test("each workspace folder is searched in order", () => {
  const found = locateMcc("mcc", ["/a", "/b"], {}, "linux", only("/b/.venv/bin/mcc"));
  assert.equal(found.command, "/b/.venv/bin/mcc");
});

test("Windows: Scripts\\mcc.exe", () => {
  const found = locateMcc("mcc", ["C:\\proj"], {}, "win32", only("C:\\proj\\.venv\\Scripts\\mcc.exe"));
  assert.equal(found.command, "C:\\proj\\.venv\\Scripts\\mcc.exe");
});

test("the activated environment (VIRTUAL_ENV) comes after the workspace's", () => {
  const exists = only("/home/u/env/bin/mcc");
  assert.deepEqual(locateMcc("mcc", ["/proj"], { VIRTUAL_ENV: "/home/u/env" }, "linux", exists), {
    command: "/home/u/env/bin/mcc",
    source: "VIRTUAL_ENV",
  });
});

test("nothing found: plain mcc from PATH", () => {
  assert.deepEqual(locateMcc("mcc", ["/proj"], {}, "linux", only()), { command: "mcc", source: "PATH" });
});

test("a changed mcc.path wins, a relative one from the first folder", () => {
  const exists = only("/proj/.venv/bin/mcc");
  assert.equal(locateMcc("/opt/mcc/bin/mcc", ["/proj"], {}, "linux", exists).command, "/opt/mcc/bin/mcc");
  assert.equal(locateMcc("tools/mcc", ["/proj"], {}, "linux", exists).command, "/proj/tools/mcc");
  assert.equal(locateMcc("mcc-dev", ["/proj"], {}, "linux", exists).command, "mcc-dev");
});
