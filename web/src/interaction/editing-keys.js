// The full UI's editing keys (the list: shortcut-list.js): a key per tool,
// [ and ] for the brush radius, C / Shift+C to select the brush region at
// the view centre, ? for the shortcut overlay. Like keyboard-shortcuts.js
// they are ignored while typing in a field or with Ctrl/Cmd/Alt held (but
// for a [ or ] typed with AltGr or Option, as German, French and Nordic
// layouts type them; AltGr reaches the page as Ctrl+Alt on Windows), and
// none acts while the overlay is open. Ctrl/Cmd+O and Ctrl/Cmd+S are the
// Mesh panel's Open… and Save edits, in a field too, instead of the
// browser's own (open a page, save the page).
import { FLATTEN_MODE_TOOLS } from '../tools/tool-registry.js';
import { isTyping } from './keyboard-shortcuts.js';
import { TOOL_KEYS } from './shortcut-list.js';

// Each [ or ] press scales the radius by this; the field's limits and step.
const RADIUS_FACTOR = 1.25;
const RADIUS_MIN = 0.5;
const RADIUS_MAX = 100;

// toolChosen(id): a tool chosen by its key is said (a screen reader heard
// nothing: the key moves no focus to the tool's button).
export function installEditingKeys(target, lifetime, { settings, dialog, selectRegion, files, toolChosen }) {
  const toolOfKey = new Map(Object.entries(TOOL_KEYS).map(([id, key]) => [key, id]));
  const fileActions = { o: files.open, s: files.save };
  lifetime.listen(target, 'keydown', (event) => {
    // A dialog's keys are its own (the replace dialog's buttons, Esc).
    if (event.target instanceof Element && event.target.closest('dialog[open]')) return;
    const fileAction = fileActions[event.key.toLowerCase()];
    if (!dialog.open && fileAction && (event.ctrlKey || event.metaKey) && !event.altKey && !event.shiftKey) {
      event.preventDefault();
      fileAction();
      return;
    }
    if (dialog.open || isTyping(event) || event.metaKey) return;
    const bracket = event.key === '[' || event.key === ']';
    const printedWithAltGr = bracket && (event.getModifierState('AltGraph') || event.altKey);
    if (!printedWithAltGr && (event.ctrlKey || event.altKey)) return;
    const key = event.key.toLowerCase();
    const tool = toolOfKey.get(key);
    if (event.key === '?') {
      dialog.showModal();
    } else if (tool && !event.shiftKey) {
      if (settings.values.mode === 'flatten' && !FLATTEN_MODE_TOOLS.includes(tool)) return;
      settings.update('tool', tool);
      toolChosen(tool);
    } else if (bracket) {
      const radius = settings.values.brush.radiusPercent * (event.key === ']' ? RADIUS_FACTOR : 1 / RADIUS_FACTOR);
      const rounded = Math.round(radius * 2) / 2;
      settings.update('brush', { radiusPercent: Math.min(Math.max(rounded, RADIUS_MIN), RADIUS_MAX) });
    } else if (key === 'c') {
      selectRegion({ invert: event.shiftKey });
    } else {
      return;
    }
    event.preventDefault();
  });
}
