// Undo/redo history of edit commands (three.js editor style). A command has
// `label`, `undo()` and `redo()`; it is pushed after it has been applied,
// because edits are computed by the worker before they can be recorded.
// Loading a new mesh clears the history. 'step' says what was done, undone
// or redone ({action, label, announce}) once the command's work has ended
// (an undone deletion re-runs the later edits first): a screen reader was
// told nothing of an undo or a deletion (ui/announcer.js).
import { EventEmitter } from '../shared/event-emitter.js';

// Edits are ops of the edit document (document/op-stack.js), whose commands
// hold no arrays; selection steps hold two weight arrays each. The history is
// bounded by the bytes its commands hold (`bytes`), not by a step count: the
// oldest steps go first beyond this budget.
const BUDGET_BYTES = 64 * 1024 * 1024;

export class History extends EventEmitter {
  #undoStack = [];
  #redoStack = [];

  push(command) {
    this.#undoStack.push(command);
    const bytesOf = (c) => c.bytes ?? 0;
    let total = this.#undoStack.reduce((sum, c) => sum + bytesOf(c), 0);
    while (total > BUDGET_BYTES && this.#undoStack.length > 1) total -= bytesOf(this.#undoStack.shift());
    this.#redoStack.length = 0;
    this.emit('change', this.state());
    this.emit('step', { action: 'done', label: command.label, announce: command.announce === true });
  }

  undo() {
    const command = this.#undoStack.pop();
    if (!command) return false;
    const work = command.undo();
    this.#redoStack.push(command);
    this.emit('change', this.state());
    this.#stepAfter(work, 'undone', command);
    return true;
  }

  redo() {
    const command = this.#redoStack.pop();
    if (!command) return false;
    const work = command.redo();
    this.#undoStack.push(command);
    this.emit('change', this.state());
    this.#stepAfter(work, 'redone', command);
    return true;
  }

  // A failure is reported by the command itself (op-stack.js): the step is
  // said all the same, as the history now holds it.
  #stepAfter(work, action, command) {
    const say = () => this.emit('step', { action, label: command.label, announce: true });
    Promise.resolve(work).then(say, say);
  }

  clear() {
    this.#undoStack.length = 0;
    this.#redoStack.length = 0;
    this.emit('change', this.state());
  }

  state() {
    return {
      canUndo: this.#undoStack.length > 0,
      canRedo: this.#redoStack.length > 0,
      undoLabel: this.#undoStack.at(-1)?.label ?? null,
      redoLabel: this.#redoStack.at(-1)?.label ?? null,
    };
  }
}
