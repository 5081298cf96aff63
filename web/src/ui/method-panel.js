// Solver method and the iteration cap of committed edits.
import { h, section } from './dom.js';
import { numberField, selectField, showWhen } from './fields.js';

export function methodPanel({ settings }) {
  const arapNote = h('p', { className: 'hint' },
    'ARAP with handles: drag the fully selected part; the soft border bends, the rest stays.');
  return section(
    'Method',
    selectField(settings, 'solver', {
      key: 'method',
      label: 'Solver',
      options: [
        ['anarap', 'AnARAP'],
        ['andefgrad', 'AnDefGrad'],
        ['arap', 'ARAP with handles'],
        ['linear', 'Linear'],
      ],
    }),
    numberField(settings, 'solver', { key: 'iterations', label: 'Iterations', min: 1, max: 500, step: 1, integer: true }),
    showWhen(settings, 'solver', arapNote, (s) => s.method === 'arap'),
  );
}
