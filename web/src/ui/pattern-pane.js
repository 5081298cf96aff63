// The pane beside the 3D view in flatten mode: a header (colour by the error
// along or across the wanted direction, fit to view) over the PatternView.
import { heatRange } from '../viewer/heat-palettes.js';
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
  // The 3D heat map's range rule (Display panel: fixed or adapted), on the errors coloured here.
  let shown = null;
  const coloring = () => {
    const colorBy = settings.values.flatten.colorBy;
    const errors = shown ? (colorBy === 'cross' ? shown.crossError : shown.compressionError) : [];
    return [colorBy, heatRange('compression', errors, settings.values.display.heatRange).value];
  };
  const syncColoring = () => {
    const [colorBy, range] = coloring();
    container.dataset.range = String(range); // the legend's top, for tests and assistive tools
    view.setColoring(colorBy, range);
  };
  settings.on('change', ({ section }) => (section === 'flatten' || section === 'display') && syncColoring());
  syncColoring();
  // What the pane shows, for tests and assistive tools: pieces and triangles drawn.
  const show = (pattern) => {
    container.dataset.pieces = pattern ? String(pattern.grainlines.length) : '0';
    container.dataset.triangles = pattern ? String(pattern.triangles.length / 3) : '0';
    shown = pattern;
    const [colorBy, range] = coloring();
    container.dataset.range = String(range);
    view.show(pattern, [colorBy, range]);  // one drawing of the new pattern (96k triangles for the koala's head)
  };
  editor.on('pattern', show);
  const syncVisible = () => (container.hidden = settings.values.mode !== 'flatten');
  settings.on('change', ({ section }) => section === 'mode' && syncVisible());
  syncVisible();
  show(null);
  return view;
}
