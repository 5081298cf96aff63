// The stages of the flattening pipeline (internal; the API is
// anisoform/flatten.h): its nine .cpp files and the tests use them.
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
//  5b. refine_stretch (flatten_refine.cpp, beyond the paper): the errors of
//     step 6 themselves, smoothed, minimised from the best fold-free map by
//     projected Newton with a fold-free line search;
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

#include <algorithm>
#include <functional>
#include <memory>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "anisoform/flatten.h"
#include "anisoform/mesh.h"
#include "base/convergence_progress.h"
#include "mesh/topology.h"

namespace aniso {

class LaplacianSolver;

// ---- the patch -------------------------------------------------------------

// The faces of `mesh` whose three vertices have vertex_mask[i] != 0 (an empty
// mask selects everything). Throws Error(BadParameter) when the mask has the
// wrong size or holds no whole triangle, Error(BadMesh) when a coordinate of the
// patch is not finite, and Error(BadMesh) "the patch is closed: flattening needs
// a boundary; select a part of the mesh" when a component has no boundary loop.
FlattenPatch extract_flatten_patch(const Mesh& mesh, const std::vector<char>& vertex_mask);

// The patch's triangles' neighbours through shared edges (triangle_adjacency,
// geometry/frames.h), built the first time a stage asks and then kept: the
// targets' direction filling and the cut regions both walk them, and every
// request of a Flattener shares one (built twice per call, they took a
// quarter of the 50k cylinder's flatten call). Holds a pointer to `patch`.
class TriangleNeighbours {
 public:
  explicit TriangleNeighbours(const FlattenPatch& patch) : patch_(&patch) {}
  const VertexAdjacency& get() const;

 private:
  const FlattenPatch* patch_;
  mutable std::optional<VertexAdjacency> adjacency_;
};

// ---- per-triangle charts ---------------------------------------------------

TriangleCharts triangle_charts(const Mesh& mesh);

// Relative area below which a triangle counts as degenerate (area <= this
// fraction of its longest edge squared): it has no chart, no stretch to
// measure and cannot be "flipped".
constexpr double kDegenerateAreaFraction = 1e-12;

// ---- what every triangle should become -------------------------------------

// Targets for the patch of `input` (the mesh the patch was extracted from).
// Global: `su`, `sv` everywhere. Constraints: per-vertex field and amounts by
// propagate_direction_field over the patch; a triangle takes the line-field
// mean of its corners' directions (doubled-angle average in its chart) and the
// mean of their amounts; when no constraint carries amounts, `su`, `sv` apply
// everywhere. Throws Error(BadParameter) for a non-positive or non-finite
// amount, a zero global direction, or a constraint vertex outside the patch.
FlattenTargets flatten_targets(const Mesh& input, const FlattenPatch& patch,
                               const TriangleCharts& charts, const TriangleNeighbours& neighbours,
                               const FlattenDirections& directions, double su, double sv);

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
// by a virtual fan vertex, and every interior vertex is a convex combination
// of its neighbours: uniform weights, then up to `stretch_rounds` rounds of
// weights divided by the ends' L2 stretch (flatten_tutte.cpp says why and
// what it measured), keeping the map of lowest total stretch. For a patch of
// disk topology with holes (genus 0) no triangle is folded over. Scaled to
// the 3D area like lscm_free_boundary. uv: #P by 2.
constexpr int kDefaultStretchRounds = 5;
void tutte_embedding(const FlattenPatch& patch, const TriangleCharts& charts, Eigen::MatrixX2d& uv,
                     int stretch_rounds = kDefaultStretchRounds);

// Scales each component of uv about its centroid so that its signed area is
// the sum of `triangle_area` (#T) over it: the 3D areas for a start map, the
// areas the targets ask for (area * su * sv) before the iterations. A
// component with negative total area is mirrored first (v -> -v).
void scale_to_area(const FlattenPatch& patch, const Eigen::VectorXd& triangle_area,
                   Eigen::MatrixX2d& uv);

// A map with each vertex's u and v side by side (#P by 2, row-major): the
// passes over triangles gather their corners from a copy of this layout, one
// cache line per corner where the column-major Eigen::MatrixX2d takes two.
using UvRows = Eigen::Matrix<double, Eigen::Dynamic, 2, Eigen::RowMajor>;

// ---- the local/global solver -----------------------------------------------

// A relative decrease of the energy that a step cannot show: the energy's sum
// over the triangles resolves about 1e-13 of itself. Every stage (the
// local/global iterations and the refinement's) takes a change at or below
// it as no change, whatever the tolerance: a tolerance of 0 means "to
// round-off". Waiting for an exactly zero change instead depends on the
// compiler's rounding: the hemisphere at su 0.8 stopped natively after 90
// iterations, and in WASM ran its 1000 in the first stage and never refined.
constexpr double kRoundOffDecrease = 1e-11;

// Whether a step from `previous` to `energy` gained at most `tolerance` of
// the energy, or less than round-off.
inline bool small_decrease(double previous, double energy, double tolerance) {
  return previous - energy <= std::max(tolerance, kRoundOffDecrease) * previous;
}


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
  // The vertices its Laplacian pins (one per component), which the stretch
  // refinement holds too.
  const std::vector<int>& pinned() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  int factorizations_ = 0;
};

// The fold guard: the largest fraction of the step from `from` towards `to`
// (#P by 2 each) that folds no non-degenerate triangle over, times a safety
// share (0.8) so that none is driven to exactly zero area; 1 when the whole
// step keeps every triangle's signed area positive.
double fold_free_step_fraction(const Triangles& F, const TriangleCharts& charts,
                               const Eigen::Ref<const Eigen::MatrixXd>& from,
                               const Eigen::Ref<const Eigen::MatrixXd>& to);

// ---- the stretch refinement (flatten_refine.cpp) -------------------------------

// The refinement's progress: after each step, its stage (refine_stage_outlook's
// order), the iterations so far (counted from iterations_before) and the
// stage's energy; false stops it (the map so far is kept).
using RefineProgress = std::function<bool(int stage, int iteration, double energy)>;

struct StretchRefineReport {
  int start = -1;          // which of the starts it ran from; -1: none is fold-free (uv unchanged)
  int iterations = 0;      // all stages'
  int coarse_iterations = 0;  // of them, the stages with rho smoothed more (flatten_refine.cpp)
  double energy = 0.0;     // the refinement's energy at the end (about the mean errors)
  bool converged = false;  // Newton's predicted or the actual relative decrease fell below the tolerance
  bool stalled = false;    // the fold guard or the line search blocked every step
  int factorizations = 0;  // of Newton's system (one per step, more when one needed more regularization)
  std::vector<double> energy_history;  // the final stage's: its start, then after each iteration
};

// Writes to uv (#P by 2) the map that minimises the smoothed mean of
// |along/su - 1| + |across/sv - 1| plus a small area term (the file's head
// says exactly what), by projected Newton with a fold-free backtracking line
// search, from the fold-free one of `starts` with the lowest energy, first
// with the absolute values smoothed more (stages, flatten_refine.cpp):
// monotone within each stage, and no triangle folds. `pinned`: one vertex per
// component, held (the energy does not see where a piece lies). Runs at most
// settings.max_iterations - iterations_before iterations (settings.progress
// is not called: `progress` is, after every step).
StretchRefineReport refine_stretch(const FlattenPatch& patch, const TriangleCharts& charts,
                                   const FlattenTargets& targets, const std::vector<int>& pinned,
                                   const ArapFlattenSettings& settings, int iterations_before,
                                   const std::vector<Eigen::MatrixX2d>& starts, Eigen::MatrixX2d& uv,
                                   const RefineProgress& progress = {});

// The refinement's stages in the order refine_stretch runs them, as a
// progress bar sees them: each one's share of the refinement's time
// (measured) and the relative energy change at which it ends about.
std::vector<StagedProgress::Stage> refine_stage_outlook(double tolerance);

// ---- measuring --------------------------------------------------------------

TriangleStretch measure_stretch(const Triangles& F, const TriangleCharts& charts,
                                const FlattenTargets& targets, const Eigen::MatrixX2d& uv);

// Signed area of triangle t in uv (positive when counter-clockwise).
double uv_signed_area(const Triangles& F, const Eigen::MatrixX2d& uv, int t);

// Triangles (non-degenerate in 3D) whose signed area in uv is <= 0.
int count_folded(const Triangles& F, const TriangleCharts& charts, const Eigen::MatrixX2d& uv);

// How many times the pattern's outline (the boundary loops at uv) crosses
// itself: 0 for a pattern that lies flat without overlapping itself
// (flatten_overlap.cpp).
int count_outline_crossings(const FlattenPatch& patch, const Eigen::MatrixX2d& uv);

// The error part of the metrics (the counts and timings are the caller's).
void summarize_stretch(const TriangleCharts& charts, const FlattenTargets& targets,
                       const TriangleStretch& stretch, FlattenMetrics& metrics);

// The error of one triangle that decides whether it needs a cut: the larger
// of |along/su - 1| and |across/sv - 1| (NaN for a degenerate triangle).
double cut_region_error(const FlattenTargets& targets, const TriangleStretch& stretch, int t);

// The regions of the patch that need a dart or a cut (FlattenRegion, flatten.h),
// in input-mesh vertex indices, largest (by 3D area) first.
std::vector<FlattenRegion> find_cut_regions(const FlattenPatch& patch, const TriangleCharts& charts,
                                            const TriangleNeighbours& neighbours,
                                            const FlattenTargets& targets,
                                            const TriangleStretch& stretch);

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

}  // namespace aniso
