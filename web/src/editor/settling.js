// Settling a live edit: a drag's or a slider's previews are an iteration
// each, so the shape under a resting pointer stayed a few iterations in (a
// 30-step shear of the 50k cylinder's top half: 13 % of the diagonal from the
// committed shape; a twist 5.3 %). Once the pointer has rested
// SETTLE_IDLE_MS, the same op is previewed again, warm-started, until the
// relative energy change is below SETTLE_CHANGE (the solver's default
// tolerance) or SETTLE_MS after the last change: 60 more iterations took
// those to 3.6 % and 0.8 %. Each settling preview runs the iterations that
// fit in SETTLE_CALL_MS by the last one's time (at most the core's preview
// cap), so that a new value, which replaces the next one, waits no longer
// than for its own preview. Without the idle wait, settling between a drag's
// moves slowed it (50k vertices: 18.8 -> 12-13 shapes/s); with it,
// 16.7-18.8 against 17.8-18.1 without settling, alternated.
const SETTLE_IDLE_MS = 120;
const SETTLE_MS = 3000;
const SETTLE_CHANGE = 1e-6;
const SETTLE_CALL_MS = 30;

/**
 * After a live preview with `stats` ({energy, ms, iterations}), asks for the
 * next settling one: next(iterations, energy) once the value has rested,
 * unless it settled, SETTLE_MS passed since `changedAt`, or current() no
 * longer holds (a new value, the edit ended). `previousEnergy`: the last
 * settling preview's energy, or null after a new value.
 */
export function settleNext({ stats, previousEnergy, changedAt, current, next }) {
  const { energy, ms, iterations } = stats;
  const settled = previousEnergy !== null && Math.abs(previousEnergy - energy) <= SETTLE_CHANGE * Math.abs(previousEnergy);
  const resting = performance.now() - changedAt;
  if (!current() || settled || resting >= SETTLE_MS) return;
  const fit = Math.floor((SETTLE_CALL_MS * Math.max(iterations, 1)) / Math.max(ms, 1e-3));
  const go = () => {
    // The core caps a preview's iterations (kPreviewIterations, session.h).
    if (current()) next(Math.max(fit, 1), energy);
  };
  if (resting >= SETTLE_IDLE_MS) go();
  else setTimeout(go, SETTLE_IDLE_MS - resting);
}
