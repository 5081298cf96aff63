// What a screen reader says when work ends: a mesh loaded, an edit solved, a
// pattern flattened (errors and warnings have their own alert and status
// regions, messages.js). The status bar shows these figures but is no live
// region: it changes at every preview frame, which would talk over the user.
import { formatCount, formatPercent } from '../shared/number-format.js';
import { h } from './dom.js';

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
}
