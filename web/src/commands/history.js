// Undo/redo history of edit commands (three.js editor style). A command has
// `label`, `undo()` and `redo()`; it is pushed after it has been applied,
// because edits are computed by the worker before they can be recorded.
// Loading a new mesh clears the history.
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
  }

  undo() {
    const command = this.#undoStack.pop();
    if (!command) return false;
    command.undo();
    this.#redoStack.push(command);
    this.emit('change', this.state());
    return true;
  }

  redo() {
    const command = this.#redoStack.pop();
    if (!command) return false;
    command.redo();
    this.#undoStack.push(command);
    this.emit('change', this.state());
    return true;
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
