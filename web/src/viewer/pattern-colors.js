// Colours of the compression-error maps of the 2D pattern view: white at no
// error, through amber to red at `range` and beyond (an error is a size,
// |achieved / wanted - 1|, so the scale is one-sided): the compression
// palette of heat-palettes.js, as the 3D heat map and its legend draw it.
// NaN (a degenerate triangle, nothing to measure) is grey.
import { HEAT_PALETTES, paletteColor } from './heat-palettes.js';

export function heatColor(error, range) {
  if (!Number.isFinite(error)) return 'rgb(150,150,150)';
  return rgb(paletteColor(HEAT_PALETTES.compression, error / range));
}

export function rgb([r, g, b]) {
  return `rgb(${Math.round(r)},${Math.round(g)},${Math.round(b)})`;
}
