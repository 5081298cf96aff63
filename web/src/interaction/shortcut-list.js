// Every key of the modeller, in one list: the tool keys (chosen as in
// Blender where it has the same tool: S scale, R rotate), the brush radius
// keys ([ and ] as in Blender and SculptGL) and the rest. The key handlers
// (keyboard-shortcuts.js, editing-keys.js), the tool buttons' titles and the
// shortcut overlay (ui/shortcut-dialog.js) all read it from here.

/** Tool id → its key (event.key, lower case). */
export const TOOL_KEYS = {
  select: 'b',
  stretch: 's',
  thicken: 't',
  shear: 'h',
  rotate: 'r',
  twist: 'w',
  arrows: 'a',
};

/** [keys, what they do] for the overlay; the tools' rows come first, named by their labels. */
export function shortcutRows(tools) {
  const toolRows = [...tools.values()].map((tool) => [TOOL_KEYS[tool.id].toUpperCase(), `${tool.label} tool`]);
  return [
    ...toolRows,
    ['[ and ]', 'Brush radius smaller / larger'],
    ['C', 'Select the brush region (sphere or box) at the surface in the middle of the view'],
    ['Shift+C', 'The same, with the brush mode inverted (add ↔ subtract); taken away, the whole sphere or box, no soft edge'],
    ['F or Home', 'Frame the whole mesh'],
    ['Arrow keys', 'Pan the view (3D view focused); Shift+arrows orbit'],
    ['+ (or =) and −', 'Zoom the view in / out (3D view focused)'],
    ['Ctrl+O', 'Open a mesh, or saved edits (with their mesh)'],
    ['Ctrl+S', 'Save the edits as a file (.json)'],
    ['Delete', 'Delete the edit whose name has the focus in the Edits list'],
    ['Ctrl+Z', 'Undo'],
    ['Ctrl+Shift+Z or Ctrl+Y', 'Redo'],
    ['Esc', 'Cancel the drag or the solve in progress; close this list'],
    ['?', 'Show this list'],
  ];
}
