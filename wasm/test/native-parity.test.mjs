// The WASM build gives the native build's results: the same edits through the
// native CLI (ANISO_CLI=/path/to/anisoform), once as flags and once as the very
// op object JS passes (`--op FILE.json`), and through a WASM session agree
// within 1e-6 of the bounding-box diagonal (the WASM positions are float32).
// AnARAP runs a fixed number of iterations (tolerance 0) so that all stop at
// the same step.
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import { mkdtempSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import path from 'node:path';
import { after, before, test } from 'node:test';

import { boundingBox, loadAnisoform, maxVertexDistance, meshPath, objVertices, sessionWith } from '../node-support.mjs';

const cli = process.env.ANISO_CLI;
const skip = cli ? false : 'ANISO_CLI is not set: give the path of the native `anisoform` CLI to compare against';

let wasm;
let outputDir;
before(async () => {
  ({ wasm } = await loadAnisoform());
  outputDir = mkdtempSync(path.join(tmpdir(), 'anisoform-parity-'));
});
after(() => {
  if (outputDir) rmSync(outputDir, { recursive: true, force: true });
});

// The upper 40 % of the mesh along its longest axis, with a soft border.
function upperBox(info) {
  const { min, max } = info.bbox;
  const extent = max.map((x, k) => x - min[k]);
  const axis = extent.indexOf(Math.max(...extent));
  const boxMin = [...min];
  boxMin[axis] = min[axis] + 0.6 * extent[axis];
  const direction = [0, 0, 0];
  direction[axis] = 1;
  return { min: boxMin, max: [...max], direction, falloff: 0.1 * extent[axis] };
}

const EDITS = [
  { name: 'anarap stretch', method: 'anarap', transform: { scale: [1.4, 0.9] }, cli: ['--scale', '1.4,0.9'], iterations: 12 },
  { name: 'andefgrad stretch', method: 'andefgrad', transform: { scale: [1.4, 0.9] }, cli: ['--scale', '1.4,0.9'] },
];
const CASES = [
  ...['closed/spool.off', 'closed/torus.obj'].flatMap((file) => EDITS.map((edit) => ({ file, ...edit }))),
  { file: 'closed/spool.off', name: 'andefgrad twist', method: 'andefgrad', twist: 40 },
];

for (const c of CASES) {
  test(`${c.file}, ${c.name}: WASM equals native within 1e-6 of the diagonal`, { skip }, (t) => {
    const session = sessionWith(wasm, c.file);
    try {
      const box = upperBox(session.info());
      session.select({ box: { min: box.min, max: box.max } }, { falloff: box.falloff });
      const transform = c.twist ? { twist: { axis: box.direction, degreesPerUnit: c.twist } } : c.transform;
      const op = { method: c.method, direction: { type: 'global', vector: box.direction }, transform };
      const cliArgs = ['deform', meshPath(c.file), '', '--method', c.method,
        '--select', `box:${[...box.min, ...box.max].join(',')}`, '--falloff', String(box.falloff),
        '--direction', `global:${box.direction.join(',')}`];
      cliArgs.push(...(c.twist ? ['--twist', `${box.direction.join(',')}:${c.twist}`] : c.cli));
      if (c.iterations) {
        Object.assign(op, { maxIterations: c.iterations, tolerance: 0 });
        cliArgs.push('--iterations', String(c.iterations), '--tolerance', '0');
      }
      const output = path.join(outputDir, `${path.basename(c.file)}-${c.name.replace(/\s/g, '-')}.obj`);
      cliArgs[2] = output;
      const report = JSON.parse(execFileSync(cli, cliArgs, { encoding: 'utf8' }));

      const result = session.deform(op);
      assert.equal(result.selected, report.selected);
      assert.equal(result.iterations, report.iterations);
      const native = objVertices(readFileSync(output, 'utf8'));
      const diagonal = boundingBox(native).diagonal;
      assert.ok(report.max_displacement > 1e-3 * diagonal, 'the edit moved the mesh');

      // The same op object, as JSON, through the CLI's --op (the selection stays a flag).
      const opFile = `${output}.op.json`;
      writeFileSync(opFile, JSON.stringify(op));
      const opOutput = `${output}.op.obj`;
      execFileSync(cli, ['deform', meshPath(c.file), opOutput, '--op', opFile,
        '--select', `box:${[...box.min, ...box.max].join(',')}`, '--falloff', String(box.falloff)]);
      const fromOp = objVertices(readFileSync(opOutput, 'utf8'));
      assert.equal(maxVertexDistance(fromOp, native), 0, '--op and the flags give the same positions');

      const distance = maxVertexDistance(session.positions(), native);
      t.diagnostic(`max distance ${(distance / diagonal).toExponential(2)} x diagonal`);
      assert.ok(distance <= 1e-6 * diagonal, `max distance ${distance} > 1e-6 x diagonal ${diagonal}`);
    } finally {
      session.delete();
    }
  });
}
