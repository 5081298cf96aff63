// The direction an edit uses, from the Direction panel's settings
// (global axis, principal curvature, arrows, or the last screen drag), and the
// one a flattening uses, from the Flatten panel's (global axis or arrows with
// their own compression), in the public API's `direction` form.
import { axisVector } from '../shared/settings.js';

export class DirectionMissingError extends Error {
  constructor(message) {
    super(message);
    this.name = 'DirectionMissingError';
    this.code = 'bad-parameter';
  }
}

const NO_ARROWS = 'no arrows are placed: drag on the surface with the Arrows tool first, or choose another direction source';

/**
 * Whether an edit's result depends on its direction: not for a twist alone
 * (its maps are the twist's Jacobian) nor for a rotation about the normal
 * alone, whatever the method (the core builds their element maps without
 * the direction's frame; wasm/test/deform.test.mjs checks this against the
 * solver, both ways). Apply sends those without a direction, so that they
 * need no drag or arrows first.
 */
export function transformUsesDirection(transform) {
  const parts = Object.keys(transform);
  if (parts.length !== 1) return true;
  if (parts[0] === 'twist') return false;
  return !(parts[0] === 'rotate' && transform.rotate.axis === 'n');
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
        throw new DirectionMissingError(NO_ARROWS);
      }
      return {
        type: 'constraints',
        constraints: values.arrows.map(({ vertex, direction }) => ({ vertex, direction })),
      };
    case 'screen':
      if (!values.lastScreen) {
        throw new DirectionMissingError(
          'no screen direction yet: drag on the mesh with a transform tool (the drag sets it), or choose another direction source',
        );
      }
      return values.lastScreen;
    default:
      throw new DirectionMissingError(`unknown direction source '${source}'`);
  }
}

/**
 * The Flatten panel's direction: a global axis ('auto' = the longest side of
 * the mesh's bounding box, as the CLI's default) or the arrows, each with its
 * own compression where one was set (the others take the panel's amounts,
 * since the core only spreads amounts when every constraint has them).
 */
export function flattenDirectionFromSettings(values, bounds) {
  const { source, axis, custom, along, across } = values.flatten;
  if (source === 'arrows') {
    if (values.arrows.length === 0) {
      throw new DirectionMissingError(NO_ARROWS);
    }
    const ownAmounts = values.arrows.some((arrow) => arrow.su !== undefined || arrow.sv !== undefined);
    return {
      type: 'constraints',
      constraints: values.arrows.map(({ vertex, direction, su, sv }) =>
        ownAmounts ? { vertex, direction, su: su ?? along, sv: sv ?? across } : { vertex, direction }),
    };
  }
  if (axis === 'auto') {
    const extent = bounds.max.map((value, k) => value - bounds.min[k]);
    const longest = extent.indexOf(Math.max(...extent));
    return { type: 'global', vector: [0, 1, 2].map((k) => (k === longest ? 1 : 0)) };
  }
  return { type: 'global', vector: [...axisVector(axis, custom)] };
}
