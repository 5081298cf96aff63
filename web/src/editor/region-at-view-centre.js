// Selecting without painting (the C key, the Select tool's button): the
// brush's region (a sphere, or an axis-aligned cube, of the brush radius,
// with its soft edge) centred on the surface point in the middle of the 3D view, or on the orbit
// target when no surface is there. It is added or subtracted as the brush
// mode says (Shift inverts it, as for a stroke); the core's select rule does
// the selecting, as one undo step. Subtracted, it is the whole ball or cube
// with no soft edge, so that Shift+C takes away all that C put there: the
// core's subtract, min(old, 1 - new), keeps a weight of at most one half
// where the region's own is as low (a ring of 32 of C's 50 vertices was left).

/** @returns {Promise<number>|null} the number of selected vertices; null without a mesh */
export function selectRegionAtViewCentre({ api, editor, viewer, picker, settings }, { invert = false } = {}) {
  const document = editor.document;
  if (!document) return null;
  const canvas = viewer.canvas;
  const hit = picker.pick(canvas.clientWidth / 2, canvas.clientHeight / 2);
  const center = hit ? hit.point : viewer.controls.target.toArray();
  const { radiusPercent, softnessPercent, mode, region } = settings.values.brush;
  const radius = (radiusPercent / 100) * document.bounds().diagonal;
  // The brush's soft edge, as a dab has it: full weight out to
  // radius x (1 - softness), fading to none at the radius (the core's falloff
  // runs outside its region). It used to be ignored here.
  const subtract = (mode === 'subtract') !== invert;
  const soft = subtract ? 0 : radius * (softnessPercent / 100);
  const hard = radius - soft;
  const shape = region === 'box'
    ? { box: { min: center.map((value) => value - hard), max: center.map((value) => value + hard) } }
    : { sphere: { center, radius: hard } };
  const before = document.selection;
  return api.select(shape, { mode: subtract ? 'subtract' : 'add', falloff: soft }).then((count) => {
    // Nothing there (the orbit target in the air): said, not a silent no-op.
    if (!hit && editor.document === document && document.selection === before) {
      editor.emit('notice', {
        message: 'Nothing to select at the view centre: no surface lies there or within the brush radius. '
          + 'Move the mesh under the centre (F frames it) or paint on it.',
        source: 'select',
      });
    }
    return count;
  });
}
