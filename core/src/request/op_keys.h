// The allowed keys of every object of the public op (op.h): the parsers
// refuse any other key, and op_schema() lists these for the tests that check
// the TypeScript declarations.
#pragma once

#include "json_fields.h"

namespace aniso::op_keys {

using json_fields::Keys;

inline const Keys kOp{"method", "direction", "transform", "pins", "handles", "move", "elements",
                      "maxIterations", "rotations", "rotationCoupling", "rotationSteps", "tolerance", "acceleration", "preview", "warmStart"};
inline const Keys kRotationSchemes{"coupled", "steps"};
inline const Keys kAccelerations{"lbfgs", "anderson", "none"};
inline const Keys kTransform{"scale", "thickness", "shear", "rotate", "twist"};
inline const Keys kRotate{"axis", "degrees"};
inline const Keys kTwist{"axis", "degreesPerUnit", "origin"};
inline const Keys kDirectionTypes{"global", "curvature", "screen", "constraints", "dense"};
inline const Keys kGlobal{"type", "vector"};
inline const Keys kCurvature{"type", "which", "smoothing"};
inline const Keys kScreen{"type", "from", "to", "camera"};
inline const Keys kCamera{"view", "projection", "viewport", "anchor", "normal"};
inline const Keys kConstraints{"type", "constraints"};
inline const Keys kConstraint{"vertex", "direction", "su", "sv"};
inline const Keys kDense{"type", "directions"};
inline const Keys kRegionKinds{"all", "sphere", "box", "vertices"};
inline const Keys kSphere{"center", "radius"};
inline const Keys kBox{"min", "max"};
inline const Keys kVertices{"vertices", "weights"};
inline const Keys kSelect{"falloff", "mode"};
inline const Keys kMeshOptions{"weld"};
inline const Keys kPatternOptions{"mmPerUnit"};
inline const Keys kFlatten{"compress", "direction", "baseline", "patch", "maxIterations", "tolerance", "refine"};

}  // namespace aniso::op_keys
