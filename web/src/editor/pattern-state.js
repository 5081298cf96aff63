// The garment pattern of the committed mesh: the last flattening (the
// worker's Session.flatten) and its export as SVG or DXF. The pattern is kept
// until the mesh, its positions or the flattened selection change.
import { Request } from '../worker/protocol.js';
import { badParameter } from '../shared/errors.js';
import { flattenInPageWords } from './edit-wording.js';

export class PatternState {
  /** The last flattening (FlattenPayload plus its options), or null. */
  pattern = null;
  #editor;
  #client;

  constructor({ editor, client }) {
    this.#editor = editor;
    this.#client = client;
  }

  /**
   * Flattens the committed mesh (or its selection); options as
   * Session.flatten (wasm/CONTRACT.md). The mesh and its history are untouched.
   */
  async flatten(options = {}) {
    const editor = this.#editor;
    const document = editor.requireDocument();
    if (editor.gestureActive || editor.busy) throw editor.report(badParameter('an edit is in progress'), 'Flatten');
    if (!options || typeof options !== 'object') throw editor.report(badParameter('options must be an object'), 'Flatten');
    if (options.patch === 'selection') {
      if (document.selectionCount === 0) {
        const error = badParameter('nothing is selected: paint the patch to flatten, or flatten the whole mesh');
        throw editor.report(error, 'Flatten');
      }
      editor.selectionState.syncForEdit();
    }
    const done = editor.beginBusy();
    try {
      const result = await this.#client.request(Request.flatten, { options });
      // Undo, redo and edits wait while this runs (busy); only a new mesh can
      // have arrived meanwhile.
      if (editor.document !== document) return result;
      this.pattern = { ...result, options: { patch: 'mesh', ...options } };
      editor.emit('pattern', this.pattern);
      // A patch that does not flatten as one piece says why and what to do
      // (flatten_problem, flatten.h), and where it needs a dart or a cut.
      const warning = flattenWarning(result.metrics);
      if (warning) editor.emit('warning', { message: warning, source: 'flatten' });
      return result;
    } catch (error) {
      throw editor.report(flattenInPageWords(error), 'Flatten failed');
    } finally {
      done();
      editor.emit('progress', { stage: 'done', message: '' });
    }
  }

  /**
   * The last flattening as an SVG or DXF file (bytes); options.mmPerUnit
   * defaults to the core's guess of the mesh's unit (info.unitGuess).
   */
  async export(format, options = {}) {
    try {
      if (!this.pattern) throw badParameter('there is no pattern: flatten the mesh first');
      const mmPerUnit = options.mmPerUnit ?? this.#editor.document?.info.unitGuess?.mmPerUnit ?? 1;
      const { bytes } = await this.#client.request(Request.exportPattern, { format, mmPerUnit });
      return bytes.buffer.slice(bytes.byteOffset, bytes.byteOffset + bytes.byteLength);
    } catch (error) {
      throw this.#editor.report(error, `Pattern export as ${String(format).toUpperCase()} failed`);
    }
  }

  /** The mesh or its positions changed: the pattern no longer applies. */
  drop() {
    if (!this.pattern) return;
    this.pattern = null;
    this.#editor.emit('pattern', null);
  }

  /** The selection changed: a pattern of the selected patch no longer applies. */
  selectionChanged() {
    if (this.pattern?.options.patch === 'selection') this.drop();
  }
}

/**
 * The banner for a flattening: metrics.problem (why it is not one piece),
 * metrics.warnings (shear, directions along the normal) and
 * metrics.suggestedCuts (the regions above the core's error threshold,
 * largest first), or null when there is nothing to say.
 */
export function flattenWarning(metrics) {
  const sentences = [];
  if (metrics.problem) sentences.push(`${metrics.problem}.`);
  // What a usable pattern still should say (flatten_warnings, flatten.h).
  // The core names the CLI's flag and the API's option; the page has a checkbox.
  const inPanelWords = (warning) => warning.replace('--no-refine or refine: false', 'Refine lengths off');
  for (const warning of (metrics.warnings ?? []).map(inPanelWords)) sentences.push(`${warning[0].toUpperCase()}${warning.slice(1)}.`);
  const cuts = metrics.suggestedCuts ?? [];
  if (cuts.length > 0) {
    const largest = cuts[0];
    const where = cuts.length === 1 ? 'one region misses' : `${cuts.length} regions miss`;
    sentences.push(`This patch needs a dart or a cut here: ${where} the wanted stretch by more than the fabric eases `
      + `(the largest, ${largest.vertices.length} vertices around vertex ${largest.vertex}, by ${Math.round(100 * largest.errorMean)} % on average; `
      + 'the heat map shows where).');
  }
  return sentences.length > 0 ? `Flatten: ${sentences.join(' ')}` : null;
}
