// mcc debug driven by a real DAP client: DebugClient, the client VS Code's debug adapters are
// tested with (@vscode/debugadapter-testsupport, npm). The session for each dialect: a
// breakpoint in a loop, run to it, read the position and a variable, step into a subroutine,
// change an input, continue to the end. MCC is the mcc command (the test sets it to the venv's).
import { test } from 'node:test';
import assert from 'node:assert/strict';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { DebugClient } from '@vscode/debugadapter-testsupport';

const FIXTURES = path.join(path.dirname(fileURLToPath(import.meta.url)), '..', 'fixtures');
const MCC = process.env.MCC || 'mcc';

// The branch each program takes once input 1 is flipped: the test that runs this file computes it
// from a run without the debugger (the products' input polarities decide the default).
const FLIPPED = JSON.parse(process.env.MCC_FLIPPED_BRANCH || '{}');

// file, loop line, call line, subroutine line, loop variable, axis
const PROGRAMS = [
  ['loop.mxt', 10, 11, 20, 'Q1', '1'],
  ['loop.prg', 8, 9, 18, 'V1', 'X'],
  ['loop.x150', 16, 17, 4, 'VAR1', '1'],
];

async function scopes(dc, frameId) {
  const response = await dc.scopesRequest({ frameId });
  return Object.fromEntries(response.body.scopes.map((s) => [s.name, s.variablesReference]));
}

async function vars(dc, ref) {
  const response = await dc.variablesRequest({ variablesReference: ref });
  return response.body.variables;
}

for (const [file, loopLine, callLine, subLine, counter, axis] of PROGRAMS) {
  test(`a debugging session on ${file}`, async () => {
    const branch = FLIPPED[file];
    assert.ok(typeof branch === 'number', `MCC_FLIPPED_BRANCH has no line for ${file}`);
    const program = path.join(FIXTURES, file);
    const dc = new DebugClient(MCC, 'debug', 'mcc');
    await dc.start();
    try {
      // launch, breakpoint in the loop, run to it
      await dc.hitBreakpoint({ program }, { path: program, line: loopLine });
      let stack = (await dc.stackTraceRequest({ threadId: 1 })).body.stackFrames;
      let refs = await scopes(dc, stack[0].id);
      const variables = await vars(dc, refs['Program variables']);
      assert.equal(variables.find((v) => v.name === counter).value, '0');
      const axes = await vars(dc, refs['Axes']);
      assert.match(axes.find((v) => v.name === `axis ${axis}`).value, /^1000 steps/);

      // over the increment to the call, then into the subroutine (X150: the sequence)
      await Promise.all([dc.nextRequest({ threadId: 1 }), dc.assertStoppedLocation('step', { path: program, line: callLine })]);
      await Promise.all([dc.stepInRequest({ threadId: 1 }), dc.assertStoppedLocation('step', { path: program, line: subLine })]);
      stack = (await dc.stackTraceRequest({ threadId: 1 })).body.stackFrames;
      assert.equal(stack[1].line, callLine);

      // flip input 1 while paused; the program then takes the other branch
      refs = await scopes(dc, stack[0].id);
      const io = await vars(dc, refs['Inputs and outputs']);
      const level = io.find((v) => v.name === 'input 1').value;
      const flipped = level === '1' ? '0' : '1';
      const set = await dc.setVariableRequest({ variablesReference: refs['Inputs and outputs'], name: 'input 1', value: flipped });
      assert.equal(set.body.value, flipped);
      await dc.setBreakpointsRequest({ source: { path: program }, breakpoints: [{ line: branch }] });
      await Promise.all([dc.continueRequest({ threadId: 1 }), dc.assertStoppedLocation('breakpoint', { path: program, line: branch })]);

      // and on to the end
      await Promise.all([dc.continueRequest({ threadId: 1 }), dc.waitForEvent('terminated')]);
    } finally {
      await dc.stop();
    }
  });
}
