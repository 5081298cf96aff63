// Principal curvature directions per vertex (Rusinkiewicz 2004: per-face
// curvature tensors from normal differences, averaged onto vertices in their
// tangent frames), optionally smoothed as a line field, since raw curvature
// directions are noisy. Used for the snake of the paper's Fig. 8.
#pragma once

#include <string>
#include <vector>

#include "anisoform/mesh.h"

namespace aniso {

enum class CurvatureDirection { Min, Max };

// Min and max by magnitude: k_min is the principal curvature of least |k|
// (the direction that bends least: along a tube), k_max the one of greatest
// |k|, so neither swaps when the faces are wound the other way. The values are
// signed (positive where convex towards the normals).
struct PrincipalCurvature {
  Positions min_direction;  // #V by 3 unit tangent vectors
  Positions max_direction;  // #V by 3 unit tangent vectors
  Eigen::VectorXd k_min;    // #V, |k_min| <= |k_max|
  Eigen::VectorXd k_max;    // #V
};

PrincipalCurvature principal_curvature(const Mesh& mesh);

// The chosen principal direction per vertex (#V by 3, unit, tangent), smoothed
// by `smoothing_steps` steps of line-field averaging over one-rings
// (0 = raw). Umbilic vertices (|k_max| - |k_min| tiny) take their neighbours'
// direction through the smoothing. The vectors' signs agree across edges
// (orient_line_field, line_orientation.h), but where the field cannot be
// oriented (around a singularity).
Positions curvature_direction_field(const Mesh& mesh, CurvatureDirection which,
                                    int smoothing_steps = 10);

// Where a principal direction is no more than noise: the two principal
// curvatures differ in magnitude by at most this fraction of their sum
// (|k_max| - |k_min| <= f (|k_max| + |k_min|)), i.e. one bends less than 1.5
// times as much as the other, or the surface is flat there (both ~0 for the
// mesh's size). Rusinkiewicz's estimate on an ordinary triangulation is off
// by up to some 10 % in each curvature (the torus test allows 10 %), so
// below a factor 1.5 the order of the two, and the direction, can be the
// triangulation's rather than the shape's. Measured: 90 % of the hemisphere's
// vertices are below it, 0.2 % of the knotted tube's, 6-24 % of organic
// meshes' (hand, cat, human_woman, spot, bunny), 27 % of fandisk's (flat faces).
constexpr double kUnreliableCurvatureAnisotropy = 0.2;

// A curvature field is warned about when more than this share of the selected
// vertices has no reliable principal direction: then a visible part of the
// edit goes the way the smoothing or the triangulation happens to point.
constexpr double kUnreliableCurvatureShare = 0.25;

// 1 per vertex without a reliable principal direction (see above).
std::vector<char> lacks_principal_direction(const Mesh& mesh);

// A warning naming the share of the selected vertices (weight > 0) that
// `lacking` marks, when it exceeds kUnreliableCurvatureShare; else "".
std::string unreliable_curvature_warning(const std::vector<char>& lacking, const Eigen::VectorXd& weights);

// The most smoothing steps a direction source may ask for. Each step is one
// sweep over every one-ring (O(edges)) and carries a direction one ring
// further, so 1000 steps reach across far more rings than the default 10 ever
// needs, while one call stays bounded: measured in WASM (Node 20), 1000 steps
// on the 200k-vertex koala take 46 s, against 12+ minutes inside one call,
// with no way to stop it, for the 1e9 steps that were once accepted.
constexpr int kMaxCurvatureSmoothing = 1000;

// Error(BadParameter) unless 0 <= steps <= kMaxCurvatureSmoothing.
void validate_curvature_smoothing(int steps);

}  // namespace aniso
