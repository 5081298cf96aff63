// The page's edit document (core document.h, docs/document.schema.json): the
// base mesh, named regions and the ordered ops, plus the ops undone (the redo
// list). Plain data; the core checks and replays it (op-runner.js sends it).
// toJSON() is what api.document() returns and what autosave stores.
import { badParameter } from '../shared/errors.js';

export const DOCUMENT_FORMAT = 'anisoform-document';
export const DOCUMENT_VERSION = 1;

const clone = (value) => structuredClone(value);
const sameSteps = (a, b) => JSON.stringify(a) === JSON.stringify(b);

export class EditDocument {
  /** @type {{name: string, vertices: number, triangles: number, hash: string}} */
  mesh;
  /** [{name, steps}] */
  regions = [];
  /** [{id, label, enabled, region, op}] */
  ops = [];
  /** Undone ops, the next to redo last. */
  undone = [];
  #nextId = 1;

  constructor(mesh) {
    this.mesh = { ...mesh };
  }

  /** A document from its JSON (already replayed by the core, so well-formed). */
  static fromJSON(json) {
    const document = new EditDocument(json.mesh);
    document.regions = clone(json.regions);
    document.ops = json.ops.map((op) => ({ label: op.id, enabled: true, ...clone(op) }));
    for (const { id } of document.ops) {
      const number = Number(/^op-(\d+)$/.exec(id)?.[1]);
      if (number >= document.#nextId) document.#nextId = number + 1;
    }
    return document;
  }

  /** The document with the ops done so far (regions no op uses are left out). */
  toJSON() {
    const used = new Set(this.ops.map((op) => op.region));
    return {
      format: DOCUMENT_FORMAT,
      version: DOCUMENT_VERSION,
      mesh: { ...this.mesh },
      regions: clone(this.regions.filter((region) => used.has(region.name))),
      ops: clone(this.ops),
    };
  }

  indexOf(opId) {
    const index = this.ops.findIndex((op) => op.id === opId);
    if (index < 0) throw badParameter(`the document has no op '${opId}'`);
    return index;
  }

  /** The region named for these select steps: an existing one with the same steps, or a new one. */
  regionFor(steps) {
    const existing = this.regions.find((region) => sameSteps(region.steps, steps));
    if (existing) return existing.name;
    let n = this.regions.length + 1;
    while (this.regions.some((region) => region.name === `region-${n}`)) n++;
    this.regions.push({ name: `region-${n}`, steps: clone(steps) });
    return `region-${n}`;
  }

  /** Appends an op (the redo list is dropped); returns it. */
  append({ label, steps, op }) {
    const entry = { id: `op-${this.#nextId++}`, label, enabled: true, region: this.regionFor(steps), op: clone(op) };
    this.ops.push(entry);
    this.undone.length = 0;
    return entry;
  }

  /** Takes back the op append() just added (its solve failed). */
  dropLast(entry) {
    if (this.ops.at(-1) === entry) this.ops.pop();
  }

  undoLast() {
    const op = this.ops.pop();
    if (op) this.undone.push(op);
    return op ?? null;
  }

  redoNext() {
    const op = this.undone.pop();
    if (op) this.ops.push(op);
    return op ?? null;
  }

  /**
   * The op with `patch` applied (a copy; the document is unchanged): its
   * transform merged into the op's, its method, direction and move replacing the op's.
   */
  withChanges(opId, { transform, method, direction, move }) {
    const entry = this.ops[this.indexOf(opId)];
    const op = clone(entry.op);
    if (transform) op.transform = { ...op.transform, ...clone(transform) };
    if (method !== undefined) op.method = method;
    if (direction !== undefined) op.direction = clone(direction);
    if (move !== undefined) op.move = clone(move);
    return op;
  }
}

/**
 * `json` with its base mesh named `meshName`, once it is opened on a mesh
 * file of that name (the document keeps the name the mesh was loaded
 * under). Without a name, or anything but a document, `json` as it is.
 */
export function withMeshFileName(json, meshName) {
  if (!json || typeof json !== 'object' || !json.mesh || typeof json.mesh !== 'object' || !meshName) return json;
  return { ...json, mesh: { ...json.mesh, name: meshName } };
}

/**
 * The select steps of the selection an op is committed with: the rule when
 * the selection came from region selects on the current rest pose, else its
 * weights as a sparse vertex list; an empty selection means the whole mesh
 * (selection-state.js, syncForEdit).
 */
export function regionSteps(rule, selection, selectionCount) {
  if (selectionCount === 0) return [{ region: { all: true } }];
  if (rule) return clone(rule);
  const vertices = [];
  const weights = [];
  for (let i = 0; i < selection.length; i++) {
    if (selection[i] > 0) {
      vertices.push(i);
      weights.push(selection[i]);
    }
  }
  return [{ region: { vertices, weights } }];
}

/**
 * Whether two documents' JSON (toJSON) say the same: the same values, the
 * order of an object's keys aside (a document read back by fromJSON lists an
 * op's keys in another order).
 */
export function sameDocument(a, b) {
  return canonical(a) === canonical(b);
}

function canonical(value) {
  return JSON.stringify(value, (_, v) => (v && typeof v === 'object' && !Array.isArray(v)
    ? Object.fromEntries(Object.keys(v).sort().map((key) => [key, v[key]]))
    : v));
}
