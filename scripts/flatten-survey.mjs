#!/usr/bin/env node
// Flattens every open test mesh whole with the CLI's defaults (su 0.8 along
// the longest axis), ours and the uniform baseline, and prints one Markdown
// row per mesh: iterations, converged, folded triangles, mean compression and
// combined (compression + cross) errors, seconds. The numbers the README's
// "Flattening refinement" quotes come from here. The bunny alone takes about
// 100 s: use a release build.
//
//   node scripts/flatten-survey.mjs [--cli build-dev/cli/anisoform] [mesh-name ...]
import { execFileSync } from 'node:child_process';
import { mkdtempSync, readdirSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { dirname, join, parse, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';
import { parseArgs } from 'node:util';

const root = resolve(dirname(fileURLToPath(import.meta.url)), '..');
const { values, positionals } = parseArgs({
  options: { cli: { type: 'string', default: process.env.ANISO_CLI ?? join(root, 'build-dev/cli/anisoform') } },
  allowPositionals: true,
});
const openDir = join(process.env.ANISO_SHARED_DIR ?? join(root, '..', 'shared'), 'meshes', 'open');
const files = readdirSync(openDir)
  .filter((file) => /\.(obj|off|ply|stl)$/i.test(file))
  .filter((file) => positionals.length === 0 || positionals.includes(parse(file).name))
  .sort();
const scratch = mkdtempSync(join(tmpdir(), 'flatten-survey-'));

function flatten(file, extra) {
  const out = join(scratch, 'pattern.obj');
  const json = execFileSync(values.cli, ['flatten', join(openDir, file), out, '--compress', '0.8', ...extra], {
    encoding: 'utf8',
    stdio: ['ignore', 'pipe', 'ignore'],
    maxBuffer: 64 * 1024 * 1024,
  });
  return JSON.parse(json);
}

const combined = (m) => m.compression_error_mean + m.cross_error_mean;
const fixed = (x) => x.toFixed(4);
console.log('| mesh | iterations | converged | folded | compression ours / baseline | combined ours / baseline | s |');
console.log('|---|---|---|---|---|---|---|');
try {
  for (const file of files) {
    const ours = flatten(file, []);
    const base = flatten(file, ['--baseline', 'uniform']);
    console.log(
      `| ${parse(file).name} | ${ours.iterations} | ${ours.converged} | ${ours.flipped} | ` +
        `${fixed(ours.compression_error_mean)} / ${fixed(base.compression_error_mean)} | ` +
        `${fixed(combined(ours))} / ${fixed(combined(base))} | ${ours.seconds.toFixed(1)} |`,
    );
  }
} finally {
  rmSync(scratch, { recursive: true, force: true });
}
