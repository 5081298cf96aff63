// An init script for pages that create and dispose modellers: it counts, from
// outside the package, what a modeller could leave behind. window.__census()
// returns {workers, workersCreated, observers, listeners, detachedListeners, frames}:
//   workers    Workers created and not terminated
//   workersCreated  Workers created so far (a worker handed from one
//              modeller to the next is not created again)
//   observers  ResizeObservers observing something and not disconnected
//   listeners  DOM listeners added and not removed, on the window, the
//              document or an element still in the document
//   detachedListeners  the same on elements no longer in the document
//              (they go with the element; reported, not a leak)
//   frames     requestAnimationFrame calls so far (a view that keeps
//              redrawing adds to it)
export function installResourceCensus() {
  const workers = new Set();
  let workersCreated = 0;
  const NativeWorker = window.Worker;
  window.Worker = class CountedWorker extends NativeWorker {
    constructor(...args) {
      super(...args);
      workers.add(this);
      workersCreated += 1;
    }

    terminate() {
      workers.delete(this);
      super.terminate();
    }
  };

  const observers = new Set();
  const NativeResizeObserver = window.ResizeObserver;
  window.ResizeObserver = class CountedResizeObserver extends NativeResizeObserver {
    observe(...args) {
      observers.add(this);
      super.observe(...args);
    }

    disconnect() {
      observers.delete(this);
      super.disconnect();
    }
  };

  // One entry per (target, type, listener, capture), as the DOM keeps them.
  const listeners = new Map();
  const keyOf = (target, type, listener, options) => {
    const capture = typeof options === 'boolean' ? options : Boolean(options?.capture);
    return { type, listener, capture };
  };
  const entriesOf = (target) => {
    if (!listeners.has(target)) listeners.set(target, []);
    return listeners.get(target);
  };
  const same = (a, b) => a.type === b.type && a.listener === b.listener && a.capture === b.capture;
  const nativeAdd = EventTarget.prototype.addEventListener;
  const nativeRemove = EventTarget.prototype.removeEventListener;
  EventTarget.prototype.addEventListener = function add(type, listener, options) {
    if (listener && (this instanceof Node || this === window)) {
      const key = keyOf(this, type, listener, options);
      const entries = entriesOf(this);
      if (!entries.some((entry) => same(entry, key))) entries.push(key);
    }
    return nativeAdd.call(this, type, listener, options);
  };
  EventTarget.prototype.removeEventListener = function remove(type, listener, options) {
    const entries = listeners.get(this);
    if (entries) {
      const key = keyOf(this, type, listener, options);
      const index = entries.findIndex((entry) => same(entry, key));
      if (index >= 0) entries.splice(index, 1);
    }
    return nativeRemove.call(this, type, listener, options);
  };

  let frames = 0;
  const nativeRequestAnimationFrame = window.requestAnimationFrame.bind(window);
  window.requestAnimationFrame = (callback) => {
    frames++;
    return nativeRequestAnimationFrame(callback);
  };

  window.__census = () => {
    let attached = 0;
    let detached = 0;
    for (const [target, entries] of listeners) {
      const reachable = target === window || target === document || target.isConnected;
      if (reachable) attached += entries.length;
      else detached += entries.length;
    }
    return { workers: workers.size, workersCreated, observers: observers.size, listeners: attached, detachedListeners: detached, frames };
  };
}
