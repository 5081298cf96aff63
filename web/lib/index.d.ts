// The anisoform package: createModeller, createSolverPool and <anisoform-modeller>.
// The api object's types (the same as window.anisoform on the standalone
// site) are in api.d.ts beside this file.
import type { Anisoform, ChangeEvent, ErrorEvent, ProgressEvent } from './api.js';

export * from './api.js';

/** A URL (resolved against the page), a File or Blob, or the file's bytes. */
export type MeshSource = string | URL | File | Blob | ArrayBuffer | ArrayBufferView;

export interface ModellerOptions {
  /** 'full' (default): side panel, status bar, messages, drag-and-drop; needs `import 'anisoform/style.css'`. 'none': the 3D view alone (orbit), edits through the api. */
  ui?: 'full' | 'none';
  /** The mesh to load first (default: none; `api.ready` then resolves once the solver is up). */
  mesh?: MeshSource;
  /** The file name of `mesh` when it is bytes or a nameless Blob: its extension picks the reader (obj, off, ply, stl, glb). */
  meshName?: string;
  /**
   * An edit document (saved edits), or its URL, to open on `mesh` as its base mesh (api.open); needs
   * `mesh`. Edits that cannot be opened leave `mesh` shown without them, the error reported as an
   * 'error' event (`ready` still resolves).
   */
  document?: unknown;
  /**
   * Keep the work (edit document and base mesh) in IndexedDB after every change and restore it on
   * the next start instead of `mesh` (default false: one store per origin, so only a page with a
   * single modeller should turn it on; the standalone site does).
   */
  autosave?: boolean;
  /** 'focus' (default): keyboard shortcuts while focus is inside the modeller. 'page': on the whole window (a page that is only the modeller). */
  keyboard?: 'focus' | 'page';
  /** The solver worker's URL (same origin), when a bundler or server moved it; default: solver-worker.js beside anisoform.js. */
  workerUrl?: string | URL;
  /** The WASM's URL; default: anisoform.wasm beside the worker. */
  wasmUrl?: string | URL;
  /**
   * A pool of warm solver workers (createSolverPool): the modeller takes an idle one (same
   * workerUrl and wasmUrl) instead of starting its own, and dispose() gives its worker back
   * when no request is in flight; its 3D view's WebGL renderer (canvas and context) likewise.
   */
  solvers?: SolverPool;
  /**
   * Draw a mesh opened from glTF with its own materials, textures and vertex colours, in the
   * edited shape (default false: the editing surface, which shows the selection and heat maps).
   */
  materials?: boolean;
}

export interface SolverPoolOptions {
  /** How many idle workers (and as many views' WebGL contexts) to keep (default 1; 0 keeps none). */
  keep?: number;
  /** How long an idle worker or view is kept before it is ended, in seconds (default 60). */
  idleSeconds?: number;
}

/**
 * Solver workers kept between modellers. Starting a worker (its scripts, the WASM compiled, its
 * code not yet optimised) is most of a modeller's start; a page that disposes a modeller and
 * makes another can hand the worker on. A kept worker's WASM session is freed; its memory is kept
 * (WASM memory never shrinks) until it is taken, times out or the pool is disposed. The 3D view's
 * WebGL renderer is handed on the same way (its canvas and GL context; what it drew is freed).
 */
export interface SolverPool {
  /** The number of idle workers kept. */
  readonly size: number;
  /** Ends the idle workers and views' GL contexts; those given back later are ended at once. */
  dispose(): void;
}

/** Throws an Error with code 'bad-parameter' for an unknown option or a bad value. */
export function createSolverPool(options?: SolverPoolOptions): SolverPool;

export interface Modeller {
  /** The modeller's api: load, select, deform, undo, export, events... */
  readonly api: Anisoform;
  /** Like api.load, and also takes a URL; failures are also 'error' events. */
  load(source: MeshSource, name?: string): Promise<{ vertices: number; triangles: number }>;
  /**
   * Opens an edit document (saved edits), or its URL, on the mesh loaded, or on `mesh` as its base
   * (like api.open, which takes no URLs); failures are also 'error' events, and the work is kept.
   */
  open(document: unknown, mesh?: MeshSource, name?: string): Promise<void>;
  /** A glTF mesh drawn with its own materials (true) or the editing surface (false), as the option `materials`. */
  setMaterials(on: boolean): void;
  /**
   * Lays the same modeller out for another ui ('full' | 'none'), as the element's `ui` attribute does:
   * its worker, mesh, edits, selection, camera and an edit in flight go on; throws 'bad-parameter' for another value.
   */
  setUi(ui: 'full' | 'none'): void;
  /** Cancels the pending frame, stops the ResizeObservers, the worker (and its WASM session; an idle worker goes back to the `solvers` pool) and removes every listener and element it added. */
  dispose(): void;
  /** Listeners and clean-up steps the modeller still holds (0 after dispose). */
  readonly held: number;
}

export function createModeller(container: HTMLElement, options?: ModellerOptions): Modeller;

/**
 * <anisoform-modeller src="part.glb" edits="part-edits.json" ui="none">: attributes src (mesh URL,
 * loaded when set or changed), edits (saved edits' URL, opened on src when set or changed; src and
 * edits changed together open the new edits on the new mesh), ui ('full' | 'none') and materials
 * (present: a glTF mesh drawn with its own materials, as the option); CustomEvents
 * 'change', 'error', 'progress' with the api's payload as `detail`; `.api`
 * while connected; disposed when disconnected. Registered on import.
 */
export class AnisoformModellerElement extends HTMLElement {
  readonly api: Anisoform | null;
  addEventListener<K extends keyof AnisoformModellerEventMap>(type: K,
    listener: (this: AnisoformModellerElement, event: AnisoformModellerEventMap[K]) => unknown,
    options?: boolean | AddEventListenerOptions): void;
  addEventListener(type: string, listener: EventListenerOrEventListenerObject, options?: boolean | AddEventListenerOptions): void;
  removeEventListener<K extends keyof AnisoformModellerEventMap>(type: K,
    listener: (this: AnisoformModellerElement, event: AnisoformModellerEventMap[K]) => unknown,
    options?: boolean | EventListenerOptions): void;
  removeEventListener(type: string, listener: EventListenerOrEventListenerObject, options?: boolean | EventListenerOptions): void;
  /**
   * A pool (createSolverPool) to take the solver worker from and give it back to on disconnect,
   * shared with other elements and modellers; used from the next connection or `ui` change.
   * Without one, a `ui` change still rebuilds on the same worker, and disconnecting ends it.
   */
  solvers: SolverPool | null;
}

/** The element's events: the api's, as CustomEvents with the api's payload as `detail`. */
export interface AnisoformModellerEventMap {
  change: CustomEvent<ChangeEvent>;
  error: CustomEvent<ErrorEvent>;
  progress: CustomEvent<ProgressEvent>;
}

/** Registers the element under `name` (default 'anisoform-modeller') if not yet registered. */
export function defineModellerElement(name?: string): void;

declare global {
  interface HTMLElementTagNameMap {
    'anisoform-modeller': AnisoformModellerElement;
  }
}
