// The error, notice and warning banners over the viewport. Errors say in
// plain words what went wrong (a load error also says the current mesh was
// kept); notices say what a load repaired or found; warnings say that the
// last edit folded triangles over, until the positions change again. All can
// be dismissed.
export function installMessages(root, { editor }) {
  const error = root.querySelector('[data-testid=error]');
  const notice = root.querySelector('[data-testid=notice]');
  const warning = root.querySelector('[data-testid=warning]');
  const show = (element, text) => {
    element.replaceChildren(
      Object.assign(document.createElement('span'), { textContent: text }),
      Object.assign(document.createElement('button'), {
        className: 'dismiss',
        textContent: '×',
        title: 'Dismiss',
        onclick: () => (element.hidden = true),
      }),
    );
    element.hidden = false;
  };
  editor.on('error', ({ message }) => {
    const kept = editor.document ? ` The current mesh (${editor.document.name}) is unchanged.` : '';
    const sentence = message.replace(/\.?\s*$/, '.');
    show(error, message.startsWith('Could not load') ? sentence + kept : sentence);
  });
  editor.on('notice', ({ message }) => show(notice, message));
  // An edit's warning comes after its 'change'; undo, redo and the next edit clear it.
  editor.on('change', ({ reason }) => reason === 'positions' && (warning.hidden = true));
  editor.on('warning', ({ message }) => show(warning, message));
  // A successful load clears old messages; a new load's notice comes after.
  editor.on('mesh', () => {
    error.hidden = true;
    notice.hidden = true;
    warning.hidden = true;
  });
  return { showError: (text) => show(error, text) };
}
