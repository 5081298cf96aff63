// <anisoform-modeller src="part.glb" edits="part-edits.json" ui="none">: a
// modeller as an HTML element. Attributes: src (a mesh URL, loaded when set
// or changed), edits (the URL of saved edits, opened on src when set or
// changed: both changed together open the edits on the new mesh, or show it
// without them when they cannot be opened), ui
// ('full', the default, or 'none'; a change lays the same modeller out
// anew: its worker, mesh, edits and an edit in flight go on, and listeners
// hear no load again; a value not known is reported and the modeller kept). The api's
// events come out as DOM CustomEvents ('change', 'error', 'progress', with the
// api's payload as `detail`); `.api` is the modeller's api while connected.
// Removing the element disposes the modeller (once the task that removed it
// has not put it back: moved to another parent, it keeps its work);
// connecting it again builds a new one.
// The solver worker: the element's own pool (ended on disconnect); `.solvers`, a pool from
// createSolverPool, shares workers with other elements and modellers: the
// worker then goes back to it on disconnect.
import { createModeller } from './create-modeller.js';
import { ElementApi } from './element-api.js';
import { UI_MODES } from './modeller-layout.js';
import { badParameter } from '../shared/errors.js';
import { SolverPool } from '../worker/solver-pool.js';

const RELAYED_EVENTS = ['change', 'error', 'progress'];

// Outside a browser (a server render, a Node script importing the package)
// there is no HTMLElement: the class is then defined on a plain base and
// never registered, so importing the package does not throw.
const ElementBase = typeof HTMLElement === 'undefined' ? class {} : HTMLElement;

export class AnisoformModellerElement extends ElementBase {
  static observedAttributes = ['src', 'edits', 'ui', 'materials'];
  #modeller = null;
  #offs = [];
  /** The embedder's pool (the `solvers` property), or null. */
  #sharedSolvers = null;
  /** While connected without a shared pool: the pool a rebuild takes the worker from. */
  #ownSolvers = null;
  /** Whether src changed since the last load (a change of edits alone opens them on the mesh loaded). */
  #srcChanged = false;
  #reconciling = false;
  /** The ui the modeller is laid out for. */
  #ui = 'full';
  /** `.api`: one object across ui changes (element-api.js). */
  #api = new ElementApi();
  /** Settles `.api.ready` with the load a src or edits change starts. */
  #settleReady = null;

  /** A pool (createSolverPool) to take the solver worker from and give it back to; used from the next connection or ui change. */
  get solvers() {
    return this.#sharedSolvers;
  }

  set solvers(pool) {
    if (pool != null && !(pool instanceof SolverPool)) {
      throw badParameter('anisoform-modeller: solvers must be a pool made by createSolverPool(), or null');
    }
    this.#sharedSolvers = pool ?? null;
  }

  /**
   * The modeller's api (window.anisoform's interface), or null while
   * disconnected: the same object across ui changes, its listeners kept.
   */
  get api() {
    return this.#modeller ? this.#api.api : null;
  }

  connectedCallback() {
    // Moved (removed and put back in one task, as frameworks and dialogs
    // move elements): the modeller and its work go on.
    if (this.#modeller) return;
    if (getComputedStyle(this).display === 'inline') this.style.display = 'block';
    this.#build();
  }

  disconnectedCallback() {
    // A task later, not a microtask: a move whose code awaits between the
    // removal and the insertion (an async framework hook, a transition)
    // runs its continuation as a microtask, after a microtask teardown had
    // disposed the modeller and its edits.
    setTimeout(() => {
      if (this.isConnected) return;
      this.#teardown();
      this.#ownSolvers?.dispose();
      this.#ownSolvers = null;
    }, 0);
  }

  attributeChangedCallback(name, previous, value) {
    if (!this.#modeller || previous === value) return;
    if (name === 'ui') {
      this.#layOutFor(value ?? 'full');
    } else if (name === 'materials') {
      this.#modeller.setMaterials(value !== null);
    } else {
      // src and edits set one after the other (a configurator switching
      // products) load once: the new mesh with the new edits.
      this.#srcChanged ||= name === 'src';
      if (this.#reconciling) return;
      this.#reconciling = true;
      // `ready` is this src's from now on (read right after setting it).
      this.#api.follow(new Promise((resolve) => {
        this.#settleReady = resolve;
      }));
      queueMicrotask(() => this.#reconcile());
    }
  }

  #reconcile() {
    this.#reconciling = false;
    const src = this.getAttribute('src');
    const edits = this.getAttribute('edits');
    const srcChanged = this.#srcChanged;
    this.#srcChanged = false;
    if (!this.#modeller) {
      this.#settleReady?.();
      this.#settleReady = null;
      return;
    }
    const done = () => {}; // the 'error' event has told
    const modeller = this.#modeller;
    let loading = null;
    if (edits && srcChanged && src) {
      // A new product whose edits cannot be opened is shown without them (as
      // at the start), not the product before: open() put that one back.
      loading = modeller.open(edits, src).catch((error) => {
        if (modeller !== this.#modeller || error.meshFailed) throw error; // the mesh itself failed: said once
        return modeller.load(src);
      });
    } else if (edits) {
      loading = modeller.open(edits);
    } else if (srcChanged && src) {
      loading = modeller.load(src);
    }
    loading?.catch(done);
    this.#settleReady?.(loading); // `ready`: this src and edits
    this.#settleReady = null;
  }

  // A new ui: the same modeller laid out anew (createModeller's setUi). It
  // was rebuilt on its work: an edit in flight was rejected ("disposed") and
  // the load replayed to the listeners. An unknown value is refused as the
  // option is, as an 'error' event, and the modeller stays as it is.
  #layOutFor(ui) {
    if (!UI_MODES.includes(ui)) {
      const message = `anisoform-modeller: ui must be ${UI_MODES.map((m) => `'${m}'`).join(' or ')}, got '${ui}'`;
      this.dispatchEvent(new CustomEvent('error', { detail: { code: 'bad-parameter', message } }));
      return;
    }
    if (ui === this.#ui) return;
    this.#modeller.setUi(ui);
    this.#ui = ui;
  }

  // The modeller from the attributes.
  #build() {
    const src = this.getAttribute('src');
    if (this.#sharedSolvers) {
      this.#ownSolvers?.dispose();
      this.#ownSolvers = null;
    } else {
      this.#ownSolvers ??= new SolverPool();
    }
    const edits = this.getAttribute('edits');
    const ui = this.getAttribute('ui') ?? 'full';
    // A ui not known at connection builds the default one (and says so), as a change to it keeps the last.
    this.#ui = UI_MODES.includes(ui) ? ui : 'full';
    const start = { ...(src ? { mesh: src } : {}), ...(src && edits ? { document: edits } : {}) };
    this.#modeller = createModeller(this, {
      ui: this.#ui,
      materials: this.hasAttribute('materials'),
      ...start,
      solvers: this.#sharedSolvers ?? this.#ownSolvers,
    });
    const modeller = this.#modeller;
    const { api } = modeller;
    this.#api.attach(api);
    this.#offs = RELAYED_EVENTS.map((type) => api.on(type, (detail) => this.dispatchEvent(new CustomEvent(type, { detail }))));
    if (ui !== this.#ui) this.#layOutFor(ui);
  }

  #teardown() {
    for (const off of this.#offs) off();
    this.#offs = [];
    this.#modeller?.dispose();
    this.#modeller = null;
  }
}

/**
 * Registers the element as <anisoform-modeller> (once per page), or under
 * another name: a class is registered under one name only, so each other
 * name gets a subclass of its own (the package's import has registered
 * the class itself, and a custom name always threw).
 */
export function defineModellerElement(name = 'anisoform-modeller') {
  if (typeof customElements === 'undefined' || customElements.get(name)) return;
  const registered = customElements.getName?.(AnisoformModellerElement) ?? (customElements.get('anisoform-modeller') === AnisoformModellerElement ? 'anisoform-modeller' : null);
  customElements.define(name, registered ? class extends AnisoformModellerElement {} : AnisoformModellerElement);
}
