// The anisoform package: createModeller and the <anisoform-modeller> element
// (registered on import). README: "Embedding".
import { defineModellerElement } from './modeller-element.js';

export { createModeller } from './create-modeller.js';
export { AnisoformModellerElement, defineModellerElement } from './modeller-element.js';

defineModellerElement();
