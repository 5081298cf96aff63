// The listeners one layout's panels add to the modeller's editor and
// settings, held for that layout only: a ui change (createModeller's
// setUi) ends them with the layout, and shows the panels of the new one the
// modeller's state as it is (prime) instead of leaving them empty until its
// next event. The modeller itself (worker, document, mesh, an edit in
// flight) goes on untouched: a ui change used to rebuild it, rejecting the
// edit in flight ("disposed") and replaying the load to every listener.

/** `emitter` for one layout: its on() listeners are also ended by `lifetime` and kept in `heard`. */
export function scopedEmitter(emitter, lifetime, heard) {
  return new Proxy(emitter, {
    get(target, key) {
      if (key === 'on') {
        return (event, callback) => {
          const off = target.on(event, callback);
          heard.push({ event, callback });
          lifetime.defer(off);
          return off;
        };
      }
      // The emitter's own methods and getters run on it (its private fields).
      const value = Reflect.get(target, key, target);
      return typeof value === 'function' ? value.bind(target) : value;
    },
    set: (target, key, value) => Reflect.set(target, key, value, target),
  });
}

/**
 * Tells the listeners `heard` of a new layout's panels what the editor
 * holds now, as its events would have: the mesh, the document, the
 * selection, the history, whether it solves, the last flattening. Only
 * those: the modeller's own listeners and the api's hear nothing.
 */
export function primeEditorListeners(heard, editor) {
  const mesh = editor.document;
  const state = [
    ['mesh', mesh],
    ['document', mesh && editor.ops.document],
    ['selection', mesh && { weights: mesh.selection, count: mesh.selectionCount, live: false }],
    ['history', editor.history.state()],
    ['busy', editor.busy],
    ['pattern', editor.pattern],
  ];
  for (const [event, payload] of state) {
    if (payload === null || payload === undefined) continue;
    for (const entry of heard) if (entry.event === event) entry.callback(payload);
  }
}
