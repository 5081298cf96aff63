// The pane beside the 3D view in flatten mode: a header (colour by the error
// along or across the wanted direction, fit to view) over the PatternView.
import { COMPRESSION_ERROR_RANGE } from '../viewer/heatmap-display.js';
import { PatternView } from '../viewer/pattern-view.js';
import { h } from './dom.js';
import { selectField } from './fields.js';

export function patternPane(container, { editor, settings, lifetime }) {
  const host = h('div', { className: 'pattern-host' });
  const view = new PatternView(host, lifetime);
  const fit = h('button', { className: 'button', title: 'Fit the pattern to the pane (double-click)', onclick: () => view.fit() }, 'Fit');
  container.append(
    h('header', { className: 'pattern-header' },
      h('h2', {}, 'Pattern'),
      selectField(settings, 'flatten', {
        key: 'colorBy', label: 'Colour', options: [['compression', 'Error along'], ['cross', 'Error across']],
      }),
      fit),
    host,
  );
  const syncColoring = () => view.setColoring(settings.values.flatten.colorBy, COMPRESSION_ERROR_RANGE);
  settings.on('change', ({ section }) => section === 'flatten' && syncColoring());
  syncColoring();
  // What the pane shows, for tests and assistive tools: pieces and triangles drawn.
  const show = (pattern) => {
    container.dataset.pieces = pattern ? String(pattern.grainlines.length) : '0';
    container.dataset.triangles = pattern ? String(pattern.triangles.length / 3) : '0';
    view.show(pattern);
  };
  editor.on('pattern', show);
  const syncVisible = () => (container.hidden = settings.values.mode !== 'flatten');
  settings.on('change', ({ section }) => section === 'mode' && syncVisible());
  syncVisible();
  show(null);
  return view;
}
