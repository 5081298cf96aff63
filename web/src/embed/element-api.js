// The api of an <anisoform-modeller>, one object for the element's life:
// a ui change builds a new modeller (with the work), and an api taken from
// the element before it (a configurator's `const { api } = element`) used to
// be the disposed one's, refusing every call and its listeners silent. This
// one forwards each call to the modeller of the moment, moves its on()
// listeners to each new one, and its `ready` follows the latest src: a src
// that failed (404) and then a good one resolve it again.
export class ElementApi {
  #current = null;
  #listeners = new Set(); // {event, callback, off}
  #ready = Promise.resolve();
  /** The object handed out (read-only): its methods those of the current modeller's api. */
  api;

  constructor() {
    const forward = (name) => (...args) => this.#current[name](...args);
    const target = {};
    this.api = new Proxy(target, {
      get: (_, name) => {
        if (name === 'ready') return this.#ready;
        if (name === 'on') return (event, callback) => this.#on(event, callback);
        const value = this.#current?.[name];
        return typeof value === 'function' ? forward(name) : value;
      },
      has: (_, name) => name in (this.#current ?? {}),
      ownKeys: () => Reflect.ownKeys(this.#current ?? {}),
      getOwnPropertyDescriptor: (_, name) => {
        if (!this.#current || !(name in this.#current)) return undefined;
        return { value: this.api[name], enumerable: true, configurable: true, writable: false };
      },
      set: () => false,
      defineProperty: () => false,
      deleteProperty: () => false,
    });
  }

  /** The modeller's api from now on (its listeners moved to it); `ready`: what it is starting with. */
  attach(modellerApi) {
    for (const entry of this.#listeners) {
      entry.off?.();
      entry.off = modellerApi.on(entry.event, entry.callback);
    }
    this.#current = modellerApi;
    this.follow(modellerApi.ready);
  }

  /** `ready` becomes `promise` (the start, or a new src's load). */
  follow(promise) {
    this.#ready = Promise.resolve(promise).then(() => undefined);
    this.#ready.catch(() => {}); // reported as an 'error' event
  }

  #on(event, callback) {
    const entry = { event, callback, off: this.#current.on(event, callback) };
    this.#listeners.add(entry);
    return () => {
      entry.off?.();
      this.#listeners.delete(entry);
    };
  }
}
