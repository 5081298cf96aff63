// Direction source: the screen drag, a global axis (X/Y/Z/custom), the
// principal curvature field (min/max), or the arrows placed on the surface.
import { h, section } from './dom.js';
import { selectField, showWhen, vectorField } from './fields.js';

export function directionPanel({ settings }) {
  const arrowsNote = h('p', { className: 'hint' });
  const syncArrows = () =>
    (arrowsNote.textContent = settings.values.arrows.length
      ? `${settings.values.arrows.length} arrow(s), spread into a smooth field.`
      : 'Place arrows with the Arrows tool.');
  settings.on('change', ({ section: name }) => name === 'arrows' && syncArrows());
  syncArrows();
  const screenNote = h('p', { className: 'hint' }, 'The drag sets the direction and the amount.');

  return section(
    'Direction',
    selectField(settings, 'direction', {
      key: 'source',
      label: 'Source',
      options: [
        ['screen', 'Screen drag'],
        ['global', 'Global axis'],
        ['curvature', 'Curvature'],
        ['arrows', 'Arrows'],
      ],
    }),
    showWhen(settings, 'direction', screenNote, (d) => d.source === 'screen'),
    showWhen(settings, 'direction',
      selectField(settings, 'direction', { key: 'axis', label: 'Axis', options: [['x', 'X'], ['y', 'Y'], ['z', 'Z'], ['custom', 'Custom']] }),
      (d) => d.source === 'global'),
    showWhen(settings, 'direction', vectorField(settings, 'direction', { key: 'custom', label: 'Vector' }),
      (d) => d.source === 'global' && d.axis === 'custom'),
    showWhen(settings, 'direction',
      selectField(settings, 'direction', { key: 'curvature', label: 'Field', options: [['max', 'Max curvature'], ['min', 'Min curvature']] }),
      (d) => d.source === 'curvature'),
    showWhen(settings, 'direction', arrowsNote, (d) => d.source === 'arrows'),
  );
}
