// An init script for pages that create and dispose modellers: it counts, from
// outside the package, what a modeller could leave behind. window.__census()
// returns {workers, workersCreated, observers, listeners, detachedListeners, frames, contexts, glObjects}:
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
//   contexts   WebGL contexts made and not lost (a kept view's among them:
//              solver-pool.js)
//   glObjects  GL buffers, textures, programs and vertex arrays made and not
//              deleted, in those contexts
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

  // GL objects per context: made minus deleted.
  const contexts = new Map();
  const made = new WeakSet();
  const nativeGetContext = HTMLCanvasElement.prototype.getContext;
  HTMLCanvasElement.prototype.getContext = function getContext(type, ...rest) {
    const context = nativeGetContext.call(this, type, ...rest);
    if (context && /^(webgl|webgl2|experimental-webgl)$/.test(type) && !contexts.has(context)) contexts.set(context, 0);
    return context;
  };
  const KINDS = [['createBuffer', 'deleteBuffer'], ['createTexture', 'deleteTexture'], ['createProgram', 'deleteProgram'],
    ['createVertexArray', 'deleteVertexArray']];
  for (const prototype of [WebGLRenderingContext.prototype, WebGL2RenderingContext.prototype]) {
    for (const [make, remove] of KINDS) {
      const nativeMake = prototype[make];
      const nativeDelete = prototype[remove];
      if (!nativeMake) continue;
      prototype[make] = function counted(...args) {
        const object = nativeMake.apply(this, args);
        if (object && contexts.has(this)) {
          made.add(object);
          contexts.set(this, contexts.get(this) + 1);
        }
        return object;
      };
      prototype[remove] = function counted(object) {
        if (made.delete(object)) contexts.set(this, contexts.get(this) - 1);
        return nativeDelete.call(this, object);
      };
    }
  }

  window.__census = () => {
    const live = [...contexts].filter(([context]) => !context.isContextLost());
    let attached = 0;
    let detached = 0;
    for (const [target, entries] of listeners) {
      const reachable = target === window || target === document || target.isConnected;
      if (reachable) attached += entries.length;
      else detached += entries.length;
    }
    return {
      workers: workers.size, workersCreated, observers: observers.size, listeners: attached, detachedListeners: detached, frames,
      contexts: live.length, glObjects: live.reduce((sum, [, count]) => sum + count, 0),
    };
  };
}
