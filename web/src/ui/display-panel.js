// What the viewport shows besides the surface.
import { section } from './dom.js';
import { checkboxField, selectField } from './fields.js';

export function displayPanel({ settings }) {
  return section(
    'Display',
    checkboxField(settings, 'display', { key: 'selection', label: 'Selection weights' }),
    checkboxField(settings, 'display', { key: 'glyphs', label: 'Direction glyphs' }),
    selectField(settings, 'display', {
      key: 'heatMap',
      label: 'Heat map',
      options: [
        ['off', 'Off'],
        ['area', 'Area change'],
        ['stretch', 'Stretch'],
        ['compression', 'Compression error (flatten)'],
      ],
    }),
    selectField(settings, 'display', {
      key: 'heatRange',
      label: 'Heat range',
      options: [['adaptive', 'Adapted to the data'], ['fixed', 'Fixed (×2 / 10 %)']],
    }),
    checkboxField(settings, 'display', { key: 'flatShading', label: 'Flat shading' }),
    checkboxField(settings, 'display', { key: 'wireframe', label: 'Wireframe' }),
    // The file's look: its materials, textures and vertex colours, in the
    // edited shape (the selection and heat maps are then not drawn).
    checkboxField(settings, 'display', { key: 'materials', label: "File's materials (glTF)" }),
  );
}
