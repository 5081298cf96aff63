// Live re-parameterisation: a slider being dragged calls setParameter with
// {preview: true}; the document and the snapshot cache stay as they are.
//
// On the LAST op, the worker's rest pose is put at that op's input and its
// region selected once; each slider value is then a warm-started
// one-iteration preview (no commit), at the solver's iteration rate, which
// settles while the slider rests (editor/settling.js).
// On an earlier op, each value replays the ops from it on, from its cached
// input, each as a cold live preview (the core's replay option `preview`: a
// few iterations); only the latest value waits while one replays.
// The release (setParameter without preview) re-runs the document from the
// op, as a replay would; anything else the stack runs first leaves the live
// state (leave), putting the document's last state back in the worker.
import { settleNext } from '../editor/settling.js';
import { Request } from '../worker/protocol.js';

export class LivePreview {
  #editor;
  #client;
  #runner;
  #run;
  #document;
  #live = null; // {opId, index, ready: Promise} (the last op), or {opId, index} (an earlier op)
  #waiting = null; // the latest value of an earlier op's slider: {opId, index, op, resolve, reject}
  #replaying = false;

  /**
   * run(work, {keepLive}): the stack's one-at-a-time runner; runner: its
   * OpRunner (restore, replay); document: () => the EditDocument.
   */
  constructor({ editor, client, runner, run, document }) {
    this.#editor = editor;
    this.#client = client;
    this.#runner = runner;
    this.#run = run;
    this.#document = document;
  }

  /** Whether the worker holds a live state (a slider's op input and region). */
  get active() {
    return this.#live !== null;
  }

  /**
   * Forgets the live state and the slider values not solved yet (a change, a
   * commit or an undo supersedes them); true when the worker held a live state.
   */
  leave() {
    const wasLive = this.#live !== null;
    this.#live = null;
    this.#client.dropQueuedPreview();
    this.#waiting?.resolve(null);
    this.#waiting = null;
    return wasLive;
  }

  /** Op `opId` (at `index`, enabled) shown with `op` in its place; resolves null when a newer value superseded it. */
  preview(opId, index, op) {
    return index === this.#document().ops.length - 1 ? this.#previewLast(opId, index, op) : this.#previewEarlier(opId, index, op);
  }

  async #previewLast(opId, index, op) {
    if (this.#live?.opId !== opId) {
      const live = { opId, index };
      this.#live = live;
      live.ready = this.#run(async () => {
        await this.#runner.restore(index, { show: false });
        await this.#client.request(Request.selectDocumentRegion, { document: this.#document().toJSON(), opId });
        this.#editor.selectionState.forget();
      }, { keepLive: true });
    }
    const live = this.#live;
    live.lastOp = op;
    live.changedAt = performance.now();
    await live.ready;
    // A warm-started preview (solver-client.js): the release solves in full.
    const result = await this.#client.preview({ ...op, warmStart: true }, this.#editor.heatMapKind);
    if (!result || this.#live !== live) return null;
    this.#showLast(result);
    this.#settleLast(live, op, null, result.stats);
    return { iterations: result.stats.iterations, ms: result.stats.ms };
  }

  #showLast(result) {
    this.#editor.emit('positions', { positions: result.positions, live: true, distortion: result.distortion });
    this.#editor.emit('stats', { ...result.stats, live: true });
  }

  // While the slider rests on the last op's value, the value goes on
  // iterating (settling.js), as a drag's does.
  #settleLast(live, op, previousEnergy, stats) {
    const current = () => this.#live === live && live.lastOp === op;
    settleNext({
      stats,
      previousEnergy,
      changedAt: live.changedAt,
      current,
      next: (iterations, energy) => {
        this.#client.preview({ ...op, warmStart: true }, this.#editor.heatMapKind, iterations).then((result) => {
          if (!result || !current()) return;
          this.#showLast(result);
          this.#settleLast(live, op, energy, result.stats);
        }, (error) => {
          if (current()) this.#editor.report(error, 'The live preview failed');
        });
      },
    });
  }

  #previewEarlier(opId, index, op) {
    this.#waiting?.resolve(null);
    return new Promise((resolve, reject) => {
      this.#waiting = { opId, index, op, resolve, reject };
      if (!this.#replaying) this.#replayWaiting();
    });
  }

  async #replayWaiting() {
    this.#replaying = true;
    while (this.#waiting) {
      const { opId, index, op, resolve, reject } = this.#waiting;
      this.#waiting = null;
      await this.#run(async () => {
        this.#live = { opId, index };
        await this.#runner.restore(index, { show: false });
        const json = this.#document().toJSON();
        json.ops[index].op = op;
        return this.#runner.replay(index, json.ops.length, { json, preview: true });
      }, { keepLive: this.#live?.opId === opId }).then((result) => {
        if (this.#live?.opId !== opId) return resolve(null);
        this.#editor.emit('positions', { positions: result.positions, live: true, distortion: result.distortion });
        return resolve({ replayed: result.summary.replayed });
      }, reject);
    }
    this.#replaying = false;
  }
}
