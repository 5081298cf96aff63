// The viewport: renderer, camera, orbit controls and its frames.
// Frames are drawn on demand: requestRender asks the browser for one
// animation frame, and nothing runs between requests, so an idle editor costs
// neither GPU nor CPU time (a loop of animation frames that drew nothing kept
// the browser's frame pipeline running: 14 % of a core on an idle page). The
// drawn frames are also counted for the status bar's frames per second.
import { Color, PerspectiveCamera, Scene, Vector3, WebGLRenderer } from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';
import { EventEmitter } from '../shared/event-emitter.js';
import { freeGpuObjects } from './free-gpu-objects.js';
import { rendersInSoftware } from './software-rendering.js';

// A three-quarter view from the front right, slightly above.
const DEFAULT_VIEW_DIRECTION = new Vector3(0.8, 0.35, -1).normalize();

const SPHERE_MARGIN = 1.1;

export class Viewer extends EventEmitter {
  /** The pending animation frame's id, 0 when none is requested. */
  #frameRequest = 0;
  #disposed = false;
  #frameTimes = [];
  /** () => {center, diagonal} of the shown mesh, or null before one is loaded. */
  #boundsSource = () => null;
  /** Target and distance the last fit left, to tell whether the user zoomed or panned since. */
  #lastFit = null;
  #resizeObserver;
  /** The drawing buffer's size as last set: 'width x height @ pixel ratio'. */
  #bufferSize = '';
  /** The view's size in CSS pixels, as of the last resize (read without laying the page out). */
  width = 1;
  height = 1;

  /**
   * @param {HTMLElement} container  receives the canvas
   * @param {import('../embed/lifetime.js').Lifetime} lifetime  cancels the pending frame, ends the observer and the GL context
   * @param {import('../worker/solver-pool.js').SolverPool | null} [pool]  takes a kept renderer (canvas and GL context) from it, and gives it back at dispose
   */
  constructor(container, lifetime, pool = null) {
    super();
    this.container = container;
    // A CPU rasteriser draws without multisampling (software-rendering.js).
    const antialias = !rendersInSoftware();
    // Kept renderers are told apart by the context attribute that differs.
    const rendererKey = antialias ? 'antialias' : 'no-antialias';
    // Its drawing buffer is sized by #resize, below.
    this.renderer = pool?.takeRenderer(rendererKey) ?? new WebGLRenderer({ antialias });
    this.canvas = this.renderer.domElement;
    this.canvas.dataset.testid = 'viewport';
    this.canvas.dataset.antialias = String(antialias);
    this.canvas.setAttribute('aria-label', '3D viewport: drag on the mesh to use the tool, elsewhere to orbit');
    this.canvas.tabIndex = 0;
    container.prepend(this.canvas);
    // A browser keeps about 16 live WebGL contexts a page and takes the
    // oldest one's away beyond that (or after a GPU reset): the view then
    // stayed blank without a word. Said ('contextlost'), and when the
    // browser gives the context back three.js rebuilds its state, but not
    // the clear colour (the view came back black).
    const clearColor = new Color(0x1d2127);
    this.renderer.setClearColor(clearColor);
    lifetime.listen(this.canvas, 'webglcontextlost', (event) => {
      event.preventDefault(); // asks the browser to restore it when it can
      if (!this.#disposed) this.emit('contextlost'); // not the dispose's own forceContextLoss
    });
    lifetime.listen(this.canvas, 'webglcontextrestored', () => {
      this.renderer.setClearColor(clearColor);
      this.requestRender();
      this.emit('contextrestored');
    });

    this.scene = new Scene();
    this.camera = new PerspectiveCamera(35, 1, 0.01, 100);
    this.controls = new OrbitControls(this.camera, this.canvas);
    this.controls.addEventListener('change', () => this.requestRender());

    this.#resizeObserver = new ResizeObserver(() => this.#resize());
    this.#resizeObserver.observe(container);
    this.#resize();
    lifetime.defer(() => {
      this.#disposed = true;
      cancelAnimationFrame(this.#frameRequest);
      this.#resizeObserver.disconnect();
      this.controls.dispose();
      this.canvas.remove();
      if (pool) {
        // The next modeller's view draws with it: what this one drew goes
        // now, and so do the canvas's data attributes (this view's state:
        // the surface, glyph counts... that the next one sets anew).
        freeGpuObjects(this.scene);
        for (const key of Object.keys(this.canvas.dataset)) delete this.canvas.dataset[key];
        pool.giveRenderer(this.renderer, rendererKey);
      } else {
        this.renderer.dispose();
        // Browsers keep only a few WebGL contexts per page: give this one back now.
        this.renderer.forceContextLoss();
      }
    });
  }

  /**
   * Moves the view into `container` (a new layout of the same modeller: the
   * element's ui changed), with what was drawn over it (`overlays`: the
   * axis gizmo, the brush cursor...); the camera and the GL context stay.
   */
  moveTo(container, overlays = []) {
    this.#resizeObserver.unobserve(this.container);
    this.container = container;
    container.prepend(this.canvas);
    container.append(...overlays);
    this.#resizeObserver.observe(container);
    this.#resize();
  }

  /** Draws the scene in the next animation frame (once, however often it is asked before). */
  requestRender() {
    if (this.#frameRequest !== 0 || this.#disposed) return;
    this.#frameRequest = requestAnimationFrame(() => this.#draw());
  }

  #draw() {
    this.#frameRequest = 0;
    this.renderer.render(this.scene, this.camera);
    const now = performance.now();
    this.#frameTimes.push(now);
    while (this.#frameTimes[0] < now - 1000) this.#frameTimes.shift();
    this.emit('frame', now);
  }

  /** Frames drawn during the last second. */
  get framesPerSecond() {
    const now = performance.now();
    return this.#frameTimes.filter((time) => time >= now - 1000).length;
  }

  #resize() {
    const width = Math.max(1, this.container.clientWidth);
    const height = Math.max(1, this.container.clientHeight);
    this.width = width;
    this.height = height;
    // Setting a canvas's width or height clears and reallocates its drawing
    // buffer, even to the size it has (and three.js sets both): a start set
    // it six times (the pixel ratio, the first fit, the resize observer's
    // first call at the same size), each a round trip to the GPU process.
    // The pixel ratio is read again, as it changes with the browser's zoom.
    // A view's first call always sets it: a renderer handed on by the pool
    // starts with its buffer cleared, not showing the last modeller's frame.
    const pixelRatio = Math.min(window.devicePixelRatio, 2);
    const bufferSize = `${width}x${height}@${pixelRatio}`;
    if (bufferSize !== this.#bufferSize) {
      this.#bufferSize = bufferSize;
      this.renderer.setDrawingBufferSize(width, height, pixelRatio);
    }
    this.canvas.style.width = '100%';
    this.canvas.style.height = '100%';
    this.camera.aspect = width / height;
    this.camera.updateProjectionMatrix();
    // A new viewport size (the Deform/Flatten switch halves or restores it, or
    // the window changes) re-fits the mesh, but only while the camera still
    // has the last fit's target and distance: orbiting alone keeps both (the
    // fit is a bounding sphere, the same from every side), so an orbited view
    // is re-fitted with its direction kept, while a view the user zoomed,
    // panned or focused into is theirs and stays as they left it.
    if (this.#lastFit && this.#stillFitted()) this.frame();
    this.requestRender();
  }

  /** Where frame() finds the mesh bounds {center, diagonal}. */
  setBoundsSource(source) {
    this.#boundsSource = source;
  }

  #stillFitted() {
    const { target, distance } = this.#lastFit;
    const tolerance = distance * 1e-6;
    return this.controls.target.distanceTo(target) <= tolerance
      && Math.abs(this.camera.position.distanceTo(this.controls.target) - distance) <= tolerance;
  }

  /**
   * Fits the camera to the whole mesh: its bounding sphere fills the narrower
   * of the two fields of view (so the canvas aspect counts), looking along the
   * current view direction, or the default one with {defaultDirection: true}
   * (a new mesh; `facing`: the side an open surface faces, looked at). The one fit of the page: load, Frame button, F / Home keys,
   * anisoform.frame() and the re-fit on resize.
   */
  frame({ defaultDirection = false, facing = null } = {}) {
    const bounds = this.#boundsSource();
    if (!bounds) return;
    const radius = Math.max(bounds.diagonal / 2, 1e-6);
    const halfVertical = (this.camera.fov * Math.PI) / 360;
    const halfHorizontal = Math.atan(Math.tan(halfVertical) * this.camera.aspect);
    const distance = (radius / Math.sin(Math.min(halfVertical, halfHorizontal))) * SPHERE_MARGIN;
    const direction = defaultDirection
      ? DEFAULT_VIEW_DIRECTION.clone()
      : this.camera.position.clone().sub(this.controls.target).normalize();
    if (direction.lengthSq() === 0) direction.copy(DEFAULT_VIEW_DIRECTION);
    // An open surface is first seen from the side it faces: the default
    // direction mirrored through the surface's mean plane when it is behind.
    if (defaultDirection && facing) {
      const normal = new Vector3(...facing);
      const behind = direction.dot(normal);
      if (behind < 0) direction.addScaledVector(normal, -2 * behind).normalize();
    }
    this.controls.target.fromArray(bounds.center);
    this.camera.position.copy(this.controls.target).addScaledVector(direction, distance);
    this.camera.near = distance / 100;
    this.camera.far = distance * 100;
    this.camera.updateProjectionMatrix();
    this.controls.update();
    this.#lastFit = { target: this.controls.target.clone(), distance };
    this.requestRender();
  }

  /** Moves the orbit target to `point` (xyz), keeping the view direction and distance. */
  focusOn(point) {
    const offset = this.camera.position.clone().sub(this.controls.target);
    this.controls.target.fromArray(point);
    this.camera.position.copy(this.controls.target).add(offset);
    this.controls.update();
    this.requestRender();
  }

  /** Where the camera is, to put it back later (setView): a reload keeps the view (view-autosave.js). */
  view() {
    return {
      position: this.camera.position.toArray(),
      target: this.controls.target.toArray(),
      up: this.camera.up.toArray(),
      zoom: this.camera.zoom,
      near: this.camera.near,
      far: this.camera.far,
    };
  }

  /**
   * Puts the camera where view() found it; false (nothing moved) when `view`
   * is not one: a camera on its target, an up of zero length or along the
   * line of sight, or near not before far draw nothing (a stored up of
   * [0, 0, 0] left the view empty without a word).
   */
  setView(view) {
    const isPoint = (value) => Array.isArray(value) && value.length === 3 && value.every(Number.isFinite);
    const positive = (value) => Number.isFinite(value) && value > 0;
    if (!view || ![view.position, view.target, view.up].every(isPoint) || ![view.zoom, view.near, view.far].every(positive)) return false;
    const sight = new Vector3().fromArray(view.target).sub(new Vector3().fromArray(view.position));
    const up = new Vector3().fromArray(view.up);
    const across = new Vector3().crossVectors(sight, up).length();
    if (!(sight.length() > 0) || !(across > 1e-9 * sight.length() * up.length()) || !(view.near < view.far)) return false;
    this.camera.position.fromArray(view.position);
    this.camera.up.fromArray(view.up);
    this.controls.target.fromArray(view.target);
    Object.assign(this.camera, { zoom: view.zoom, near: view.near, far: view.far });
    this.camera.updateProjectionMatrix();
    this.controls.update();
    this.requestRender();
    return true;
  }

  /** The camera as the solver needs it for screen drags (wasm/CONTRACT.md). */
  cameraState() {
    this.camera.updateMatrixWorld();
    return {
      view: Array.from(this.camera.matrixWorldInverse.elements),
      projection: Array.from(this.camera.projectionMatrix.elements),
      viewport: [0, 0, this.canvas.clientWidth, this.canvas.clientHeight],
    };
  }

  /**
   * A pointer's client position as a canvas pixel (CSS px, y down, as
   * clientWidth counts them): what picking, painting, toNdc and the brush
   * outline all take. Under CSS `zoom` on the page the client rect is
   * zoomed and clientWidth is not; the raw offset from the rect landed
   * picks and paint at twice the distance from the view's corner.
   */
  canvasPoint(clientX, clientY) {
    const rect = this.canvas.getBoundingClientRect();
    const scaleX = rect.width > 0 ? this.canvas.clientWidth / rect.width : 1;
    const scaleY = rect.height > 0 ? this.canvas.clientHeight / rect.height : 1;
    return { x: (clientX - rect.left) * scaleX, y: (clientY - rect.top) * scaleY };
  }

  /** Canvas pixel (CSS px, y down) to normalized device coordinates. */
  toNdc(x, y) {
    return { x: (x / this.canvas.clientWidth) * 2 - 1, y: -(y / this.canvas.clientHeight) * 2 + 1 };
  }
}
