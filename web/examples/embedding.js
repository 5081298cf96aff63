// Two modellers on one page through the anisoform package: the spool with no
// panel, Spot with the full UI. Each "Dispose" button ends one of them
// (worker, pending frame, observers, listeners). window.anisoformExample holds
// both, createModeller, createSolverPool and defineModellerElement, for the console and the
// end-to-end tests.
import { createModeller, createSolverPool, defineModellerElement } from 'anisoform';
import 'anisoform/style.css';

const modellers = {
  spool: createModeller(document.querySelector('[data-testid=host-spool]'), { ui: 'none', mesh: '../spool.off' }),
  spot: createModeller(document.querySelector('[data-testid=host-spot]'), { ui: 'full', mesh: '../spot_triangulated.obj' }),
};
for (const button of document.querySelectorAll('[data-dispose]')) {
  button.addEventListener('click', () => {
    modellers[button.dataset.dispose].dispose();
    button.disabled = true;
  });
}
window.anisoformExample = { createModeller, createSolverPool, defineModellerElement, modellers };
