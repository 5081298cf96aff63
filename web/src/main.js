// The standalone site: one full modeller filling the page, with the bundled
// Spot mesh, keyboard shortcuts for the whole page, and its API as
// window.anisoform (for the page's users and the Playwright tests).
import { createModeller } from './embed/create-modeller.js';
import './site.css';

// Public domain "Spot" by Keenan Crane (see spot_README.txt beside it).
const DEFAULT_MESH = 'spot_triangulated.obj';

const modeller = createModeller(document.querySelector('.site-modeller'), {
  ui: 'full',
  mesh: DEFAULT_MESH,
  keyboard: 'page',
  autosave: true,
});
window.anisoform = modeller.api;
