// Status bar: mesh size, selection, last solve time (and whether it reached
// its iteration cap), frames per second, and progress of loading /
// factorizing (a bar with a fraction, or an indeterminate one when the
// worker cannot tell how far it is).
import { openSurface } from '../editor/problem-summary.js';
import { formatCount } from '../shared/number-format.js';
import { h } from './dom.js';

export function statusBar(container, { editor, viewer, lifetime }) {
  const mesh = h('span', { className: 'status-item status-mesh', 'data-testid': 'status-mesh' });
  const solve = h('span', { className: 'status-item status-solve', 'data-testid': 'status-solve' }, 'solve —');
  const fps = h('span', { className: 'status-item status-fps', 'data-testid': 'status-fps' });
  // A progressbar to assistive technology: how far when the worker can tell
  // (aria-valuenow), busy without a value when it cannot.
  const bar = h('span', {
    className: 'progress-bar', role: 'progressbar', 'aria-label': 'Progress', 'aria-valuemin': '0', 'aria-valuemax': '100',
  }, h('span', { className: 'progress-fill' }));
  const showFraction = (fraction, text) => {
    bar.classList.toggle('indeterminate', fraction === undefined);
    bar.firstChild.style.width = fraction === undefined ? '' : `${Math.round(fraction * 100)}%`;
    if (fraction === undefined) bar.removeAttribute('aria-valuenow');
    else bar.setAttribute('aria-valuenow', String(Math.round(fraction * 100)));
    bar.setAttribute('aria-valuetext', text);
  };
  const progressText = h('span', { className: 'progress-text' });
  // Stops a committed solve (Esc does too): the state before it stays.
  const cancel = h('button', {
    type: 'button', className: 'button progress-cancel', 'data-testid': 'cancel-solve', hidden: true,
    title: 'Stop this solve (Esc): the mesh stays as it was', onclick: () => editor.cancelSolve(),
  }, 'Cancel');
  const progress = h('span', { className: 'status-item progress', 'data-testid': 'progress', hidden: true }, bar, progressText, cancel);
  container.append(mesh, progress, h('span', { className: 'spacer' }), solve, fps);

  // The last committed solve's words: a drag's previews show over them, and
  // a drag dropped (Esc) shows them again ("preview 41.8 ms" stayed).
  let committed = { text: 'solve —', title: '' };
  const showCommitted = () => {
    solve.textContent = committed.text;
    solve.title = committed.title;
  };
  editor.on('gesture', (active) => !active && showCommitted());
  editor.on('mesh', (document) => {
    // The last solve was of the mesh before.
    committed = { text: 'solve —', title: '' };
    showCommitted();
    const surface = openSurface(document.info);
    mesh.textContent = `${formatCount(document.vertexCount)} vertices · ${formatCount(document.triangleCount)} triangles${surface.text}`;
    mesh.title = surface.title;
  });
  editor.on('stats', ({ ms, iterations, live, converged }) => {
    // A committed solve cut off by its iteration cap says so: on a large
    // mesh the default cap can end an edit before its energy settles.
    // (A live preview runs one iteration by design.)
    const capped = !live && converged === false;
    solve.textContent = `${live ? 'preview' : 'solve'} ${ms.toFixed(1)} ms · ${iterations} it${capped ? ' · cap reached' : ''}`;
    solve.title = capped
      ? 'The solve stopped at its iteration cap before the energy settled: raise Iterations (Method) for a closer result'
      : '';
    if (!live) committed = { text: solve.textContent, title: solve.title };
  });
  editor.on('progress', ({ stage, message, fraction }) => {
    // A background step (the solver's preparation) ending during a
    // committed solve leaves that solve's progress and its Cancel shown.
    if (stage === 'done' && editor.busy) return;
    progress.hidden = stage === 'done';
    progressText.textContent = fraction === undefined ? message : `${message} ${Math.round(fraction * 100)} %`;
    showFraction(fraction, progressText.textContent);
  });
  editor.on('busy', (busy) => {
    progress.hidden = !busy;
    cancel.hidden = !busy;
    if (busy) {
      progressText.textContent = 'Solving';
      showFraction(undefined, 'Solving');
    }
  });
  // Frames are drawn on demand, so an idle view draws none. The text is
  // only replaced when it changes: each replacement is a layout and a paint.
  lifetime.every(500, () => {
    const frames = viewer.framesPerSecond;
    const text = frames > 0 ? `${frames} fps` : 'idle';
    if (fps.textContent !== text) fps.textContent = text;
  });
}
