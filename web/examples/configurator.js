// A product configurator on the anisoform package, used as an embedder
// would: the <anisoform-modeller> element (no side panel) shows the spool,
// and three sliders set three edits of its upper part: height (stretch along
// the spool's axis), twist (about the axis) and thickness (across it).
//
// The three edits are made once, at the sliders' neutral values, and become
// the ops of the modeller's edit document; a slider then only changes its
// op's amount with api.setParameter: while it moves ('input') as a live
// preview, and when it is let go ('change') committed, which re-solves the
// op and the ones after it from the op's input. A slider position therefore
// always gives the same shape (the document's replay), and the document
// holds the three ops (undo in the view can take back slider changes, and
// then the three first edits: a slider whose op is gone waits, disabled).
import 'anisoform';

const AXIS = [1, 0, 0]; // the spool's axis of revolution (x in spool.off)
const form = document.querySelector('[data-testid=configurator]');
const status = form.querySelector('[data-testid=status]');
const sliders = { height: form.elements.height, twist: form.elements.twist, thickness: form.elements.thickness };
const { api } = document.querySelector('anisoform-modeller');

await api.ready;
const [lowest, highest] = extentAlong(api.positions(), AXIS);
const length = highest - lowest;

// Each slider's edit: its transform at a slider value, given the op's
// transform as the document stores it (the twist keeps its resolved origin).
const EDITS = {
  height: (stored, value) => ({ scale: [value, 1] }),
  twist: (stored, value) => ({ twist: { axis: AXIS, ...stored.twist, degreesPerUnit: value / length } }),
  thickness: (stored, value) => ({ scale: [1, value] }),
};
// And back: the slider value an op's transform holds (a neutral stretch is stored without its scale).
const VALUES = {
  height: (transform) => transform.scale?.[0] ?? 1,
  twist: (transform) => (transform.twist?.degreesPerUnit ?? 0) * length,
  thickness: (transform) => transform.scale?.[1] ?? 1,
};

// The upper part: everything above the middle, blended over a fifth of the length.
await api.select({ box: { min: [0, -10, -10], max: [10, 10, 10] } }, { falloff: 0.2 * length });
const ops = {};
for (const [name, transformAt] of Object.entries(EDITS)) {
  await api.deform({ method: 'anarap', direction: { type: 'global', vector: AXIS },
    transform: transformAt({}, Number(sliders[name].value)) });
  const op = api.document().ops.at(-1);
  ops[name] = { id: op.id, stored: op.op.transform, sent: VALUES[name](op.op.transform) };
}

let updates = 0;
let committing = 0;
// Every shape the modeller shows, preview or committed, is one update.
api.on('positions', ({ live }) => {
  updates++;
  form.dataset.updates = String(updates);
  form.dataset.solved = live ? 'preview' : 'full';
});
setState('idle', 'Ready');

// Undo and redo (Ctrl+Z in the view) change the ops' amounts too: a slider
// follows its op when the op holds another value than the slider last sent
// (not on the slider's own commits, so that a slider dragged again during
// one does not jump). An op undone away (one of the three first edits)
// leaves its slider disabled until redo brings it back.
api.on('change', ({ reason }) => {
  if (reason !== 'document') return;
  const document = api.document();
  for (const [name, slider] of Object.entries(sliders)) {
    const op = document.ops.find((entry) => entry.id === ops[name].id);
    slider.disabled = !op;
    if (!op) continue;
    ops[name].stored = op.op.transform;
    const value = VALUES[name](op.op.transform);
    if (value === ops[name].sent) continue;
    ops[name].sent = value;
    slider.value = String(value);
  }
  showValues();
});

form.addEventListener('input', (event) => {
  showValues();
  if (event.target.name in EDITS) setAmount(event.target.name, { preview: true });
});
form.addEventListener('change', (event) => {
  if (event.target.name in EDITS) setAmount(event.target.name);
});
form.addEventListener('reset', () => {
  // The form puts the default values back after this event.
  setTimeout(() => {
    showValues();
    for (const name of Object.keys(EDITS)) setAmount(name);
  });
});
form.querySelector('[data-testid=export-glb]').addEventListener('click', exportGlb);
showValues();

function showValues() {
  const value = (name) => Number(sliders[name].value);
  form.querySelector('output[for=height]').value = `${value('height').toFixed(2)}×`;
  form.querySelector('output[for=twist]').value = `${value('twist')}°`;
  form.querySelector('output[for=thickness]').value = `${value('thickness').toFixed(2)}×`;
}

// A preview that a newer value superseded resolves with null: nothing to say.
async function setAmount(name, { preview = false } = {}) {
  const { id, stored } = ops[name];
  const transform = EDITS[name](stored, Number(sliders[name].value));
  if (preview) {
    api.setParameter(id, { transform }, { preview: true }).catch(showFailure);
    return;
  }
  ops[name].sent = VALUES[name](transform);
  committing++;
  setState('solving', 'Solving…');
  const started = performance.now();
  try {
    await api.setParameter(id, { transform });
    if (committing === 1) setState('idle', `Solved in ${(performance.now() - started).toFixed(0)} ms`);
  } catch (error) {
    showFailure(error);
  } finally {
    committing--;
  }
}

function showFailure(error) {
  status.textContent = `Could not apply the change: ${error.message}`;
  if (committing <= 1) form.dataset.state = 'idle';
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
