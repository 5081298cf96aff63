// What a screen reader says when work ends: a mesh loaded, an edit solved, a
// pattern flattened, the selection changed, a step undone, redone or an edit
// deleted (history 'step'), a tool chosen by its key (say()); and that a
// solve still runs after a second (Esc cancels it). Errors and warnings have
// their own alert and status regions (messages.js). The status bar shows
// these figures but is no live region: it changes at every preview frame,
// which would talk over the user. One region for the whole modeller.
import { formatCount, formatPercent } from '../shared/number-format.js';
import { h } from './dom.js';
import { selectionText } from './selection-panel.js';

const LONG_SOLVE_MS = 1000;

export function installAnnouncer(container, { editor }) {
  const region = h('p', { className: 'visually-hidden', role: 'status', 'aria-live': 'polite', 'data-testid': 'announcer' });
  container.append(region);
  // The same words twice in a row are still said again (a second edit alike).
  const say = (text) => {
    region.textContent = region.textContent === text ? `${text}\u00a0` : text;
  };
  editor.on('mesh', (document) => say(`Loaded ${document.name}: ${formatCount(document.vertexCount)} vertices, `
    + `${formatCount(document.triangleCount)} triangles`));
  editor.on('stats', ({ live, ms, iterations, converged }) => {
    if (live) return;
    say(`Edit solved: ${iterations} iterations, ${ms.toFixed(0)} ms${converged === false ? ', stopped at the iteration cap' : ''}`);
  });
  editor.on('pattern', (pattern) => {
    if (!pattern) return;
    const m = pattern.metrics;
    say(`Flattened: compression error ${formatPercent(m.compressionErrorMean)} mean, `
      + `${formatPercent(m.compressionErrorMax)} max; cross error ${formatPercent(m.crossErrorMean)} mean, `
      + `${formatPercent(m.crossErrorMax)} max; ${m.flipped} flipped triangles`);
  });
  editor.on('selection', ({ live }) => !live && editor.document && say(selectionText(editor.document)));
  const STEP_WORDS = { done: '', undone: 'Undone: ', redone: 'Redone: ' };
  editor.on('step', ({ action, label, announce }) => announce && say(`${STEP_WORDS[action]}${label}`));
  let solving = null;
  editor.on('busy', (busy) => {
    clearTimeout(solving);
    solving = busy ? setTimeout(() => say('Solving… Esc cancels'), LONG_SOLVE_MS) : null;
  });
  return { say };
}
