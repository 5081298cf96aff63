// Undo/redo history of edit commands (three.js editor style). A command has
// `label`, `undo()` and `redo()`; it is pushed after it has been applied,
// because edits are computed by the worker before they can be recorded.
// Loading a new mesh clears the history.
import { EventEmitter } from '../shared/event-emitter.js';

// Each step may hold two position arrays (2.4 MB each at 200k vertices);
// 100 steps keep the worst case near half a gigabyte.
const MAX_STEPS = 100;

export class History extends EventEmitter {
  #undoStack = [];
  #redoStack = [];

  push(command) {
    this.#undoStack.push(command);
    if (this.#undoStack.length > MAX_STEPS) this.#undoStack.shift();
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
