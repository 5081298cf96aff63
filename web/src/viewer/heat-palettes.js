// The heat maps' palettes and ranges: the one place their colours live (the
// surface shader gets them as uniforms, the legend draws its bar from them,
// the 2D pattern view uses the compression palette) and where the value at
// full colour is chosen.
//
// Stretch and area change are both log2 ratios, so they get different
// palettes (blue / red against green / purple) to be told apart at a glance;
// the compression error has no sign and runs white - amber - red.

export const HEAT_PALETTES = {
  stretch: {
    title: 'Stretch (largest principal stretch)', oneSided: false,
    neutral: [235, 235, 230], shrunk: [36, 89, 217], grown: [217, 46, 31],
  },
  area: {
    title: 'Area change', oneSided: false,
    neutral: [235, 235, 230], shrunk: [26, 140, 77], grown: [140, 41, 158],
  },
  compression: {
    title: 'Compression error (flatten)', oneSided: true,
    neutral: [245, 245, 240], middle: [250, 190, 70], grown: [205, 35, 30],
  },
};

// Fixed ranges: the distortion maps saturate at twice / half (log2 = 1); the
// compression error at 10 %, a tolerance garment makers work to.
export const FIXED_HEAT_RANGE = { stretch: 1.0, area: 1.0, compression: 0.1 };

// Adaptive ranges saturate at the 95th percentile of |value|, so a patch that
// is everywhere far off still shows where it is worst; never below a floor,
// so that round-off on an unedited mesh does not light up (a 10 % change in
// log2 for the distortions, 2 % for the compression error).
export const ADAPTIVE_PERCENTILE = 0.95;
const ADAPTIVE_FLOOR = { stretch: Math.log2(1.1), area: Math.log2(1.1), compression: 0.02 };

/** The value shown at full colour: {value, adaptive}. `values`: what is drawn (log2 ratios or errors). */
export function heatRange(kind, values, mode) {
  if (mode !== 'adaptive') return { value: FIXED_HEAT_RANGE[kind], adaptive: false };
  const sizes = [];
  for (const value of values) if (Number.isFinite(value)) sizes.push(Math.abs(value));
  if (sizes.length === 0) return { value: ADAPTIVE_FLOOR[kind], adaptive: true };
  sizes.sort((a, b) => a - b);
  const percentile = sizes[Math.min(sizes.length - 1, Math.floor(ADAPTIVE_PERCENTILE * (sizes.length - 1)))];
  return { value: Math.max(percentile, ADAPTIVE_FLOOR[kind]), adaptive: true };
}

/** The palette's colour (rgb 0..255) at t in [-1, 1] (one-sided: [0, 1]), as the shader mixes it. */
export function paletteColor(palette, t) {
  const clamped = Math.min(Math.max(t, palette.oneSided ? 0 : -1), 1);
  if (palette.oneSided) {
    return clamped < 0.5
      ? mix(palette.neutral, palette.middle, 2 * clamped)
      : mix(palette.middle, palette.grown, 2 * clamped - 1);
  }
  // sqrt makes small distortions visible without saturating large ones.
  return mix(palette.neutral, clamped >= 0 ? palette.grown : palette.shrunk, Math.sqrt(Math.abs(clamped)));
}

function mix(a, b, f) {
  return a.map((value, k) => value + f * (b[k] - value));
}
