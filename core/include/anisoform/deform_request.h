// The vocabulary every layer shares: which method, which direction source,
// what a deformation request holds and what it returns. It sits at the bottom
// of the include graph (mesh, transforms, direction constraints, screen drags
// only), so that the modules below the Deformer (element targets, the AnARAP
// iterations, the session, the CLI) can use the types without including the
// solver. Deformer::deform (deformer.h) runs a DeformRequest.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "anisoform/direction_field.h"
#include "anisoform/mesh.h"
#include "anisoform/screen_direction.h"
#include "anisoform/transforms.h"

namespace aniso {

enum class Method {
  AnArap,     // anisotropic ARAP on vertex fans (METHOD §5)
  AnDefGrad,  // anisotropic deformation gradients, one Poisson solve (METHOD §6)
  Arap,       // isotropic ARAP with handles: the paper's baseline
  Linear,     // linear directional map blended by weight: the "cage-like" baseline
};
Method parse_method(const std::string& name);  // "anarap" ...; Error(BadParameter)
const char* method_name(Method method);

enum class ArapElements {
  Spokes,         // the fan's edges from the centre vertex (Sorkine & Alexa)
  SpokesAndRims,  // plus the fan's rim edges (Chao et al.; CGAL's default)
};

// How AnARAP treats a rotational part of T (rotate, twist, shear; METHOD §5).
enum class RotationScheme {
  Coupled,  // neighbouring rotations tied together: converges (ours, beyond the paper)
  Steps,    // the paper's: no fixed point, `rotation_steps` steps from the rest pose
};

// How AnARAP / ARAP's local/global iterations are sped up.
enum class Acceleration {
  Lbfgs,     // L-BFGS preconditioned by the prefactored Laplacian (anarap_lbfgs.cpp)
  Anderson,  // Anderson acceleration with an energy safeguard (anderson.h)
  None,      // plain local/global (the paper's)
};

struct DirectionSource {
  enum class Kind {
    Global,        // `vector`, projected per element
    CurvatureMin,  // principal curvature direction fields (smoothed)
    CurvatureMax,
    Constraints,   // `constraints` propagated to a line field (amounts too)
    Screen,        // `screen`: a pointer drag unprojected at the anchor's depth
    Dense,         // `dense`: #V by 3, one direction per vertex, used as is
  };
  Kind kind = Kind::Global;
  Eigen::Vector3d vector = Eigen::Vector3d::UnitX();
  std::vector<DirectionConstraint> constraints;
  ScreenDrag screen;
  Positions dense;
  int curvature_smoothing = 10;
};

// Checks a direction source against a mesh of n vertices before any work is
// done with it: the curvature smoothing in range (curvature.h), at least one
// constraint and each one valid (validate_direction_constraints), one finite
// direction per vertex for a dense field. Error(BadParameter) naming what is
// wrong. Deformer::deform and Session::direction_field call it; a global or
// screen direction is checked where it becomes one vector.
void validate_direction_source(const DirectionSource& source, int n);

struct DeformRequest {
  Method method = Method::AnArap;
  Eigen::VectorXd selection;  // #V selection weights in [0, 1]; empty = all 1
  DirectionSource direction;
  TransformSpec transform;
  std::vector<int> pins;     // held at their rest positions
  std::vector<int> handles;  // Arap: moved by handle_offset and held
  Eigen::Vector3d handle_offset = Eigen::Vector3d::Zero();
  ArapElements elements = ArapElements::Spokes;
  int max_iterations = 50;   // AnARAP / ARAP: cap on local/global iterations
  double tolerance = 1e-6;   // relative energy change that ends the iterations
  // Converging iterations (not the paper's rotation steps) are accelerated:
  // the same fixed point, in several times fewer iterations.
  Acceleration acceleration = Acceleration::Lbfgs;
  // AnARAP with a rotational part in T (rotate, twist, shear): the paper's
  // scheme has no fixed point (METHOD §5): each step turns the selected fans
  // once more, so it runs exactly `rotation_steps` steps. The coupled scheme
  // converges like a stretch (max_iterations, tolerance); rotation_coupling
  // is its alpha (anarap.h): larger keeps a region's rotation more exactly,
  // smaller lets the rest of the mesh bend more freely.
  RotationScheme rotations = RotationScheme::Coupled;
  double rotation_coupling = 1.0;
  int rotation_steps = 1;
  bool warm_start = true;    // start from the previous result of the same setup
  // AnARAP / ARAP: false skips the local step after the last solve, which
  // only measures the final energy (the positions are the same); the energy
  // reported is then the one before the last solve, an upper bound. A live
  // preview does not need it: the next preview refits the rotations first.
  bool final_energy = true;
  // A live preview (resolve_edit sets it for an op with preview: true). AnARAP
  // then takes scale-only targets from steps kept across calls (see
  // AnArapSolver::set_scale_targets; not for a screen drag, whose direction
  // changes with every value): a slider's next amount costs one pass over
  // the spokes. Equal to the direct targets up to rounding, and chosen by the
  // request alone, so a result never depends on what ran before.
  bool preview = false;
};

struct DeformResult {
  Positions V;                          // #V by 3 deformed positions
  Method method = Method::AnArap;
  int selected = 0;                     // vertices with weight > 0
  int iterations = 0;
  double energy = 0.0;                  // final energy (AnDefGrad: the Poisson energy)
  std::vector<double> energy_history;   // after each iteration (AnARAP / ARAP)
  bool converged = true;
  int directions_filled = 0;            // degenerate projections filled (METHOD §3)
  int inverted = 0;                     // triangles folded over (count_inverted)
  int factorizations = 0;               // total so far in this session
  double precompute_ms = 0.0;           // factorization etc. done for this call
  double solve_ms = 0.0;
  // What the user should know about the result, in words (a curvature field
  // without clear directions over much of the selection).
  std::vector<std::string> warnings;
};

}  // namespace aniso
