// The editor's settings: active tool, method, direction source, brush and
// the numeric amounts of every transform. Panels write them, tools read them;
// a drag writes its amount back so the numeric field shows the live value.
import { EventEmitter } from './event-emitter.js';

export function defaultSettings() {
  return {
    // 'deform' edits the mesh; 'flatten' makes a garment pattern of it (side by side with a 2D view).
    mode: 'deform',
    tool: 'select',
    // Iterations cap a committed AnARAP/ARAP solve; previews run a few, warm-started.
    solver: { method: 'anarap', iterations: 50 },
    direction: { source: 'screen', axis: 'x', custom: [1, 0, 0], curvature: 'max' },
    // Arrows placed on the surface: [{vertex, point, direction, su?, sv?}] (direction source
    // 'arrows'; su/sv: the arrow's own compression, flatten mode).
    arrows: [],
    // The last drag's screen direction, camera included, for "Apply" with the screen source.
    lastScreen: null,
    // region: the shape the C key selects at the view centre ('sphere' | 'box', the brush radius).
    brush: { radiusPercent: 8, softnessPercent: 50, mode: 'add', region: 'sphere' },
    stretch: { along: 1.5, across: 1 },
    thicken: { factor: 1.3 },
    shear: { amount: 0.5 },
    rotate: { axis: 'n', degrees: 30 },
    // Origin 'centroid': the core's default (the axis line through the selection's
    // weighted centroid); 'point': the axis line through `point` (typed, or a click on the mesh).
    twist: { axis: 'y', custom: [0, 1, 0], degreesPerUnit: 90, origin: 'centroid', point: [0, 0, 0] },
    // heatRange: 'adaptive' (95th percentile of the values shown) or 'fixed' (heat-palettes.js).
    // materials: a glTF mesh drawn with its own materials instead of the editing surface.
    display: {
      selection: true, glyphs: true, heatMap: 'off', heatRange: 'adaptive', flatShading: false, wireframe: false,
      materials: false,
    },
    // Flattening: the patch, the wanted stretch along / across the direction
    // (0.8 = 20 % shrinkage), the garment-CAD baseline, the pattern files' scale:
    // the mesh's unit ('guess': the core's guess from the mesh's size; m, cm, mm,
    // in; 'custom': mmPerUnit millimetres per unit).
    flatten: {
      patch: 'mesh', source: 'global', axis: 'auto', custom: [1, 0, 0],
      along: 0.8, across: 1, baseline: false, refine: true, unit: 'guess', mmPerUnit: 10, colorBy: 'compression',
    },
  };
}

export class Settings extends EventEmitter {
  // What a value of each setting may be: 'section' (a value of its own, as
  // the tool) or 'section.key' -> accept(value), the value kept (a number
  // clamped to its field's range) or undefined when it is refused. The
  // panels declare them where their fields are (ui/fields.js), so a value
  // typed in a field and one put back after a reload (restore) pass the same
  // rule; a setting no field edits has none, and is not put back.
  #rules = new Map();

  constructor(values = defaultSettings()) {
    super();
    this.values = values;
  }

  /** Declares the rule of a setting (key undefined: the section is one value); see #rules. */
  defineRule(section, key, accept) {
    this.#rules.set(key === undefined ? section : `${section}.${key}`, accept);
  }

  /** `value` as the rule of the setting keeps it, or undefined when refused (or when it has no rule). */
  accepted(section, key, value) {
    return this.#rules.get(key === undefined ? section : `${section}.${key}`)?.(value);
  }

  /** A plain copy of the values, to keep (a reload puts it back: restore). */
  snapshot() {
    return structuredClone(this.values);
  }

  /**
   * Puts back the values of a snapshot that their rules accept (the rest
   * stay as they are: a setting without a rule, one a newer build renamed,
   * a value out of its field's range is clamped as a typed one is), and
   * announces each section changed. The mode comes first, as the tool it
   * keeps goes with it (mode-switch.js).
   */
  restore(saved) {
    if (!isPlainObject(saved)) return;
    for (const section of Object.keys(this.values)) {
      if (!(section in saved)) continue;
      const current = this.values[section];
      if (!isPlainObject(current)) {
        const value = this.accepted(section, undefined, saved[section]);
        if (value !== undefined && value !== current) this.update(section, value);
        continue;
      }
      if (!isPlainObject(saved[section])) continue;
      const patch = {};
      for (const key of Object.keys(current)) {
        const value = key in saved[section] ? this.accepted(section, key, saved[section][key]) : undefined;
        if (value !== undefined) patch[key] = value;
      }
      if (Object.keys(patch).length > 0) this.update(section, patch);
    }
  }

  /** Merges `partial` into a section (or sets a top-level value) and announces it. */
  update(section, partial) {
    const current = this.values[section];
    this.values[section] = isPlainObject(current) && isPlainObject(partial)
      ? { ...current, ...partial }
      : partial;
    this.emit('change', { section });
  }

  /**
   * Puts back what only meant something on the mesh it was made on: the
   * arrows (vertex indices), the last screen drag (its anchor point), a twist
   * origin point and the heat map of the flattening. The editor runs this at
   * every load (Editor.bindToMesh); typed amounts and choices stay, but for
   * the twist rate, in degrees per unit of the mesh, which the twist tool
   * sets again for each mesh loaded.
   */
  resetMeshBound() {
    const defaults = defaultSettings();
    if (this.values.arrows.length > 0) this.update('arrows', defaults.arrows);
    if (this.values.lastScreen !== null) this.update('lastScreen', defaults.lastScreen);
    if (this.values.twist.origin === 'point') {
      this.update('twist', { origin: defaults.twist.origin, point: defaults.twist.point });
    }
    if (this.values.display.heatMap === 'compression') this.update('display', { heatMap: defaults.display.heatMap });
  }
}

function isPlainObject(value) {
  return Boolean(value) && typeof value === 'object' && !Array.isArray(value);
}

const AXES = { x: [1, 0, 0], y: [0, 1, 0], z: [0, 0, 1] };

/** A unit vector for an axis setting: 'x' | 'y' | 'z' | 'custom' (then `custom`). */
export function axisVector(axis, custom) {
  return AXES[axis] ?? custom;
}
