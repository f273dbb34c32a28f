// The mcc command lines behind Compile, Simulate, Download and Upload (src/cli.ts), and how a
// compile report is read.
import { strict as assert } from "assert";
import { test } from "node:test";
import { compileArgs, compileOutput, downloadArgs, parseCompile, simulateArgs, uploadArgs } from "../../src/cli";

test("compile is always validated and writes into the output directory", () => {
  const output = compileOutput("/proj/src/feeder.mxt", "mcode", "build", "/proj");
  assert.equal(output, "/proj/build/feeder.mxt");
  assert.deepEqual(compileArgs("/proj/src/feeder.mxt", output, undefined), [
    "compile", "/proj/src/feeder.mxt", "--verify", "--format", "json", "-o", "/proj/build/feeder.mxt",
  ]);
});

test("compiling to another dialect names the target and its extension", () => {
  const output = compileOutput("/proj/cell.prg", "x150", "/tmp/out", "/proj");
  assert.equal(output, "/tmp/out/cell.x150");
  assert.deepEqual(compileArgs("/proj/cell.prg", output, "x150").slice(-2), ["--target", "x150"]);
});

test("simulate, download and upload pass the settings' extra arguments last", () => {
  assert.deepEqual(simulateArgs("a.prg", "/t/a.png", ["--until", "5"]), ["sim", "a.prg", "--plot", "/t/a.png", "--until", "5"]);
  assert.deepEqual(downloadArgs("a.mxt", "COM3", ["--save"]), ["download", "a.mxt", "--port", "COM3", "--save"]);
  assert.deepEqual(uploadArgs("x150", "u.x150", "socket://h:1", []), [
    "upload", "--port", "socket://h:1", "--dialect", "x150", "-o", "u.x150",
  ]);
});

test("a compile report with an error is not ok", () => {
  const report = parseCompile(JSON.stringify({
    files: [{ diagnostics: [{ code: "G003", severity: "error", message: "no equivalent", line: 12, column: 1 }], stats: { lines: 3 } }],
  }));
  assert.equal(report.ok, false);
  assert.equal(report.diagnostics[0].code, "G003");
  assert.equal(parseCompile(JSON.stringify({ files: [{ diagnostics: [], stats: { lines: 32 } }] })).lines, 32);
});
