// <anisoform-modeller src="part.glb" ui="none">: a modeller as an HTML
// element. Attributes: src (a mesh URL, loaded when set or changed), ui
// ('full', the default, or 'none'; a change rebuilds the modeller). The api's
// events come out as DOM CustomEvents ('change', 'error', 'progress', with the
// api's payload as `detail`); `.api` is the modeller's api while connected.
// Disconnecting disposes the modeller; connecting again builds a new one.
import { createModeller } from './create-modeller.js';

const RELAYED_EVENTS = ['change', 'error', 'progress'];

export class AnisoformModellerElement extends HTMLElement {
  static observedAttributes = ['src', 'ui'];
  #modeller = null;
  #offs = [];

  /** The modeller's api (window.anisoform's interface), or null while disconnected. */
  get api() {
    return this.#modeller?.api ?? null;
  }

  connectedCallback() {
    if (getComputedStyle(this).display === 'inline') this.style.display = 'block';
    this.#build();
  }

  disconnectedCallback() {
    this.#teardown();
  }

  attributeChangedCallback(name, previous, value) {
    if (!this.#modeller || previous === value) return;
    if (name === 'ui') {
      this.#teardown();
      this.#build();
    } else if (name === 'src' && value) {
      this.#modeller.load(value).catch(() => {}); // the 'error' event has told
    }
  }

  #build() {
    const src = this.getAttribute('src');
    this.#modeller = createModeller(this, {
      ui: this.getAttribute('ui') ?? 'full',
      ...(src ? { mesh: src } : {}),
    });
    const { api } = this.#modeller;
    this.#offs = RELAYED_EVENTS.map((type) => api.on(type, (detail) => this.dispatchEvent(new CustomEvent(type, { detail }))));
    api.ready.catch(() => {}); // reported as an 'error' event
  }

  #teardown() {
    for (const off of this.#offs) off();
    this.#offs = [];
    this.#modeller?.dispose();
    this.#modeller = null;
  }
}

/** Registers the element as <anisoform-modeller> (once per page). */
export function defineModellerElement(name = 'anisoform-modeller') {
  if (!customElements.get(name)) customElements.define(name, AnisoformModellerElement);
}
