// The 3D heat map's legend, over the viewport's bottom right corner (above the
// Frame button, clear of the messages at the top): the
// quantity's name, a colour bar drawn from the same palette as the surface,
// the values at its ends and middle, and whether the range is fixed or
// adapted to the data. Styled inline: an embedded viewer has no stylesheet.
import { ADAPTIVE_PERCENTILE, paletteColor } from './heat-palettes.js';
import { rgb } from './pattern-colors.js';

const BAR_STOPS = 9;
// Views shorter than this show the legend beside the Frame button, without its range line.
const SHORT_VIEW_PX = 360;

export class HeatmapLegend {
  constructor(viewport, lifetime) {
    const text = (testId) => {
      const span = document.createElement('span');
      span.dataset.testid = testId;
      return span;
    };
    this.title = text('heatmap-legend-title');
    this.bar = document.createElement('div');
    Object.assign(this.bar.style, { height: '10px', borderRadius: '2px', margin: '4px 0 2px' });
    this.ends = document.createElement('div');
    this.ends.dataset.testid = 'heatmap-legend-values';
    Object.assign(this.ends.style, { display: 'flex', justifyContent: 'space-between', gap: '8px' });
    this.range = text('heatmap-legend-range');
    this.element = document.createElement('div');
    this.element.dataset.testid = 'heatmap-legend';
    this.element.setAttribute('role', 'img');
    Object.assign(this.element.style, {
      position: 'absolute', width: '200px', padding: '6px 8px',
      background: '#111419e6', color: '#e6e8eb', font: '12px system-ui, sans-serif', borderRadius: '4px',
      display: 'flex', flexDirection: 'column', pointerEvents: 'none',
    });
    this.element.append(this.title, this.bar, this.ends, this.range);
    this.viewport = viewport;
    viewport.append(this.element);
    // Placed again when the view's height changes (#place).
    this.resized = new ResizeObserver(() => {
      if (!this.element.hidden) this.setShown(true);
    });
    this.resized.observe(viewport);
    lifetime.defer(() => this.resized.disconnect());
    this.hide();
  }

  /** Goes over another viewport (a new layout of the same modeller: viewer.moveTo). */
  moveTo(viewport) {
    this.resized.unobserve(this.viewport);
    this.viewport.style.removeProperty('--legend-space');
    this.viewport = viewport;
    viewport.append(this.element);
    this.resized.observe(viewport);
    if (!this.element.hidden) this.setShown(true);
  }

  /**
   * @param {object} palette  of heat-palettes.js
   * @param {{value: number, adaptive: boolean}} range  the value at full colour
   * @param {(value: number) => string} format  a shown value (log2 ratio or error) as text
   */
  show(palette, range, format) {
    const low = palette.oneSided ? 0 : -1;
    const stops = [];
    for (let i = 0; i < BAR_STOPS; i++) {
      const t = low + ((1 - low) * i) / (BAR_STOPS - 1);
      stops.push(`${rgb(paletteColor(palette, t))} ${((100 * i) / (BAR_STOPS - 1)).toFixed(1)}%`);
    }
    this.bar.style.display = '';
    this.bar.style.background = `linear-gradient(to right, ${stops.join(', ')})`;
    this.title.textContent = palette.title;
    const values = palette.oneSided ? [0, range.value / 2, range.value] : [-range.value, 0, range.value];
    this.ends.replaceChildren(...values.map((value) => Object.assign(document.createElement('span'), { textContent: format(value) })));
    this.range.textContent = range.adaptive
      ? `Range adapted to the data (${Math.round(100 * ADAPTIVE_PERCENTILE)}th percentile)`
      : 'Fixed range';
    this.element.setAttribute('aria-label', `${palette.title}: ${values.map(format).join(' to ')}; ${this.range.textContent}`);
    this.setShown(true);
  }

  /** The quantity's name and why there are no values to show (no colour bar: nothing is coloured). */
  showNothing(palette, why) {
    this.title.textContent = palette.title;
    this.bar.style.display = 'none';
    this.ends.replaceChildren();
    this.range.textContent = why;
    this.element.setAttribute('aria-label', `${palette.title}: ${why}`);
    this.setShown(true);
  }

  hide() {
    this.setShown(false);
  }

  // `hidden` alone would not hide it where no stylesheet says [hidden] is
  // display: none (an embedder's page): the inline display wins. The space
  // it takes from the bottom goes to --legend-space on the viewport, which
  // the messages at the top keep clear of (on a phone the view is short
  // and a long warning reached down over the legend's title).
  setShown(shown) {
    this.element.hidden = !shown;
    this.element.style.display = shown ? 'flex' : 'none';
    if (shown) this.#place();
    const space = shown ? this.viewport.clientHeight - this.element.offsetTop + 6 : 0;
    this.viewport.style.setProperty('--legend-space', `${space}px`);
  }

  // Above the full UI's Frame button in a tall view; in a short one (a
  // phone's Flatten view, 240 px) beside it and without the range's line,
  // so that a message at the top keeps the room for its first lines and More.
  #place() {
    const frame = this.viewport.querySelector('.viewport-frame');
    const short = this.viewport.clientHeight < SHORT_VIEW_PX;
    this.range.style.display = short ? 'none' : '';
    this.element.style.bottom = frame && !short ? '52px' : '10px';
    this.element.style.right = frame && short ? `${18 + frame.offsetWidth}px` : '10px';
  }
}
