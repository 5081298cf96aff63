// Compiled by `npm run check:types --prefix web` (web/tsconfig.json), never
// run: an embedder's calls written against the declarations, so that a
// declaration that stops describing the API as the specs use it fails to
// compile. Each call mirrors one the e2e specs make on window.anisoform, or
// (switchProduct) on the package's createModeller and createSolverPool.
import type { Anisoform, AnisoformError, DeformOp, EditDocument, FlattenOptions, Region } from '../../web/src/api/anisoform';
import { AnisoformModellerElement, createModeller, createSolverPool } from '../../web/dist-lib/index';

export async function usage(api: Anisoform): Promise<number> {
  await api.ready;
  const region: Region = { sphere: { center: [0, 0.5, 0], radius: 0.2 } };
  const count: number = await api.select(region, { falloff: 0.1, mode: 'add' });
  const stretch: DeformOp = { method: 'anarap', direction: { type: 'global', vector: [0, 1, 0] }, transform: { scale: [1.5, 1] } };
  const drag: DeformOp = { method: 'andefgrad', direction: { type: 'screen', from: [10, 20], to: [40, 20] }, transform: { scale: 1.2 } };
  const twist: DeformOp = { method: 'anarap', transform: { twist: { axis: [0, 1, 0], degreesPerUnit: 90 } }, rotationSteps: 2 };
  for (const op of [stretch, drag, twist]) {
    const { iterations, inverted } = await api.deform(op);
    if (iterations < 0 || inverted < 0) return -1;
  }
  const options: FlattenOptions = { compress: [0.9, 1], patch: 'selection', direction: { type: 'global', vector: [1, 0, 0] } };
  const { metrics, uv } = await api.flatten(options);
  await api.exportPattern('svg', { mmPerUnit: 10 });
  api.on('error', ({ code, message }) => console.log(code, message));
  api.on('document', (document: EditDocument) => console.log(document.ops.length));
  api.on('positions', ({ positions, live, distortion }) => console.log(positions.length, live, distortion?.length));
  try {
    await api.deform(stretch);
  } catch (error) {
    if ((error as AnisoformError).code === 'cancelled') return 0;
  }
  return count + metrics.compressionErrorMax + uv.length;
}

// The element's events as the package README listens to them.
export function listen(element: AnisoformModellerElement): void {
  element.addEventListener('change', (event) => console.log(event.detail.reason));
  element.addEventListener('error', (event) => console.log(event.detail.code, event.detail.message));
  element.addEventListener('progress', (event) => console.log(event.detail.stage));
  element.addEventListener('click', () => console.log('a DOM event still types as before'));
}

// A configurator switching products: the second modeller takes the first one's warm worker.
export async function switchProduct(host: HTMLElement, next: string): Promise<number> {
  const solvers = createSolverPool({ keep: 1, idleSeconds: 30 });
  const first = createModeller(host, { ui: 'none', mesh: 'spool.off', solvers });
  await first.api.ready;
  first.dispose();
  const second = createModeller(host, { ui: 'none', mesh: next, solvers });
  await second.api.ready;
  const kept: number = solvers.size;
  second.dispose();
  solvers.dispose();
  return kept + second.held;
}
