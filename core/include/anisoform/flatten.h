// Garment-pattern flattening, the public API: a free-boundary anisotropic ARAP
// parameterization (METHOD §8; paper §4.2, Fig. 11-12; Liu et al. 2008 with a
// per-triangle target), and the industry baseline it is measured against.
// Build a Flattener once per patch and call flatten() with any options; the
// pipeline stages it runs are internal (src/flatten/flatten_pipeline.h, which
// describes them in order, and how folds are avoided).
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

// The part of the mesh that is flattened: the faces whose three vertices are
// selected, made compact and split into face-connected components (pieces).
struct FlattenPatch {
  Mesh mesh;                      // #P by 3 positions, #T by 3 triangles (compact)
  std::vector<int> input_vertex;  // #P: the vertex's index in the input mesh
  std::vector<int> input_face;    // #T: the triangle's index in the input mesh
  std::vector<int> component;     // #P: face-connected component, 0..num_components-1
  int num_components = 0;
  std::vector<std::vector<int>> boundary_loops;  // patch vertex indices, in walking order
  std::vector<int> loop_component;               // per loop: its component
  // Input faces wound against most of their piece, turned over in `mesh`
  // (majority_winding) so that the pattern is seen from one side (kPatternSide,
  // pattern_export.h), ascending.
  std::vector<int> reoriented_faces;
  // Input faces left out: fins hanging off edges shared by three or more
  // faces (kMaxFinAreaShare), ascending.
  std::vector<int> dropped_faces;
};

// Faces off an edge shared by three or more faces are left out of a patch as
// a fin when they form a sheet (joined across two-face edges) of at most this
// share of the patch's area that is not the largest at that edge: a triangle
// or a flap glued on by mistake. A larger one is a part of its own, which
// the user must select and flatten apart: that patch is refused, naming the
// edge.
constexpr double kMaxFinAreaShare = 0.05;

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
  int near_normal_directions = 0;  // triangles whose wanted 3D direction is within
                                   // kNearNormalDirectionDegrees of their normal
};

// A wanted direction this close to a triangle's normal (degrees) says little
// about where the fabric runs on it: its tangent part is at most sin(10°) =
// 17 % of it, and tilting the patch by a few degrees turns that part anywhere.
constexpr double kNearNormalDirectionDegrees = 10.0;

// ---- the local/global solver -----------------------------------------------

struct ArapFlattenSettings {
  // A safety stop, not a budget: every open test mesh converges below it
  // (the bunny, the slowest, at 318 of them; README, Flattening refinement).
  int max_iterations = 1000;
  double tolerance = 1e-8;   // stop when the relative energy change falls below
                             // (the refinement's stages also stop where 10 steps
                             // together gained less than 3e-4: flatten_refine.cpp)
  bool guard_folds = true;   // shorten a global step that would fold a triangle
                             // over, whenever the current map has none folded
  // L-BFGS on the ARAP energy from a fold-free map (flatten_arap.cpp);
  // false: the plain local/global steps (the paper's).
  bool accelerate = true;
  // After the local/global iterations, minimise the reported error itself
  // (flatten_refine.cpp; beyond the paper): false keeps the paper's ARAP
  // result as it is.
  bool refine = true;
  int unfold_iterations = 50;  // from a folded start: iterations allowed to
                               // unfold it before giving up (the Flattener then
                               // starts again from a fold-free map)
  // ArapFlattening::solve calls it after every iteration with (iteration,
  // energy); returning false stops early (the map so far is kept). The
  // Flattener sets its own: it reports through FlattenOptions::progress.
  std::function<bool(int, double)> progress;
};

// ---- measuring --------------------------------------------------------------

// Per triangle, J = the linear map from its chart to the plane (2 by 2).
struct TriangleStretch {
  Eigen::VectorXd along;        // #T: |J cu|, achieved stretch along the wanted direction
  Eigen::VectorXd across;       // #T: |J cv|, achieved stretch across it
  Eigen::VectorXd sigma_max;    // #T: larger singular value of J
  Eigen::VectorXd sigma_min;    // #T: smaller singular value of J (negative if folded)
  Eigen::VectorXd area_ratio;   // #T: signed 2D area / 3D area (= det J)
  Eigen::VectorXd shear_degrees;  // #T: |angle between J cu and J cv - 90°|: the fabric's shear
  Eigen::MatrixX2d pattern_direction;  // #T by 2: J cu / |J cu|, where cu runs in the plane
  std::vector<char> degenerate;        // #T: no chart (zero 3D area): NaN in every measure
                                       // above, and left out of means and maxima
};

// A connected part of the patch (triangles sharing edges) whose error is
// above kCutRegionError: where the patch needs a dart or a cut.
struct FlattenRegion {
  std::vector<int> vertices;  // input-mesh vertex indices, ascending
  int vertex = -1;            // representative: the region's vertex nearest its centroid
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();  // area-weighted, of its triangles (3D)
  double error_mean = 0.0;    // area-weighted mean of its triangles' error (cut_region_error)
  int triangles = 0;
  double area_share = 0.0;            // its 3D area / the patch's (at most kCutRegionMaxArea)
  double connected_area_share = 0.0;  // the same of all the connected triangles above
                                      // kCutRegionError it was taken from (more than
                                      // area_share where it was cut down to its worst part)
};

// A triangle is part of a region when the larger of |along/su - 1| and
// |across/sv - 1| exceeds this (the same bound as the usable mean area
// distortion: a quarter off is more than fabric eases in), and a region is
// named when it covers at least kCutRegionMinArea of the patch's 3D area
// (single stray triangles are noise, not a place to cut).
constexpr double kCutRegionError = 0.25;
constexpr double kCutRegionMinArea = 0.01;
// A region is at most this share of the patch's 3D area: a dart or a cut
// takes in a small part of a piece. Where a connected part above the error
// is larger (a hand: two thirds of it), the region is its worst part, grown
// from its worst triangle by error, the worst neighbour first; the patch
// then needs cutting into pieces, which flatten_problem says.
constexpr double kCutRegionMaxArea = 0.1;

struct FlattenMetrics {
  int triangles = 0;
  int vertices = 0;
  int components = 0;
  int boundary_loops = 0;
  int flipped = 0;                       // folded-over triangles (count_folded)
  int non_manifold_edges = 0;            // patch edges shared by 3 or more faces (check_mesh)
  double compression_error_mean = 0.0;   // area-weighted mean of |along/su - 1|
  double compression_error_max = 0.0;    // max of |along/su - 1|
  double cross_error_mean = 0.0;         // area-weighted mean of |across/sv - 1|
  double cross_error_max = 0.0;
  double area_distortion_mean = 0.0;     // area-weighted mean of |A2d / (A3d su sv) - 1|
  // The shear the pattern gives the fabric (TriangleStretch::shear_degrees):
  // the errors above measure two lengths, not the angle between them, and a
  // triangle sheared off square can meet both.
  double shear_degrees_mean = 0.0;       // area-weighted
  double shear_degrees_max = 0.0;
  int near_normal_directions = 0;        // FlattenTargets::near_normal_directions
  int iterations = 0;
  double energy = 0.0;
  bool converged = false;
  bool capped = false;                   // stopped unconverged at the iteration cap (raise it, not cut)
  bool refined = false;                  // the stretch refinement changed the ARAP result (refine on)
  int outline_crossings = 0;             // the outline crosses itself: the pattern overlaps itself
  double seconds = 0.0;                  // wall time of the flatten call
  int filled_directions = 0;
  std::string initialization;            // "lscm" or "tutte"
  std::string method;                    // "anisotropic" or "uniform-baseline"
  std::vector<FlattenRegion> suggested_cuts;  // largest first; empty when no region's
                                              // error is above kCutRegionError
  std::vector<int> reoriented_faces;          // FlattenPatch::reoriented_faces (a warning names them)
  std::vector<int> dropped_faces;             // FlattenPatch::dropped_faces (a warning names them)
};

// Empty when the flattening is usable as one piece; otherwise why not and
// what to do, in plain words for the user (naming the worst region of
// suggested_cuts, if any, by a vertex). Not one piece: the patch has
// non-manifold edges, the solver did not converge, triangles folded over, or
// the area is off by more than kMaxUsableAreaDistortion on average (a
// hemisphere, about the most curved patch still cut whole, is 18 %; an open
// box or a hand is 36 % and more).
constexpr double kMaxUsableAreaDistortion = 0.25;
std::string flatten_problem(const FlattenMetrics& metrics);

// Above this mean shear (degrees) a flattening is warned about: a shear of g
// lengthens one diagonal of a square of fabric and shortens the other by about
// g/2 (in radians), 4.4 % at 5°, as much as the compressions a pattern builds
// in (a few to 20 %); the compression figures then flatter the pattern.
constexpr double kShearWarningDegrees = 5.0;

// A wanted direction within kNearNormalDirectionDegrees of the normal on more
// than this share of the patch's triangles is warned about.
constexpr double kNearNormalDirectionShare = 0.1;

// What a usable flattening still should say (in words, possibly none): a
// mean shear above kShearWarningDegrees; directions filled from neighbours
// (the direction was normal to their triangles), or nearly normal on more
// than kNearNormalDirectionShare of the triangles.
std::vector<std::string> flatten_warnings(const FlattenMetrics& metrics);

// ---- the Flattener ---------------------------------------------------------------

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
  // Called after every iteration, local/global and refinement's, with the
  // share of the flattening done, in [0, 1) until it ends (by stages:
  // flatten.cpp); returning false stops early (the map so far is kept).
  std::function<bool(double)> progress;
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
