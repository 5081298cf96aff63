// The 2D pattern view beside the 3D one: every flattened triangle filled by
// its compression error (how far the achieved stretch along the wanted
// direction is from the wanted one), the piece outlines, a grainline arrow per
// piece and a colour legend. Wheel zooms about the pointer, drag pans,
// double-click fits; hovering a triangle reads out its errors.
//
// Drawn with Canvas 2D rather than WebGL: a pattern is flat and static, at
// most some 100k triangles, and the canvas needs no second GL context beside
// the 3D view's (SwiftShader runs them on the CPU).
import { heatColor } from './pattern-colors.js';
import { formatPercent } from '../shared/number-format.js';

const PADDING_PX = 24;
// The colour legend (#drawLegend): its bar's top this far above the bottom
// edge, its label's baseline that far above the bar, in type of that size.
const LEGEND_BAR_PX = 22;
const LEGEND_LABEL_GAP_PX = 4;
const LEGEND_FONT_PX = 11;
// The legend's height from the bottom edge (its label's top), which Fit keeps
// the pattern above.
const LEGEND_PX = LEGEND_BAR_PX + LEGEND_LABEL_GAP_PX + LEGEND_FONT_PX + 1;

export class PatternView {
  #pattern = null;
  #colorBy = 'compression';
  #range = 0.1;
  #view = { scale: 1, x: 0, y: 0 };
  #hovered = -1;
  #drag = null;

  /**
   * @param {HTMLElement} container  receives the canvas and the readout
   * @param {import('../embed/lifetime.js').Lifetime} lifetime
   */
  constructor(container, lifetime) {
    this.container = container;
    this.canvas = document.createElement('canvas');
    this.canvas.className = 'pattern-canvas';
    this.canvas.dataset.testid = 'pattern-canvas';
    this.canvas.setAttribute('aria-label', 'Flattened pattern: colour shows the compression error');
    this.readout = document.createElement('div');
    this.readout.className = 'pattern-readout';
    this.readout.dataset.testid = 'pattern-readout';
    container.append(this.canvas, this.readout);
    const resizeObserver = new ResizeObserver(() => this.#resize());
    resizeObserver.observe(container);
    lifetime.defer(() => resizeObserver.disconnect());
    lifetime.listen(this.canvas, 'wheel', (event) => this.#zoom(event), { passive: false });
    lifetime.listen(this.canvas, 'pointerdown', (event) => this.#startPan(event));
    lifetime.listen(this.canvas, 'pointermove', (event) => this.#pointerMove(event));
    lifetime.listen(this.canvas, 'pointerup', () => (this.#drag = null));
    lifetime.listen(this.canvas, 'dblclick', () => this.fit());
    this.#resize();
  }

  /**
   * @param {object|null} pattern  the editor's pattern (FlattenPayload), or null to clear
   * @param {[string, number]} [coloring]  its colouring, as setColoring takes it (default: the current
   *   one): set with the pattern, so that a new pattern is drawn once
   */
  show(pattern, [colorBy, range] = [this.#colorBy, this.#range]) {
    this.#colorBy = colorBy;
    this.#range = range;
    this.#pattern = pattern;
    this.#hovered = -1;
    this.fit();
  }

  /** 'compression' (along the wanted direction) or 'cross' (across it); range = error at full colour. */
  setColoring(colorBy, range) {
    this.#colorBy = colorBy;
    this.#range = range;
    this.draw();
  }

  fit() {
    const pattern = this.#pattern;
    const { width, height } = this.#size();
    if (!pattern) {
      this.draw();
      return;
    }
    const [minU, minV, maxU, maxV] = uvBounds(pattern.uv, pattern.triangles);
    const spanU = Math.max(maxU - minU, 1e-12), spanV = Math.max(maxV - minV, 1e-12);
    // Between the summary over the top (one or two lines, as wide as the
    // pane) and the legend at the bottom: fitted to the whole height, a tall
    // pattern ran under both (the koala's head).
    if (this.#hovered < 0) this.readout.textContent = summary(pattern.metrics);
    const top = Math.max(PADDING_PX, this.readout.offsetTop + this.readout.offsetHeight + PADDING_PX / 2);
    const bottom = LEGEND_PX + PADDING_PX / 2;
    const scale = Math.min((width - 2 * PADDING_PX) / spanU, Math.max(1, height - top - bottom) / spanV);
    // v up on screen, as in the SVG/DXF files.
    this.#view = {
      scale,
      x: width / 2 - scale * (minU + maxU) / 2,
      y: top + (height - top - bottom) / 2 + scale * (minV + maxV) / 2,
    };
    this.draw();
  }

  draw() {
    const context = this.canvas.getContext('2d');
    const ratio = this.canvas.width / Math.max(1, this.#size().width);
    context.setTransform(ratio, 0, 0, ratio, 0, 0);
    context.clearRect(0, 0, this.canvas.width, this.canvas.height);
    const pattern = this.#pattern;
    if (!pattern) {
      this.readout.textContent = 'Flatten an open mesh or a selection to see its pattern here.';
      return;
    }
    this.#drawTriangles(context, pattern);
    this.#drawOutlines(context, pattern);
    this.#drawGrainlines(context, pattern);
    this.#drawLegend(context);
    if (this.#hovered < 0) this.readout.textContent = summary(pattern.metrics);
  }

  // One path per colour, filled and then stroked once: a fill and a stroke
  // per triangle were 96k calls of each for the koala's head (48k vertices),
  // which held the page's thread for most of a minute after the flattening.
  #drawTriangles(context, pattern) {
    const { uv, triangles } = pattern;
    const errors = this.#colorBy === 'cross' ? pattern.crossError : pattern.compressionError;
    const byColor = new Map();
    for (let t = 0; t < errors.length; t++) {
      const color = heatColor(errors[t], this.#range);
      const list = byColor.get(color);
      if (list) list.push(t);
      else byColor.set(color, [t]);
    }
    // A hairline in the fill's own colour closes the antialiasing seams between triangles.
    context.lineWidth = 0.5;
    for (const [color, list] of byColor) {
      context.beginPath();
      for (const t of list) this.#tracePath(context, uv, triangles, t);
      context.fillStyle = color;
      context.fill();
      context.strokeStyle = color;
      context.stroke();
    }
    if (this.#hovered >= 0 && this.#hovered < errors.length) {
      context.beginPath();
      this.#tracePath(context, uv, triangles, this.#hovered);
      context.strokeStyle = '#000';
      context.lineWidth = 1.5;
      context.stroke();
    }
  }

  #tracePath(context, uv, triangles, t) {
    context.moveTo(...this.#toScreen(uv, triangles[3 * t]));
    context.lineTo(...this.#toScreen(uv, triangles[3 * t + 1]));
    context.lineTo(...this.#toScreen(uv, triangles[3 * t + 2]));
    context.closePath();
  }

  #drawOutlines(context, pattern) {
    context.strokeStyle = '#111';
    context.lineWidth = 1.5;
    for (const loop of pattern.outlines) {
      context.beginPath();
      loop.forEach((vertex, index) => {
        const [x, y] = this.#toScreen(pattern.uv, vertex);
        if (index === 0) context.moveTo(x, y);
        else context.lineTo(x, y);
      });
      context.closePath();
      context.stroke();
    }
  }

  // Per piece, an arrow through the centre of its outline's bounding box
  // along the grainline (the mean wanted direction in the plane).
  #drawGrainlines(context, pattern) {
    const pieces = pieceBounds(pattern);
    context.strokeStyle = '#1d4ed8';
    context.fillStyle = '#1d4ed8';
    context.lineWidth = 2;
    pattern.grainlines.forEach(([gu, gv], piece) => {
      const box = pieces[piece];
      if (!box) return;
      const half = 0.3 * Math.min(box.maxU - box.minU, box.maxV - box.minV, Math.max(box.maxU - box.minU, box.maxV - box.minV));
      const cu = (box.minU + box.maxU) / 2, cv = (box.minV + box.maxV) / 2;
      const from = this.#project(cu - half * gu, cv - half * gv);
      const to = this.#project(cu + half * gu, cv + half * gv);
      context.beginPath();
      context.moveTo(...from);
      context.lineTo(...to);
      context.stroke();
      const angle = Math.atan2(to[1] - from[1], to[0] - from[0]);
      for (const end of [to, from]) {
        const direction = end === to ? angle : angle + Math.PI;
        context.beginPath();
        context.moveTo(...end);
        context.lineTo(end[0] - 9 * Math.cos(direction - 0.45), end[1] - 9 * Math.sin(direction - 0.45));
        context.lineTo(end[0] - 9 * Math.cos(direction + 0.45), end[1] - 9 * Math.sin(direction + 0.45));
        context.closePath();
        context.fill();
      }
    });
  }

  #drawLegend(context) {
    const { height } = this.#size();
    const x = 12, y = height - LEGEND_BAR_PX, width = 120;
    for (let i = 0; i < width; i++) {
      context.fillStyle = heatColor((i / (width - 1)) * this.#range, this.#range);
      context.fillRect(x + i, y, 1, 8);
    }
    context.fillStyle = '#e6e8eb';
    context.font = `${LEGEND_FONT_PX}px system-ui, sans-serif`;
    context.fillText('0 %', x, y - LEGEND_LABEL_GAP_PX);
    const label = `${this.#colorBy === 'cross' ? 'cross' : 'compression'} error ≥ ${formatPercent(this.#range)}`;
    context.fillText(label, x + width - context.measureText(label).width / 2, y - LEGEND_LABEL_GAP_PX);
  }

  #toScreen(uv, vertex) {
    return this.#project(uv[2 * vertex], uv[2 * vertex + 1]);
  }

  #project(u, v) {
    return [this.#view.x + this.#view.scale * u, this.#view.y - this.#view.scale * v];
  }

  #unproject(x, y) {
    return [(x - this.#view.x) / this.#view.scale, (this.#view.y - y) / this.#view.scale];
  }

  #zoom(event) {
    if (!this.#pattern) return;
    event.preventDefault();
    const factor = Math.exp(-event.deltaY * 0.0015);
    const { offsetX: x, offsetY: y } = event;
    this.#view.x = x - (x - this.#view.x) * factor;
    this.#view.y = y - (y - this.#view.y) * factor;
    this.#view.scale *= factor;
    this.draw();
  }

  #startPan(event) {
    this.#drag = { x: event.clientX, y: event.clientY };
    this.canvas.setPointerCapture(event.pointerId);
  }

  #pointerMove(event) {
    if (this.#drag) {
      this.#view.x += event.clientX - this.#drag.x;
      this.#view.y += event.clientY - this.#drag.y;
      this.#drag = { x: event.clientX, y: event.clientY };
      this.draw();
      return;
    }
    const pattern = this.#pattern;
    if (!pattern) return;
    const triangle = triangleAt(pattern, ...this.#unproject(event.offsetX, event.offsetY));
    if (triangle === this.#hovered) return;
    this.#hovered = triangle;
    this.readout.textContent = triangle < 0 ? summary(pattern.metrics)
      : `Triangle ${triangle}: compression error ${formatPercent(pattern.compressionError[triangle])}, ` +
        `cross error ${formatPercent(pattern.crossError[triangle])}`;
    this.draw();
  }

  #size() {
    return { width: Math.max(1, this.container.clientWidth), height: Math.max(1, this.container.clientHeight) };
  }

  #resize() {
    const ratio = Math.min(window.devicePixelRatio || 1, 2);
    const { width, height } = this.#size();
    this.canvas.width = Math.round(width * ratio);
    this.canvas.height = Math.round(height * ratio);
    this.fit();
  }
}


function summary(metrics) {
  return `Compression error: mean ${formatPercent(metrics.compressionErrorMean)}, ` +
    `max ${formatPercent(metrics.compressionErrorMax)} · cross error mean ${formatPercent(metrics.crossErrorMean)}, ` +
    `max ${formatPercent(metrics.crossErrorMax)} · area off ${formatPercent(metrics.areaDistortionMean)} · ` +
    `${metrics.flipped} flipped`;
}

function uvBounds(uv, triangles) {
  let minU = Infinity, minV = Infinity, maxU = -Infinity, maxV = -Infinity;
  for (const vertex of triangles) {
    const u = uv[2 * vertex], v = uv[2 * vertex + 1];
    if (u < minU) minU = u;
    if (u > maxU) maxU = u;
    if (v < minV) minV = v;
    if (v > maxV) maxV = v;
  }
  return [minU, minV, maxU, maxV];
}

// The bounding box of each piece: the union of its outlines' boxes
// (outlinePieces names each outline's piece, the index of its grainline).
function pieceBounds(pattern) {
  const boxes = pattern.grainlines.map(() => ({ minU: Infinity, minV: Infinity, maxU: -Infinity, maxV: -Infinity }));
  pattern.outlines.forEach((loop, index) => {
    const box = boxes[pattern.outlinePieces[index]];
    if (!box) return;
    for (const vertex of loop) {
      const u = pattern.uv[2 * vertex], v = pattern.uv[2 * vertex + 1];
      box.minU = Math.min(box.minU, u);
      box.maxU = Math.max(box.maxU, u);
      box.minV = Math.min(box.minV, v);
      box.maxV = Math.max(box.maxV, v);
    }
  });
  return boxes.map((box) => (Number.isFinite(box.minU) ? box : null));
}

function triangleAt({ uv, triangles }, u, v) {
  for (let t = 0; t < triangles.length / 3; t++) {
    const a = triangles[3 * t], b = triangles[3 * t + 1], c = triangles[3 * t + 2];
    const d1 = side(uv, a, b, u, v), d2 = side(uv, b, c, u, v), d3 = side(uv, c, a, u, v);
    const hasNegative = d1 < 0 || d2 < 0 || d3 < 0;
    const hasPositive = d1 > 0 || d2 > 0 || d3 > 0;
    if (!(hasNegative && hasPositive)) return t;
  }
  return -1;
}

function side(uv, i, j, u, v) {
  return (uv[2 * j] - uv[2 * i]) * (v - uv[2 * i + 1]) - (uv[2 * j + 1] - uv[2 * i + 1]) * (u - uv[2 * i]);
}
