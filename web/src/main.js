// The standalone site: one full modeller filling the page, with the bundled
// Spot mesh, keyboard shortcuts for the whole page, and its API as
// window.anisoform (for the page's users and the Playwright tests).
import { createModeller } from './embed/create-modeller.js';
import { createSolverPool } from './worker/solver-pool.js';
import './site.css';

// Public domain "Spot" by Keenan Crane (see spot_README.txt beside it).
const DEFAULT_MESH = 'spot_triangulated.obj';
// A stopped modeller's idle solver worker waits, warm, for the next start().
const solvers = createSolverPool();
const SITE_OPTIONS = Object.freeze({ ui: 'full', mesh: DEFAULT_MESH, keyboard: 'page', autosave: true, solvers });
const container = document.querySelector('.site-modeller');

let modeller = null;

/**
 * Ends the site's modeller, as leaving the page does (its solve and
 * listeners; an idle solver worker is kept for the next start(), for up to
 * a minute).
 */
function stop() {
  // Forgotten first: a dispose that throws still leaves the site free to start again.
  const ending = modeller;
  modeller = null;
  delete window.anisoform;
  ending?.dispose();
}

/** Starts the site's modeller afresh (ending the one before), as a reload does; resolves with its `ready`. */
function start() {
  stop();
  modeller = createModeller(container, SITE_OPTIONS);
  window.anisoform = modeller.api;
  return modeller.api.ready;
}

start();
// A new modeller without loading the page's code again: the end-to-end tests
// start most tests' app this way (0.25 s and 0.32 core-s with the kept
// worker, against 0.87 s and 1.45 core-s for a navigation: README, test command).
window.anisoformSite = Object.freeze({ start, stop });
