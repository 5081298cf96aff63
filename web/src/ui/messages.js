// The error, notice and warning banners over the viewport. Errors say in
// plain words what went wrong and what to do (a load error also says the
// current mesh was kept); notices say what a load repaired or found, with the
// full list on demand, or that the user stopped a solve, until the positions
// or the pattern change; errors stay until an edit is committed or a
// pattern made after them (or another mesh is opened);
// warnings say that the last edit (or the live
// preview) folded triangles over, until the positions change again, or that
// the last flattening is not usable as one piece, until the pattern changes.
// All can be dismissed. On a narrow screen a long one shows three lines and a More
// button (narrow-layout.css): the flatten warning's eight lines covered most
// of a phone's 3D view.
import { foldOverWarning } from '../editor/edit-wording.js';

export function installMessages(root, { editor, lifetime }) {
  const error = root.querySelector('[data-testid=error]');
  const notice = root.querySelector('[data-testid=notice]');
  const warning = root.querySelector('[data-testid=warning]');
  const messages = [error, notice, warning];
  // Whether the text is cut short depends on the width: checked again when it changes.
  const resized = new ResizeObserver(() => messages.forEach(fitMoreButton));
  messages.forEach((element) => resized.observe(element));
  lifetime.defer(() => resized.disconnect());
  const show = (element, text, details = []) => {
    const more = Object.assign(document.createElement('button'), { className: 'message-more', type: 'button' });
    more.dataset.testid = 'message-more';
    more.onclick = () => {
      element.classList.toggle('expanded');
      fitMoreButton(element);
    };
    const body = Object.assign(document.createElement('span'), { className: 'message-body' });
    body.append(Object.assign(document.createElement('span'), { className: 'message-text', textContent: text }), more);
    if (details.length > 0) body.append(detailsList(details));
    element.classList.remove('expanded');
    const dismiss = Object.assign(document.createElement('button'), {
      className: 'dismiss',
      type: 'button',
      textContent: '×',
      title: 'Dismiss',
      onclick: () => (element.hidden = true),
    });
    // Named in words: a screen reader said "times" or "multiplication sign".
    dismiss.setAttribute('aria-label', 'Dismiss message');
    element.replaceChildren(body, dismiss);
    element.hidden = false;
    fitMoreButton(element);
  };
  const hideAll = () => {
    error.hidden = true;
    notice.hidden = true;
    warning.hidden = true;
  };
  editor.on('error', ({ message }) => show(error, message.replace(/\.?\s*$/, '.')));
  editor.on('notice', ({ message, details, source, field }) => {
    show(notice, message, details);
    notice.dataset.source = source;
    notice.dataset.field = field ?? '';
  });
  // element.dataset.source: what put the message there (a notice: 'load',
  // 'cancel', 'busy', 'save', 'select' or 'field'; a warning: 'edit', 'preview' or 'flatten').
  const hideFrom = (element, source) => {
    if (element.dataset.source === source) element.hidden = true;
  };
  // "Cancelled: ... as they were" holds until a later edit, undo or
  // flattening changes them; then it would speak of the wrong state.
  const clearCancelNotice = () => hideFrom(notice, 'cancel');
  // An edit's warning comes after its 'change'; undo, redo and the next edit clear it.
  const warn = (message, source) => {
    show(warning, message);
    warning.dataset.source = source;
  };
  const clearWarning = (source) => hideFrom(warning, source);
  editor.on('change', ({ reason }) => {
    if (reason !== 'positions') return;
    warning.hidden = true;
    clearCancelNotice();
    hideFrom(notice, 'save'); // "No edits to save yet" is moot once there is a shape to save
    hideFrom(notice, 'field'); // so is a value a field did not take, once an edit is made
  });
  // "Undo waits until the solve has ended" is moot once it has.
  editor.on('busy', (busy) => !busy && hideFrom(notice, 'busy'));
  // "Nothing to select at the view centre" is moot once something is selected.
  editor.on('selection', ({ live }) => !live && hideFrom(notice, 'select'));
  editor.on('warning', ({ message, source = 'edit' }) => warn(message, source));
  // The live preview warns while it folds; the commit's own warning follows its 'change'.
  editor.on('stats', ({ live, inverted }) => {
    // An edit solved and committed: an error of an earlier action (an edit
    // refused, a failed export) is behind the user now.
    if (!live) error.hidden = true;
    if (!live) return;
    if (inverted > 0) warn(foldOverWarning(inverted), 'preview');
    else clearWarning('preview');
  });
  editor.on('gesture', (active) => !active && clearWarning('preview'));
  // A new flattening (its own warning follows) or none: the last one's warning is moot.
  // A flattening that succeeded puts an earlier error behind the user, as a
  // committed edit does ("nothing is selected" stayed beside the pattern).
  editor.on('pattern', (pattern) => {
    clearWarning('flatten');
    if (!pattern) return;
    clearCancelNotice();
    error.hidden = true;
  });
  // A new load makes the old messages moot, whether it succeeds (its notice
  // comes after) or fails (its error comes after).
  editor.on('loading', hideAll);
  editor.on('mesh', hideAll);
  return {
    showError: (text) => show(error, text),
    // A field's refused value is moot once the field takes one (ui/fields.js 'accepted').
    clearFieldNotice: (field) => notice.dataset.field === field && hideFrom(notice, 'field'),
  };
}

// More while the text is cut short (only where the layout clamps it), Less once opened.
function fitMoreButton(element) {
  const text = element.querySelector('.message-text');
  const more = element.querySelector('.message-more');
  if (!text || !more || element.hidden) return;
  const expanded = element.classList.contains('expanded');
  more.hidden = !expanded && !(text.scrollHeight > text.clientHeight + 1);
  more.textContent = expanded ? 'Less' : 'More';
  more.setAttribute('aria-expanded', String(expanded));
}

function detailsList(lines) {
  const details = document.createElement('details');
  details.dataset.testid = 'notice-details';
  details.append(
    Object.assign(document.createElement('summary'), { textContent: 'Details' }),
    ...lines.map((line) => Object.assign(document.createElement('p'), { textContent: line })),
  );
  return details;
}
