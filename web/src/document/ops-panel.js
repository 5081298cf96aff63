// The side panel's list of the edit document's ops (a non-destructive stack,
// like Blender's modifiers): each op can be toggled off and on, deleted,
// moved up or down, selected, and its amounts edited; the later ops re-run
// (api.setOpEnabled, api.removeOp, api.moveOp, api.setParameter), and each
// change is a step of the history.
// Opening an op shows its region on the mesh (as the op evaluates it, on its
// input) in the selection's colours, without touching the selection itself:
// looking is no step of the history, and "Use current selection" takes the
// selection made before (or after) opening it. Closing the op shows the
// selection again. Its soft border can be changed too.
import { formatCount } from '../shared/number-format.js';
import { h, section } from '../ui/dom.js';
import { falloffField, opFields } from './op-fields.js';

// The rows are drawn anew on every change: the control that had the focus
// (an op's name, an amount, Move up, the toggle) gets it back in the new
// rows; when it is gone or disabled (Move up at the top), its op's name; when
// the op is gone (deleted), the name of the op now in its place: a keyboard
// user carries on where they were. With no op left, the Edits heading (the
// focus fell to <body>, and the next Tab started at the top of the page).
function focusWithin(list, heading) {
  const focused = list.contains(globalThis.document.activeElement) ? globalThis.document.activeElement : null;
  if (!focused) return { restore: () => {} };
  const find = (testId) => (testId ? list.querySelector(`[data-testid="${CSS.escape(testId)}"]`) : null);
  const testId = focused.getAttribute('data-testid');
  const row = focused.closest('li');
  const rowIndex = [...list.children].indexOf(row);
  return {
    restore: () => {
      const same = find(testId);
      const target = same && !same.disabled ? same
        : find(row?.dataset.op && `op-select-${row.dataset.op}`)
          ?? list.querySelectorAll('.op-label')[Math.min(rowIndex, list.children.length - 1)]
          ?? heading;
      target.focus();
    },
  };
}

export function opsPanel({ api, editor }) {
  const list = h('ol', { className: 'op-list', 'data-testid': 'op-list' });
  const empty = h('p', { className: 'op-empty' }, 'No edits yet: each committed edit appears here.');
  let selected = null;
  // The editor reports failures itself (the banner); a refused change only
  // needs the rows drawn again, so that the fields show the values kept.
  const redrawIfRefused = (promise) => promise.catch(() => render());

  // Up and down in the list (the order the ops run in).
  const orderControls = (entry, index, count) => h('div', { className: 'row op-order' },
    [['up', index - 1, 'Move up', 'Run this edit before the one above it'],
      ['down', index + 1, 'Move down', 'Run this edit after the one below it']].map(([way, to, text, title]) =>
      h('button', {
        type: 'button',
        className: 'button',
        disabled: to < 0 || to >= count,
        title,
        'data-testid': `op-${way}-${entry.id}`,
        onclick: () => redrawIfRefused(api.moveOp(entry.id, to)),
      }, text)));

  const regionControls = (entry) => h('div', { className: 'op-region' },
    h('span', { 'data-testid': `op-region-${entry.id}` }, regionText(entry)),
    falloffField(entry, editor.ops.stepsOfRegion(entry.id), {
      setRegion: (steps) => redrawIfRefused(api.setRegion(entry.id, steps)),
      redraw: render,
    }),
    h('button', {
      type: 'button',
      className: 'button',
      'data-testid': `op-use-selection-${entry.id}`,
      title: "The current selection replaces this edit's region; it and the later edits re-run",
      onclick: () => editor.ops.useSelectionAsRegion(entry.id)
        .catch((error) => editor.report(error, 'The region was not changed')),
    }, "Use current selection as this op's region"));

  // The op's name: Enter or leaving the field names it (a step of the
  // history), Esc puts the name back; an empty one is the old name again.
  const nameField = (entry) => h('label', { className: 'field op-amount' }, 'Name',
    h('input', {
      type: 'text',
      value: entry.label || entry.id,
      maxLength: 80,
      'data-testid': `op-name-${entry.id}`,
      onkeydown: (event) => {
        if (event.key === 'Enter') event.target.blur();
        if (event.key !== 'Escape') return;
        event.target.value = entry.label || entry.id;
        event.stopPropagation();
      },
      onchange: (event) => {
        const name = event.target.value.trim();
        if (name === '' || name === entry.label) {
          event.target.value = entry.label || entry.id;
          return;
        }
        redrawIfRefused(api.renameOp(entry.id, name));
      },
    }));

  // The op's region drawn as a selection would be (not committed: no history step).
  // The region shown ({region, count}): a new region of the op (its soft
  // border changed, the selection made its region) is shown anew; the rows
  // drawn again keep its count.
  let shown = null;
  const regionText = (entry) => (shown?.region === entry.region && shown.count !== null
    ? `Region: ${entry.region} (${formatCount(shown.count)} vertices, shown on the mesh)`
    : `Region: ${entry.region}`);
  const showRegion = (entry) => {
    shown = { region: entry.region, count: null };
    return editor.ops.regionWeights(entry.id)
      .then((weights) => {
        if (selected !== entry.id) return;
        editor.showSelection(weights);
        shown = { region: entry.region, count: weights.reduce((sum, w) => sum + (w > 0 ? 1 : 0), 0) };
        const label = list.querySelector(`[data-testid="${CSS.escape(`op-region-${entry.id}`)}"]`);
        if (label) label.textContent = regionText(entry);
      })
      .catch((error) => editor.report(error, 'The region could not be shown'));
  };
  const showSelectionAgain = () => editor.document && editor.showSelection(editor.document.selection);

  const row = (entry, index, ops) => {
    const isSelected = entry.id === selected;
    return h('li', { className: `op-row${isSelected ? ' selected' : ''}${entry.enabled ? '' : ' disabled'}`, 'data-op': entry.id },
      // The label is the touch target (44 px on phones), the box keeps its size.
      h('label', { className: 'op-toggle', title: entry.enabled ? 'Turn this edit off' : 'Turn this edit on' },
        h('input', {
          type: 'checkbox',
          checked: entry.enabled,
          'aria-label': `${entry.label || entry.id} on`,
          'data-testid': `op-toggle-${entry.id}`,
          onchange: (event) => redrawIfRefused(api.setOpEnabled(entry.id, event.target.checked)),
        })),
      h('button', {
        className: 'op-label',
        'data-testid': `op-select-${entry.id}`,
        'aria-expanded': String(isSelected),
        title: 'Show this edit\'s amounts and region (Delete deletes it)',
        // Delete (or Backspace) on the focused name deletes the edit, as the × does.
        onkeydown: (event) => {
          if (event.key !== 'Delete' && event.key !== 'Backspace') return;
          event.preventDefault();
          redrawIfRefused(api.removeOp(entry.id));
        },
        onclick: () => {
          selected = isSelected ? null : entry.id;
          shown = null;
          render(); // shows the region of the op opened
          if (!selected) showSelectionAgain();
        },
      }, entry.label || entry.id),
      h('button', {
        type: 'button',
        className: 'dismiss op-delete',
        title: 'Delete this edit: the later edits re-run (Undo puts it back)',
        'aria-label': `Delete ${entry.label || entry.id}`,
        'data-testid': `op-delete-${entry.id}`,
        onclick: () => redrawIfRefused(api.removeOp(entry.id)),
      }, '×'),
      isSelected ? h('div', { className: 'op-amounts' },
        nameField(entry),
        opFields(entry, {
          change: (patch) => redrawIfRefused(api.setParameter(entry.id, patch)),
          // Typing previews the last edit (warm-started iterations, cheap);
          // an earlier one's preview replays every later edit, seconds a
          // keystroke on a big mesh, so it waits for the value's commit.
          // A value being typed may be half-written ("0."): its preview's refusal says nothing.
          preview: (patch) => entry.enabled && index === ops.length - 1
            && editor.ops.setParameter(entry.id, patch, { preview: true }).catch(() => {}),
          dropPreview: () => editor.ops.dropPreview(),
          redraw: render,
        }),
        regionControls(entry),
        ops.length > 1 ? orderControls(entry, index, ops.length) : null) : null);
  };

  function render() {
    const document = editor.ops.document;
    const ops = document?.ops ?? [];
    if (selected && !ops.some((entry) => entry.id === selected)) {
      selected = null; // its op is gone (deleted, undone): the selection shows again
      showSelectionAgain();
    }
    const focus = focusWithin(list, heading);
    list.replaceChildren(...ops.map(row));
    const open = ops.find((entry) => entry.id === selected);
    if (open && shown?.region !== open.region) showRegion(open);
    empty.hidden = ops.length > 0;
    focus.restore();
  }
  editor.on('document', render);
  editor.on('mesh', render);

  const panel = section('Edits', empty, list);
  const heading = panel.querySelector('h2');
  heading.tabIndex = -1; // focusable by script only: no Tab stop
  return panel;
}
