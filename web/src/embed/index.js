// The anisoform package: createModeller, createSolverPool and the
// <anisoform-modeller> element (registered on import). README: "Embedding".
import { defineModellerElement } from './modeller-element.js';

export { createModeller } from './create-modeller.js';
export { createSolverPool } from '../worker/solver-pool.js';
export { AnisoformModellerElement, defineModellerElement } from './modeller-element.js';

defineModellerElement();
