// The direction an edit uses, from the Direction panel's settings
// (global axis, principal curvature, arrows, or the last screen drag), in the
// public API's `direction` form.
import { axisVector } from '../editor/settings.js';

export class DirectionMissingError extends Error {
  constructor(message) {
    super(message);
    this.name = 'DirectionMissingError';
    this.code = 'bad-parameter';
  }
}

export function directionFromSettings(values) {
  const { source, axis, custom, curvature } = values.direction;
  switch (source) {
    case 'global':
      return { type: 'global', vector: [...axisVector(axis, custom)] };
    case 'curvature':
      return { type: 'curvature', which: curvature };
    case 'arrows':
      if (values.arrows.length === 0) {
        throw new DirectionMissingError('Place at least one arrow on the surface with the Arrows tool first.');
      }
      return {
        type: 'constraints',
        constraints: values.arrows.map(({ vertex, direction }) => ({ vertex, direction })),
      };
    case 'screen':
      if (!values.lastScreen) {
        throw new DirectionMissingError('Drag on the mesh with a transform tool to set the screen direction first.');
      }
      return values.lastScreen;
    default:
      throw new DirectionMissingError(`unknown direction source '${source}'`);
  }
}
