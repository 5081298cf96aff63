// A product configurator on the anisoform package, used as an embedder
// would: the <anisoform-modeller> element (no side panel) shows the spool,
// and three sliders set three edits of its upper part: height (stretch along
// the spool's axis), twist (about the axis) and thickness (across it).
//
// Every change is solved again from the original spool: the page steps back
// to the base mesh with api.undo() (which restores it exactly) and commits
// the three edits anew with api.deform(). While a slider moves ('input') the
// edits run a few iterations (a preview); when it is let go ('change') they
// are solved fully, so a slider position always gives the same shape. Moves
// that arrive while a solve runs are coalesced: only the latest is solved.
import 'anisoform';

const AXIS = [1, 0, 0]; // the spool's axis of revolution (x in spool.off)
const PREVIEW_ITERATIONS = 4; // as the modeller's own live drags
const FULL_ITERATIONS = 50; // the api's default for a committed edit
const form = document.querySelector('[data-testid=configurator]');
const status = form.querySelector('[data-testid=status]');
const sliders = { height: form.elements.height, twist: form.elements.twist, thickness: form.elements.thickness };
const { api } = document.querySelector('anisoform-modeller');

let applied = 0; // committed edits above the base mesh (and its selection)
let solving = false;
let wanted = null;
let updates = 0;

await api.ready;
const [lowest, highest] = extentAlong(api.positions(), AXIS);
const length = highest - lowest;
// The upper part: everything above the middle, blended over a fifth of the length.
await api.select({ box: { min: [0, -10, -10], max: [10, 10, 10] } }, { falloff: 0.2 * length });
setState('idle', 'Ready');

form.addEventListener('input', () => {
  showValues();
  request(PREVIEW_ITERATIONS);
});
form.addEventListener('change', () => request(FULL_ITERATIONS));
form.addEventListener('reset', () => {
  // The form puts the default values back after this event.
  setTimeout(() => {
    showValues();
    request(FULL_ITERATIONS);
  });
});
form.querySelector('[data-testid=export-glb]').addEventListener('click', exportGlb);
showValues();

function values() {
  return Object.fromEntries(Object.entries(sliders).map(([name, slider]) => [name, Number(slider.value)]));
}

function showValues() {
  const { height, twist, thickness } = values();
  form.querySelector('output[for=height]').value = `${height.toFixed(2)}×`;
  form.querySelector('output[for=twist]').value = `${twist}°`;
  form.querySelector('output[for=thickness]').value = `${thickness.toFixed(2)}×`;
}

// The edits for the slider values; one at its neutral value is left out, so
// the defaults give the original spool exactly.
function edits({ height, twist, thickness }, maxIterations) {
  const edit = (transform) => ({ method: 'anarap', direction: { type: 'global', vector: AXIS }, transform, maxIterations });
  const list = [];
  if (height !== 1) list.push(edit({ scale: [height, 1] }));
  if (twist !== 0) list.push(edit({ twist: { axis: AXIS, degreesPerUnit: twist / length } }));
  if (thickness !== 1) list.push(edit({ scale: [1, thickness] }));
  return list;
}

function request(maxIterations) {
  wanted = { values: values(), maxIterations };
  if (!solving) solveLatest();
}

async function solveLatest() {
  solving = true;
  setState('solving', 'Solving…');
  try {
    while (wanted) {
      const target = wanted;
      wanted = null;
      const started = performance.now();
      while (applied > 0 && api.undo()) applied--;
      for (const op of edits(target.values, target.maxIterations)) {
        await api.deform(op);
        applied++;
      }
      updates++;
      form.dataset.updates = String(updates);
      const what = target.maxIterations === FULL_ITERATIONS ? 'Solved' : 'Preview';
      status.textContent = `${what} in ${(performance.now() - started).toFixed(0)} ms`;
      form.dataset.solved = what === 'Solved' ? 'full' : 'preview';
    }
    setState('idle');
  } catch (error) {
    setState('idle', `Could not apply the change: ${error.message}`);
  } finally {
    solving = false;
  }
}

async function exportGlb() {
  const bytes = await api.export('glb');
  const url = URL.createObjectURL(new Blob([bytes], { type: 'model/gltf-binary' }));
  const link = Object.assign(document.createElement('a'), { href: url, download: 'spool.glb' });
  document.body.append(link);
  link.click();
  link.remove();
  setTimeout(() => URL.revokeObjectURL(url), 10_000);
}

function setState(state, message) {
  form.dataset.state = state;
  if (message !== undefined) status.textContent = message;
}

function extentAlong(positions, axis) {
  let min = Infinity;
  let max = -Infinity;
  for (let i = 0; i < positions.length; i += 3) {
    const t = positions[i] * axis[0] + positions[i + 1] * axis[1] + positions[i + 2] * axis[2];
    min = Math.min(min, t);
    max = Math.max(max, t);
  }
  return [min, max];
}
