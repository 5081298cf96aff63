// Garment-pattern flattening: a free-boundary anisotropic ARAP
// parameterization (METHOD §8; paper §4.2, Fig. 11-12; Liu et al. 2008 with a
// per-triangle target), and the industry baseline it is measured against.
//
// The pipeline, in the order the Flattener runs it:
//  1. extract_flatten_patch: the faces whose three vertices are selected, made
//     compact (unreferenced vertices are left out), split into components;
//     a component without a boundary loop is refused (a closed surface has no
//     free boundary to flatten to);
//  2. triangle_charts: every triangle laid flat isometrically in its own 2D
//     frame (its chart);
//  3. flatten_targets: the wanted direction cu per triangle (in its chart) and
//     the wanted stretch su along it, sv across it: T_t = C_t diag(su, sv) C_t^T;
//  4. lscm_free_boundary: the initial map (conformal, free boundary), or
//     tutte_embedding, a fold-free one (see "Folds" below);
//  5. ArapFlattening: local/global iterations on
//       E(u, L) = sum_t sum_{edges (i,j) of t} w_ij |(u_j - u_i) - L_t T_t (x_j - x_i)|^2,
//     L_t in SO(2), w_ij the clamped half-cotangent weights of laplacian.h,
//     global step = one prefactored 2D Poisson solve (one pin per component);
//  6. measure_stretch / summarize_stretch: achieved stretch along and across
//     the wanted direction per triangle, errors against the wanted amounts;
//  7. align_grainlines / layout_components: each piece turned so that its
//     mean compression direction is horizontal, pieces side by side.
//
// Folds: the local step only ever fits proper rotations, and the global step
// is guarded (shortened so that no triangle folds over) whenever the current
// map is fold-free. LSCM can fold nearly closed patches; ARAP is then given a
// few iterations to unfold, and if folds remain the Flattener starts again
// from the Tutte embedding, which has none. The guard can stall on a triangle
// driven towards zero area (very non-developable patches with hard targets):
// the result is then fold-free but not converged, and says so.
//
// Units: uv is in model units (the flattening is metric: a unit of length on
// the surface is a unit in the plane before the wanted stretch). Pattern files
// scale by millimetres per unit (pattern_export.h).
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "anisoform/direction_field.h"
#include "anisoform/mesh.h"

namespace aniso {

// ---- the patch -------------------------------------------------------------

struct FlattenPatch {
  Mesh mesh;                      // #P by 3 positions, #T by 3 triangles (compact)
  std::vector<int> input_vertex;  // #P: the vertex's index in the input mesh
  std::vector<int> input_face;    // #T: the triangle's index in the input mesh
  std::vector<int> component;     // #P: face-connected component, 0..num_components-1
  int num_components = 0;
  std::vector<std::vector<int>> boundary_loops;  // patch vertex indices, in walking order
  std::vector<int> loop_component;               // per loop: its component
};

// The faces of `mesh` whose three vertices have vertex_mask[i] != 0 (an empty
// mask selects everything). Throws Error(BadParameter) when the mask has the
// wrong size or holds no whole triangle, Error(BadMesh) when a coordinate of the
// patch is not finite, and Error(BadMesh) "the patch is closed: flattening needs
// a boundary; select a part of the mesh" when a component has no boundary loop.
FlattenPatch extract_flatten_patch(const Mesh& mesh, const std::vector<char>& vertex_mask);

// ---- per-triangle charts ---------------------------------------------------

// Each triangle's own isometric 2D frame: origin at corner 0, first axis along
// edge 0->1, second axis = normal x first axis, so a counter-clockwise
// triangle has positive area in its chart.
struct TriangleCharts {
  Positions axis_u;         // #T by 3: first chart axis in 3D (unit)
  Positions axis_v;         // #T by 3: second chart axis in 3D (unit)
  Eigen::MatrixXd corners;  // #T by 6: corner k at (corners(t,2k), corners(t,2k+1)); corner 0 = 0
  Eigen::VectorXd area;     // #T: 3D area (model units^2); 0 for a degenerate triangle
};

TriangleCharts triangle_charts(const Mesh& mesh);

// Relative area below which a triangle counts as degenerate (area <= this
// fraction of its longest edge squared): it has no chart, no stretch to
// measure and cannot be "flipped".
constexpr double kDegenerateAreaFraction = 1e-12;

// ---- what every triangle should become -------------------------------------

// Where the wanted directions come from.
struct FlattenDirections {
  enum class Kind {
    Global,       // one 3D vector, projected into every triangle
    Constraints,  // vertex constraints "INDEX DX DY DZ [SU [SV]]": propagated over the
                  // patch as a smooth line field (all patch vertices given: used as is)
  };
  Kind kind = Kind::Global;
  Eigen::Vector3d global = Eigen::Vector3d::UnitX();  // Global
  std::vector<DirectionConstraint> constraints;       // Constraints: input-mesh vertex indices
};

struct FlattenTargets {
  Eigen::MatrixX2d direction;  // #T by 2: unit cu in the triangle's chart
  Eigen::VectorXd su;          // #T: wanted stretch along cu (0.8 = 20 % shrinkage)
  Eigen::VectorXd sv;          // #T: wanted stretch across (along cv = normal x cu)
  int filled_directions = 0;   // triangles whose direction was (nearly) normal to
                               // them and was taken from their neighbours
};

// Targets for the patch of `input` (the mesh the patch was extracted from).
// Global: `su`, `sv` everywhere. Constraints: per-vertex field and amounts by
// propagate_direction_field over the patch; a triangle takes the line-field
// mean of its corners' directions (doubled-angle average in its chart) and the
// mean of their amounts; when no constraint carries amounts, `su`, `sv` apply
// everywhere. Throws Error(BadParameter) for a non-positive or non-finite
// amount, a zero global direction, or a constraint vertex outside the patch.
FlattenTargets flatten_targets(const Mesh& input, const FlattenPatch& patch,
                               const TriangleCharts& charts, const FlattenDirections& directions,
                               double su, double sv);

// The same directions with other amounts everywhere (the baseline's isometric
// flattening uses su = sv = 1 on the same field).
FlattenTargets with_uniform_amounts(const FlattenTargets& targets, double su, double sv);

// ---- initial maps ----------------------------------------------------------

// Least-squares conformal map (Levy et al. 2002) with a free boundary: per
// component two boundary vertices far apart (a diameter of its boundary) are
// pinned; the sparse normal equations are solved by SimplicialLDLT. Each
// component is then scaled about its centroid to the 3D area of its triangles.
// uv: #P by 2 output. Throws Error(Numerical) if the factorization fails.
void lscm_free_boundary(const FlattenPatch& patch, const TriangleCharts& charts,
                        Eigen::MatrixX2d& uv);

// Fold-free start (Tutte 1963, Floater 2003): per component the longest
// boundary loop is put on a circle by arc length, every other loop is closed
// by a virtual fan vertex, and every interior vertex is the mean of its
// neighbours. For a patch of disk topology with holes (genus 0) no triangle
// is folded over. Scaled to the 3D area like lscm_free_boundary. uv: #P by 2.
void tutte_embedding(const FlattenPatch& patch, const TriangleCharts& charts,
                     Eigen::MatrixX2d& uv);

// Scales each component of uv about its centroid so that its signed area is
// the sum of `triangle_area` (#T) over it: the 3D areas for a start map, the
// areas the targets ask for (area * su * sv) before the iterations. A
// component with negative total area is mirrored first (v -> -v).
void scale_to_area(const FlattenPatch& patch, const Eigen::VectorXd& triangle_area,
                   Eigen::MatrixX2d& uv);

// ---- the local/global solver -----------------------------------------------

struct ArapFlattenSettings {
  int max_iterations = 500;
  double tolerance = 1e-8;   // stop when the relative energy change falls below
  bool guard_folds = true;   // shorten a global step that would fold a triangle
                             // over, whenever the current map has none folded
  int unfold_iterations = 50;  // from a folded start: iterations allowed to
                               // unfold it before giving up (the Flattener then
                               // starts again from a fold-free map)
  // Called after every iteration with (iteration, energy); returning false
  // stops early (the map so far is kept).
  std::function<bool(int, double)> progress;
};

struct ArapFlattenReport {
  int iterations = 0;
  double energy = 0.0;          // E at the end (model units^2)
  bool converged = false;       // the tolerance was reached
  bool stalled = false;         // the guard could not make progress without a fold
  int folded = 0;               // folded triangles at the end (count_folded)
  int shortened_steps = 0;      // global steps the guard shortened
  std::vector<double> energy_history;  // E before the first and after each iteration
};

// Prefactors the patch's cotangent Laplacian once (one pinned vertex per
// component: the global step is free up to a translation; rotations are fixed
// by the local step). Every solve reuses it, whatever the targets.
class ArapFlattening {
 public:
  ArapFlattening(const FlattenPatch& patch, const TriangleCharts& charts);
  ~ArapFlattening();
  ArapFlattening(const ArapFlattening&) = delete;
  ArapFlattening& operator=(const ArapFlattening&) = delete;

  // Iterates from uv (#P by 2, in/out). Local step per triangle: the rotation
  // L_t maximizing tr(L^T S), S = sum_k w_k e'_k (T_t x_k)^T, in closed form
  // (angle atan2(S10 - S01, S00 + S11)): always a proper rotation, so the
  // local step never mirrors. Global step: L u = b with one pin per component.
  ArapFlattenReport solve(const FlattenTargets& targets, const ArapFlattenSettings& settings,
                          Eigen::MatrixX2d& uv) const;

  int factorizations() const { return factorizations_; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  int factorizations_ = 0;
};

// ---- measuring --------------------------------------------------------------

// Per triangle, J = the linear map from its chart to the plane (2 by 2).
struct TriangleStretch {
  Eigen::VectorXd along;        // #T: |J cu|, achieved stretch along the wanted direction
  Eigen::VectorXd across;       // #T: |J cv|, achieved stretch across it
  Eigen::VectorXd sigma_max;    // #T: larger singular value of J
  Eigen::VectorXd sigma_min;    // #T: smaller singular value of J (negative if folded)
  Eigen::VectorXd area_ratio;   // #T: signed 2D area / 3D area (= det J)
  Eigen::MatrixX2d pattern_direction;  // #T by 2: J cu / |J cu|, where cu runs in the plane
  std::vector<char> degenerate;        // #T: no chart (zero 3D area): NaN in every measure
                                       // above, and left out of means and maxima
};

TriangleStretch measure_stretch(const Triangles& F, const TriangleCharts& charts,
                                const FlattenTargets& targets, const Eigen::MatrixX2d& uv);

// Signed area of triangle t in uv (positive when counter-clockwise).
double uv_signed_area(const Triangles& F, const Eigen::MatrixX2d& uv, int t);

// Triangles (non-degenerate in 3D) whose signed area in uv is <= 0.
int count_folded(const Triangles& F, const TriangleCharts& charts, const Eigen::MatrixX2d& uv);

struct FlattenMetrics {
  int triangles = 0;
  int vertices = 0;
  int components = 0;
  int boundary_loops = 0;
  int flipped = 0;                       // folded-over triangles (count_folded)
  double compression_error_mean = 0.0;   // area-weighted mean of |along/su - 1|
  double compression_error_max = 0.0;    // max of |along/su - 1|
  double cross_error_mean = 0.0;         // area-weighted mean of |across/sv - 1|
  double cross_error_max = 0.0;
  double area_distortion_mean = 0.0;     // area-weighted mean of |A2d / (A3d su sv) - 1|
  int iterations = 0;
  double energy = 0.0;
  bool converged = false;
  double seconds = 0.0;                  // wall time of the flatten call
  int filled_directions = 0;
  std::string initialization;            // "lscm" or "tutte"
  std::string method;                    // "anisotropic" or "uniform-baseline"
};

// The error part of the metrics (the counts and timings are the caller's).
void summarize_stretch(const TriangleCharts& charts, const FlattenTargets& targets,
                       const TriangleStretch& stretch, FlattenMetrics& metrics);

// Area-weighted mean line direction (doubled-angle average, METHOD §4.4: the
// sign of a line does not matter) of the triangles of each component:
// #components unit 2D vectors.
std::vector<Eigen::Vector2d> mean_pattern_directions(const FlattenPatch& patch,
                                                     const TriangleCharts& charts,
                                                     const TriangleStretch& stretch);

// ---- the industry baseline --------------------------------------------------

// Scales each component of an (isometric) flattening about its centroid by
// su along `directions[c]` and sv across it, with su, sv the area-weighted
// means of the targets over the component: one uniform 2D scale per piece,
// which is what garment CAD does (paper §4.2).
void apply_uniform_scale(const FlattenPatch& patch, const TriangleCharts& charts,
                         const FlattenTargets& targets,
                         const std::vector<Eigen::Vector2d>& directions, Eigen::MatrixX2d& uv);

// ---- layout -------------------------------------------------------------------

// Mean uv of each component's vertices: #components points, the centre about
// which a piece is scaled or turned.
std::vector<Eigen::RowVector2d> component_centroids(const FlattenPatch& patch,
                                                    const Eigen::MatrixX2d& uv);

// Rotates each component about its centroid so that its grainline (#components
// unit 2D vectors, updated to +u) runs along +u: pattern pieces come out with
// their compression direction horizontal whatever orientation the start map
// happened to have. A rigid motion: no measure changes.
void align_grainlines(const FlattenPatch& patch, std::vector<Eigen::Vector2d>& grainlines,
                      Eigen::MatrixX2d& uv);

// Moves the components side by side along +u (each translated), bottom-aligned at v = 0, first starting at u = 0, with a gap of
// gap_fraction times the largest piece size between bounding boxes.
void layout_components(const FlattenPatch& patch, Eigen::MatrixX2d& uv,
                       double gap_fraction = 0.05);

// ---- the one-call interface -----------------------------------------------------

enum class FlattenMethod {
  Anisotropic,      // the wanted stretch is part of every triangle's target (ours)
  UniformBaseline,  // flatten with su = sv = 1, then apply_uniform_scale (garment CAD)
};

struct FlattenOptions {
  FlattenMethod method = FlattenMethod::Anisotropic;
  FlattenDirections directions;
  double su = 1.0;  // wanted stretch along (unless constraints carry amounts)
  double sv = 1.0;  // wanted stretch across
  ArapFlattenSettings solver;
};

struct FlattenResult {
  Eigen::MatrixX2d uv;                 // #P by 2 pattern coordinates (model units), laid out
  FlattenTargets targets;
  TriangleStretch stretch;
  std::vector<Eigen::Vector2d> grainline;  // per component: the mean pattern direction of the
                                           // wanted field (the baseline's scale axis); pieces
                                           // are turned so that it is +u (align_grainlines)
  FlattenMetrics metrics;
};

// Holds everything that depends only on the patch: charts, the LSCM start
// (and the fold-free start once needed) and the one factorization. A new
// amount, direction or method never refactors.
class Flattener {
 public:
  // vertex_mask: #V of `mesh`, nonzero = selected; empty = the whole mesh.
  Flattener(const Mesh& mesh, const std::vector<char>& vertex_mask = {});
  ~Flattener();
  Flattener(const Flattener&) = delete;
  Flattener& operator=(const Flattener&) = delete;

  FlattenResult flatten(const FlattenOptions& options);

  const FlattenPatch& patch() const;
  const TriangleCharts& charts() const;
  int factorizations() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// One-shot: Flattener(mesh, vertex_mask).flatten(options).
struct FlattenOutput {
  FlattenPatch patch;
  FlattenResult result;
};
FlattenOutput flatten(const Mesh& mesh, const std::vector<char>& vertex_mask,
                      const FlattenOptions& options);

}  // namespace aniso
