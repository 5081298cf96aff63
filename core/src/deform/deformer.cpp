#include "anisoform/deformer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <limits>
#include <new>
#include <numeric>
#include <optional>
#include <sstream>
#include <string>

#include "base/convergence_progress.h"
#include "base/math_constants.h"
#include "deform/anarap.h"
#include "deform/andefgrad.h"
#include "anisoform/direction_field.h"
#include "anisoform/distortion.h"
#include "directions/curvature.h"
#include "deform/element_targets.h"
#include "anisoform/error.h"
#include "anisoform/limits.h"
#include "deform/gauge.h"
#include "geometry/laplacian_solver.h"
#include "geometry/supernodal_ldlt.h"
#include "anisoform/mesh_check.h"
#include "anisoform/op.h"
#include "mesh/topology.h"

namespace aniso {

Method parse_method(const std::string& name) {
  if (name == "anarap") return Method::AnArap;
  if (name == "andefgrad") return Method::AnDefGrad;
  if (name == "arap") return Method::Arap;
  if (name == "linear") return Method::Linear;
  fail(ErrorCode::BadParameter,
       "unknown method '" + name + "' (expected anarap, andefgrad, arap or linear)");
}

const char* method_name(Method method) {
  switch (method) {
    case Method::AnArap: return "anarap";
    case Method::AnDefGrad: return "andefgrad";
    case Method::Arap: return "arap";
    case Method::Linear: return "linear";
  }
  return "unknown";
}

void validate_direction_source(const DirectionSource& source, int n) {
  switch (source.kind) {
    case DirectionSource::Kind::CurvatureMin:
    case DirectionSource::Kind::CurvatureMax:
      validate_curvature_smoothing(source.curvature_smoothing);
      return;
    case DirectionSource::Kind::Constraints:
      if (source.constraints.empty()) fail(ErrorCode::BadParameter, "a direction field needs at least one constraint");
      validate_direction_constraints(source.constraints, n);
      return;
    case DirectionSource::Kind::Global:
    case DirectionSource::Kind::Screen:
      return;  // checked as one vector, after a screen drag's unprojection (element_targets.cpp)
    case DirectionSource::Kind::Dense:
      if (source.dense.rows() != n) {
        fail(ErrorCode::BadParameter, "a dense direction field needs one direction per vertex (" +
                                          std::to_string(n) + "), got " + std::to_string(source.dense.rows()));
      }
      for (int i = 0; i < n; ++i) {
        if (!source.dense.row(i).allFinite()) {
          fail(ErrorCode::BadParameter, "the direction of vertex " + std::to_string(i) + " is not finite");
        }
      }
      return;
  }
}

namespace {

using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

void check_indices(const std::vector<int>& indices, int n, const char* what) {
  for (int i : indices) {
    if (i < 0 || i >= n) {
      fail(ErrorCode::BadParameter, std::string(what) + " vertex " + std::to_string(i) +
                                        " is out of range (the mesh has " + std::to_string(n) + " vertices)");
    }
  }
}

Eigen::VectorXd checked_weights(const DeformRequest& request, int n) {
  if (request.selection.size() == 0) return Eigen::VectorXd::Ones(n);
  if (request.selection.size() != n) {
    fail(ErrorCode::BadParameter, "the selection has " + std::to_string(request.selection.size()) +
                                      " weights but the mesh has " + std::to_string(n) + " vertices");
  }
  for (int i = 0; i < n; ++i) {
    const double w = request.selection[i];
    if (!(w >= 0.0 && w <= 1.0)) {
      fail(ErrorCode::BadParameter, "selection weight of vertex " + std::to_string(i) +
                                        " must be in [0, 1], got " + std::to_string(w));
    }
  }
  return request.selection;
}

void validate_request(const DeformRequest& request, int n) {
  validate(request.transform);
  // The surface methods' elements (AnARAP's triangle sides, AnDefGrad's
  // triangles) have their edges in the surface, which a scale along the
  // normal leaves as they are: sn would silently do nothing. A part gets
  // thicker by scaling across the direction (sv), as the paper's Fig. 8 does.
  if (request.transform.sn != 1.0 && (request.method == Method::AnArap || request.method == Method::AnDefGrad)) {
    std::ostringstream text;
    text << "thickness (scale along the normal) = " << request.transform.sn << " has no effect with "
         << method_name(request.method)
         << ": its elements' edges lie in the surface. To make a part thicker, scale across the direction "
            "(scale sv, the Thicken tool), or use the linear method";
    fail(ErrorCode::BadParameter, text.str());
  }
  if (request.method != Method::Arap) validate_direction_source(request.direction, n);
  check_indices(request.pins, n, "pinned");
  check_indices(request.handles, n, "handle");
  if (!request.handles.empty() && request.method != Method::Arap) {
    fail(ErrorCode::BadParameter, "handles are only used by the arap method");
  }
  // A handle moves by the offset and a pin stays at rest: one vertex cannot
  // do both (the pin won, silently).
  if (!request.handles.empty() && !request.pins.empty()) {
    std::vector<char> pinned(n, 0);
    for (const int p : request.pins) pinned[p] = 1;
    for (const int h : request.handles) {
      if (pinned[h]) {
        fail(ErrorCode::BadParameter, "vertex " + std::to_string(h) +
                                          " is both pinned and a handle: a handle moves by the offset, a pin stays "
                                          "where it is; give it as one or the other");
      }
    }
  }
  check_iteration_count(request.max_iterations, "iterations");
  check_iteration_count(request.rotation_steps, "rotation steps");
  validate_rotation_coupling(request.rotation_coupling, "rotation coupling");
  if (!(request.tolerance >= 0.0) || !std::isfinite(request.tolerance)) {
    fail(ErrorCode::BadParameter, "tolerance must be a finite number >= 0");
  }
}

// AnARAP keeps each element's shape up to a rotation of its own: a rotation
// of every element, with nothing unselected or pinned to turn against, is a
// rigid motion it cannot show. The whole mesh came back unchanged, and the
// edit was reported done.
void refuse_unseen_rotation(const DeformRequest& request, const Eigen::VectorXd& weights) {
  if (request.method != Method::AnArap || !request.transform.rotates_only() || !request.pins.empty()) return;
  if ((weights.array() < 1.0).any()) return;
  fail(ErrorCode::BadParameter,
       "a rotation of the whole mesh changes nothing with AnARAP: it keeps each part's shape up to a rotation, and "
       "with nothing unselected or pinned to turn against, the rotation is a rigid motion. Select the part to "
       "rotate (the rest holds it), or use AnDefGrad");
}

// Whether the edit moves no vertex whatever the solve: nothing selected (the
// surface methods and the linear map move selected vertices only), or ARAP
// without a handle (T = I with every held vertex at rest: the rest pose is
// the minimum). The rest pose is then the result, to the bit, with nothing
// factorized or iterated: an empty selection on the 200k koala was solved in
// full (6.7 s, 476 MB) and came back 1e-14 off in 2462 of spot's 2487
// coordinates, while the warning said the mesh was left unchanged.
bool moves_nothing(const DeformRequest& request, const Eigen::VectorXd& weights) {
  if (request.method == Method::Arap) return request.handles.empty();
  return !(weights.array() > 0.0).any();
}

// The request in the numbering whose vertex rank[i] is the input's vertex i:
// the selection, the pins and handles, a field's constraints and dense
// directions. Entries outside the mesh are left as they are (ARAP's unused
// direction is not checked).
DeformRequest renumbered(const DeformRequest& request, const std::vector<int>& rank) {
  const int n = static_cast<int>(rank.size());
  DeformRequest out = request;
  if (request.selection.size() == n) {
    for (int i = 0; i < n; ++i) out.selection[rank[i]] = request.selection[i];
  }
  for (int& p : out.pins) p = rank[p];
  for (int& h : out.handles) h = rank[h];
  for (DirectionConstraint& c : out.direction.constraints) {
    if (c.vertex >= 0 && c.vertex < n) c.vertex = rank[c.vertex];
  }
  if (request.direction.dense.rows() == n) {
    for (int i = 0; i < n; ++i) out.direction.dense.row(rank[i]) = request.direction.dense.row(i);
  }
  return out;
}

// The point the linear baseline scales about: the weighted centroid of the
// selection.
// Whether each vertex belongs to a face. The solvers leave the others where
// they are (pinned in their own component); the linear map must too.
std::vector<char> in_a_face(const Mesh& mesh) {
  std::vector<char> used(mesh.num_vertices(), 0);
  for (int t = 0; t < mesh.F.rows(); ++t) {
    for (int k = 0; k < 3; ++k) used[mesh.F(t, k)] = 1;
  }
  return used;
}

// The selection's centroid, of the vertices in a face.
Eigen::Vector3d linear_center(const Mesh& mesh, const Eigen::VectorXd& w, const std::vector<char>& used) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  double total = 0.0;
  for (int i = 0; i < mesh.num_vertices(); ++i) {
    if (!used[i]) continue;
    sum += w[i] * mesh.V.row(i).transpose();
    total += w[i];
  }
  return total > 0.0 ? Eigen::Vector3d(sum / total) : Eigen::Vector3d::Zero();
}

}  // namespace

struct Deformer::Workspace {
  // `unit`: the rest pose at unit size, which the solves run on; `rest`: as given.
  Workspace(const Mesh& unit, const Mesh& rest) : targets(unit), inversions(rest) {
    component = vertex_components(unit.F, unit.num_vertices(), &components);
  }
  TargetContext targets;
  InversionCounter inversions;  // of the rest pose as given
  std::vector<int> component;   // vertex_components, for make_gauge
  int components = 0;
  std::map<ArapElements, std::unique_ptr<AnArapSolver>> arap;
  // Warm start: the last result of a setup (method, elements, pins).
  std::string last_key;
  Positions last_V;
  // The side frames of the last direction source (side_frames), kept while
  // the source is the same: a slider's or a drag's next value would
  // otherwise build them again, and propagate a painted field again.
  std::optional<DirectionSource> frames_source;
  SideFrames frames;
  int frames_built = 0;  // how many times `frames` was built: names this one
  bool warmed_up = false;  // prepare_step's last part has run
  // What the AnARAP solver's scale and shear steps (set_scale_targets,
  // set_shear_targets) were built from: valid while the frames and the
  // weights are these.
  struct AffineSteps {
    ArapElements elements;
    int frames_built;
    Eigen::VectorXd weights;
  };
  std::optional<AffineSteps> scale_steps, shear_steps;
};

namespace {

bool same_rows(const Positions& a, const Positions& b) {
  return a.rows() == b.rows() && (a.array() == b.array()).all();
}

// Whether two sources give the same frames on one rest pose. A screen drag
// never counts as the same: its direction follows the pointer.
bool same_frames_source(const DirectionSource& a, const DirectionSource& b) {
  if (a.kind != b.kind) return false;
  switch (a.kind) {
    case DirectionSource::Kind::Global: return a.vector == b.vector;
    case DirectionSource::Kind::CurvatureMin:
    case DirectionSource::Kind::CurvatureMax: return a.curvature_smoothing == b.curvature_smoothing;
    case DirectionSource::Kind::Constraints:
      return a.constraints == b.constraints;
    case DirectionSource::Kind::Dense: return same_rows(a.dense, b.dense);
    case DirectionSource::Kind::Screen: return false;
  }
  return false;
}

// The power of two nearest below the mesh's bounding-box diagonal (1 for a
// mesh without extent): dividing by it is exact in floating point, so the
// unit-size copy is the mesh itself in other units, and scaling back is exact.
double unit_scale(double diagonal) {
  return diagonal > 0.0 && std::isfinite(diagonal) ? std::ldexp(1.0, std::ilogb(diagonal)) : 1.0;
}

// The point the unit-size copy is centred on: the bounding box's centre,
// rounded to a multiple of `scale` (a power of two). A mesh about the origin
// keeps the origin (its solve is unchanged); a mesh far from it is brought
// within 1.5 units of it, where round-off is that of any unit-size mesh
// (spot scaled by 1e-4 and moved by 1e6 was solved at 2^33 units from the
// origin: its coordinates had 20 bits fewer below the mesh's size, the solve
// stopped at its iteration cap, 1.2e-3 of the size off). The subtraction is
// exact there (both terms are multiples of the smaller one's unit in the
// last place and the difference is small), so is adding it back.
Eigen::Vector3d unit_origin(const BoundingBox& box, double scale) {
  const Eigen::Vector3d centre = 0.5 * box.min + 0.5 * box.max;  // no overflow near the coordinate bound
  return Eigen::Vector3d((centre / scale).array().round() * scale);
}

}  // namespace

Deformer::Deformer(Mesh rest, std::shared_ptr<LaplacianPatterns> patterns)
    : rest_(std::move(rest)), patterns_(std::move(patterns)) {
  require_solvable(rest_);  // also bounds the coordinates (limits.h), so the diagonal is finite
  const BoundingBox box = shape_bounding_box(rest_);
  diagonal_ = box.diagonal();
  scale_ = unit_scale(diagonal_);
  origin_ = unit_origin(box, scale_);
}

void Deformer::prepare() {
  if (prepared_) return;
  // Built in locals and moved in at the end: running out of memory here
  // leaves the Deformer unprepared, not half prepared.
  const int n = rest_.num_vertices();
  std::vector<int> order = breadth_first_order(rest_.F, n);
  std::vector<int> rank(static_cast<std::size_t>(n));
  for (int k = 0; k < n; ++k) rank[order[k]] = k;
  Mesh unit;
  unit.V.resize(n, 3);
  for (int k = 0; k < n; ++k) unit.V.row(k) = (rest_.V.row(order[k]) - origin_.transpose()) / scale_;
  // The faces in the order of their lowest (renumbered) vertex, so that the per-triangle
  // passes (targets, weights) read and write nearby vertices too. A counting sort on that
  // vertex, stable: a comparison sort took 4 % of a 200k mesh's first-edit set-up in WASM.
  const Triangles renamed = rest_.F.unaryExpr([&rank](int v) { return rank[v]; });
  const Eigen::Index m = renamed.rows();
  std::vector<int> start(static_cast<std::size_t>(n) + 1, 0);
  for (Eigen::Index f = 0; f < m; ++f) ++start[renamed.row(f).minCoeff() + 1];
  std::partial_sum(start.begin(), start.end(), start.begin());
  unit.F.resize(m, 3);
  for (Eigen::Index f = 0; f < m; ++f) unit.F.row(start[renamed.row(f).minCoeff()]++) = renamed.row(f);
  CotanWeights weights = cotangent_weights(unit);
  Eigen::SparseMatrix<double> laplacian = cotangent_laplacian(unit, weights);
  order_ = std::move(order);
  rank_ = std::move(rank);
  unit_ = std::move(unit);
  cotan_weights_ = std::move(weights);
  laplacian_ = std::move(laplacian);
  prepared_ = true;
}

Deformer::~Deformer() = default;

bool Deformer::release_memory() noexcept {
  const bool held = !solvers_.empty() || workspace_ != nullptr || planned_ != nullptr;
  solvers_.clear();
  planned_.reset();
  workspace_.reset();
  return held;
}

const LaplacianSolver& Deformer::solver_for(std::vector<int> pins, double* precompute_ms) {
  std::sort(pins.begin(), pins.end());
  pins.erase(std::unique(pins.begin(), pins.end()), pins.end());
  auto it = solvers_.find(pins);
  if (it != solvers_.end()) return *it->second;
  const auto start = Clock::now();
  const std::function<void(double)> factorized = factorize_progress();
  std::unique_ptr<LaplacianSolver> solver;
  if (planned_ && planned_pins_ == pins) {  // prepare_step() has ordered and analysed it
    if (planned_parts_ == 0) factorized(kAnalysedShare);  // else its parts have said more
    planned_->factorize(factorized);
    solver = std::move(planned_);
  } else {
    factorized(0.0);
    solver = planned_solver(pins);
    factorized(kAnalysedShare);
    solver->factorize(factorized);
  }
  factorized(1.0);
  ++factorizations_;
  *precompute_ms += ms_since(start);
  return *solvers_.emplace(std::move(pins), std::move(solver)).first->second;
}

void Deformer::report_setup(double share) const {
  if (progress_) progress_(ProgressStage::Factorize, share);
}

// A factorization's own progress (FactorProgress's fraction) as a share of
// the set-up (progress.h): exactly kSetupFactorizedShare when done (tests
// count factorizations by it).
namespace {
double factorization_share(double fraction) {
  return kSetupWorkspaceShare * (1.0 - fraction) + kSetupFactorizedShare * fraction;
}
}  // namespace

std::function<void(double)> Deformer::factorize_progress() const {
  return [this](double fraction) { report_setup(factorization_share(fraction)); };
}

std::unique_ptr<LaplacianSolver> Deformer::planned_solver(const std::vector<int>& pins) {
  std::shared_ptr<SupernodalPlan>* kept = nullptr;
  if (patterns_) kept = &patterns_->by_pins[pins];
  auto solver = std::make_unique<LaplacianSolver>(laplacian_, pins, LaplacianSolver::Deferred{},
                                                  kept && *kept ? kept->get() : nullptr);
  if (kept && solver->plan()) *kept = solver->plan();
  return solver;
}

std::vector<int> Deformer::unpinned_gauge_pins() const {
  std::vector<int> pins = make_gauge(workspace_->component, workspace_->components, {}).pins;
  std::sort(pins.begin(), pins.end());
  pins.erase(std::unique(pins.begin(), pins.end()), pins.end());
  return pins;
}

double Deformer::prepare_step() {
  // The parts' shares of the whole set-up (progress.h): the 200k-vertex
  // koala's in Node (WASM), 380-520, 45-75, 320-580, 470-680 (the numeric
  // factorization, done in kNumericParts parts) and 230 ms (the AnARAP
  // structures and the triangle adjacency: 155 ms without the adjacency and
  // the local step's scratch, which the first edit then built: 391-541
  // against 421-737 ms for a first stretch preview after the preparation),
  // then the warm-up (the 200k cylinder's: 460 ms, which its first preview
  // no longer spends).
  constexpr int kNumericParts = 4;
  const auto report = [this](double share) {
    report_setup(share);
    return share;
  };
  if (!prepared_) {
    prepare();
    return report(kSetupLaplacianShare);
  }
  if (!workspace_) {
    workspace_ = std::make_unique<Workspace>(unit_, rest_);
    return report(kSetupWorkspaceShare);
  }
  std::vector<int> pins = unpinned_gauge_pins();
  if (solvers_.find(pins) == solvers_.end()) {
    if (!planned_ || planned_pins_ != pins) {
      planned_.reset();  // before the next one is built, not beside it
      planned_ = planned_solver(pins);
      planned_pins_ = std::move(pins);
      planned_parts_ = 0;
      return report(factorization_share(kAnalysedShare));
    }
    const double until = static_cast<double>(++planned_parts_) / kNumericParts;
    if (!planned_->factorize_until(until, factorize_progress())) {
      // Not reported: the factorization's own reports (by twentieths of the
      // work) have said as much, or a little more.
      return factorization_share(kAnalysedShare + (1.0 - kAnalysedShare) * until);
    }
    double precompute_ms = 0.0;  // solver_for() counts and keeps the finished one
    solver_for(std::move(pins), &precompute_ms);
    return report(kSetupFactorizedShare);
  }
  auto& iterations = workspace_->arap[ArapElements::Spokes];
  if (!iterations) {
    iterations = std::make_unique<AnArapSolver>(unit_, cotan_weights_, laplacian_, ArapElements::Spokes);
    // And the triangles' adjacency, which the first edit's frames need
    // wherever a direction lies along a normal (on a closed mesh, somewhere).
    workspace_->targets.triangle_adjacency();
    return report(kSetupStructuresShare);
  }
  if (!workspace_->warmed_up) {
    // What else only a drag's first preview did once: the inversion count's
    // adjacency, and a preview's work (frames, scale targets, an iteration)
    // for its memory and (WASM) compiled code. After the preparation, the
    // 50k cylinder's first stretch preview took 134-199 ms in Node against
    // 15-20 for the next ones (now 38-57), the 200k's 568 against 70-90
    // (memset of memory touched for the first time 186 ms, the adjacency
    // 64, the frames 104; now 126-153); in the page, a 50k tube's first
    // shape came 176-280 ms after the drag's first move (now 104-126).
    // Only time is at stake: without the memory for it (a mesh near the
    // vertex limit), it is left to the first preview, and no memory is
    // released for it (Session's retry would release this factorization).
    // The frames along the mesh's longest axis, which runs along the surface
    // somewhere even on a flat mesh (a fixed x is a flat mesh's normal when
    // it lies in a plane x = c, whose frames are refused).
    try {
      workspace_->inversions.build_adjacency(rest_);
      DirectionSource along_longest;
      along_longest.kind = DirectionSource::Kind::Global;
      along_longest.vector = longest_axis(shape_bounding_box(rest_));
      const SideFrames frames = side_frames(workspace_->targets, along_longest);
      iterations->warm_up(*solvers_.at(pins), frames.frames);
    } catch (const std::bad_alloc&) {
      iterations->reset_rotations();
    }
    workspace_->warmed_up = true;
    return report(1.0);
  }
  return 1.0;
}

DeformResult Deformer::deform(const DeformRequest& request) {
  const auto start = Clock::now();
  const int n = rest_.num_vertices();
  validate_request(request, n);
  validate_twist(request.transform, diagonal_);
  validate_move(request.handle_offset, diagonal_);
  // Here, so that a bad weight is named by the input's numbering.
  const Eigen::VectorXd weights = checked_weights(request, n);
  refuse_unseen_rotation(request, weights);
  if (moves_nothing(request, weights)) {
    // A bad field is refused all the same, as the solve refused it (cheaply:
    // its checks need the vertex normals only).
    if (request.method != Method::Arap && request.direction.kind == DirectionSource::Kind::Constraints) {
      check_direction_constraints(rest_, request.direction.constraints);
    }
    return rest_result(request, weights);
  }
  const bool was_prepared = prepared_;
  prepare();
  if (!was_prepared) report_setup(kSetupLaplacianShare);
  const double prepare_ms = was_prepared ? 0.0 : ms_since(start);
  // Solve on the unit-size copy (limits.h: results independent of the units,
  // no overflow in squared areas) in its numbering, then scale lengths and
  // energies back and number the vertices as given.
  DeformRequest unit_request = renumbered(request, rank_);
  unit_request.transform.twist_origin = (unit_request.transform.twist_origin - origin_) / scale_;
  unit_request.transform.twist_degrees_per_unit *= scale_;
  unit_request.handle_offset /= scale_;
  DeformResult result;
  try {
    result = deform_unit(unit_request);
  } catch (const Error&) {
    // Of the errors a solve can raise, only a direction constraint's names a
    // vertex (validate_request has checked the rest): its checks run again
    // in the input's numbering, to raise the same error naming the vertex
    // the caller knows.
    if (request.direction.kind == DirectionSource::Kind::Constraints) {
      propagate_direction_field(rest_, request.direction.constraints);
    }
    throw;
  }
  Positions solved = std::move(result.V);
  result.V.resize(n, 3);
  for (int k = 0; k < n; ++k) result.V.row(order_[k]) = solved.row(k);
  result.V *= scale_;
  result.V.rowwise() += origin_.transpose();
  // Pins are held at rest as given, to the bit (the way back rounds a
  // coordinate far from origin_ only; a handle's offset is a length, scaled).
  for (const int p : request.pins) result.V.row(p) = rest_.V.row(p);
  // Energies are sums of squares, but AnARAP's per fan is evaluated expanded
  // (|e'|^2 - 2 tr(R S) + |T e|^2), which round-off takes below 0 at a
  // perfect fit (-4.4e-17 on spot unchanged): reported as 0. (A NaN stays
  // one, for the last guard below.)
  const auto reported = [this](double energy) { return (energy < 0.0 ? 0.0 : energy) * scale_ * scale_; };
  result.energy = reported(result.energy);
  for (double& energy : result.energy_history) energy = reported(energy);
  // The last guard: no non-finite number leaves the deformer.
  for (int i = 0; i < result.V.rows(); ++i) {
    if (!result.V.row(i).allFinite()) {
      fail(ErrorCode::Numerical, "the solve produced a non-finite position at vertex " + std::to_string(i));
    }
  }
  for (const double energy : result.energy_history) {
    if (!std::isfinite(energy)) fail(ErrorCode::Numerical, "the solve produced a non-finite energy");
  }
  if (!std::isfinite(result.energy)) fail(ErrorCode::Numerical, "the solve produced a non-finite energy");
  result.inverted = workspace_->inversions.count(rest_, result.V);
  result.precompute_ms += prepare_ms;  // the rest pose's weights and Laplacian are precomputation too
  result.solve_ms = ms_since(start) - result.precompute_ms;
  if (progress_) progress_(ProgressStage::Solve, 1.0);
  return result;
}

DeformResult Deformer::rest_result(const DeformRequest& request, const Eigen::VectorXd& weights) const {
  DeformResult result;
  result.V = rest_.V;
  result.method = request.method;
  result.selected = static_cast<int>((weights.array() > 0.0).count());
  result.factorizations = factorizations_;
  if (progress_) progress_(ProgressStage::Solve, 1.0);
  return result;
}

DeformResult Deformer::deform_unit(const DeformRequest& request) {
  const int n = unit_.num_vertices();
  const Eigen::VectorXd w = checked_weights(request, n);

  DeformResult result;
  result.method = request.method;
  result.selected = static_cast<int>((w.array() > 0.0).count());
  double precompute_ms = 0.0;
  if (!workspace_) {
    const auto t0 = Clock::now();
    workspace_ = std::make_unique<Workspace>(unit_, rest_);
    precompute_ms += ms_since(t0);
    report_setup(kSetupWorkspaceShare);
  }
  Workspace& ws = *workspace_;
  // prepare_step's warm-up would now reset the rotations a warm start goes on from.
  ws.warmed_up = true;
  const bool curvature_source = request.direction.kind == DirectionSource::Kind::CurvatureMin ||
                                request.direction.kind == DirectionSource::Kind::CurvatureMax;
  if (curvature_source && request.method != Method::Arap) {
    // A sphere's or a flat part's curvature field is arbitrary: said, not silent.
    const std::string warning = unreliable_curvature_warning(ws.targets.lacks_principal_direction(), w);
    if (!warning.empty()) result.warnings.push_back(warning);
  }

  if (request.method == Method::Linear) {
    // Each vertex moves by its own local map about the selection's centroid,
    // then by the twist map itself (about its axis line), as a cage would.
    TransformSpec local = request.transform;
    local.twist = false;
    const ElementTargets targets = vertex_targets(ws.targets, request.direction, local, w);
    const std::vector<char> used = in_a_face(unit_);
    const Eigen::Vector3d center = linear_center(unit_, w, used);
    result.V = unit_.V;
    for (int i = 0; i < n; ++i) {
      if (!used[i]) continue;
      const Eigen::Vector3d p = unit_.V.row(i).transpose();
      const Eigen::Vector3d q = center + targets.T[i] * (p - center);
      const Eigen::Vector3d o = request.transform.twist_origin;
      result.V.row(i) = (o + twist_rotation(request.transform, w[i], p) * (q - o)).transpose();
    }
    for (int p : request.pins) result.V.row(p) = unit_.V.row(p);
    result.directions_filled = targets.filled;
  } else if (request.method == Method::AnDefGrad) {
    const Gauge gauge = make_gauge(ws.component, ws.components, request.pins);
    const LaplacianSolver& solver = solver_for(gauge.pins, &precompute_ms);
    const ElementTargets targets = triangle_targets(ws.targets, request.direction, request.transform, w);
    Positions b;
    gradient_rhs(unit_, cotan_weights_, targets.T, b);
    result.V = unit_.V;
    solver.solve(b, result.V);
    realign(unit_, gauge, w, Alignment::Translation, result.V);
    result.energy = gradient_energy(unit_, cotan_weights_, targets.T, result.V);
    result.iterations = 1;
    result.directions_filled = targets.filled;
  } else {  // AnARAP, or ARAP with handles (deform() returns the rest pose without: moves_nothing)
    const bool isotropic = request.method == Method::Arap;
    std::vector<int> user_pins = request.pins;
    if (isotropic) user_pins.insert(user_pins.end(), request.handles.begin(), request.handles.end());
    // ARAP's unaffected part is everything but the handles.
    Eigen::VectorXd affected = w;
    if (isotropic) {
      affected.setZero();
      for (int h : request.handles) affected[h] = 1.0;
    }
    const Gauge gauge = make_gauge(ws.component, ws.components, user_pins);
    const LaplacianSolver& solver = solver_for(gauge.pins, &precompute_ms);
    auto& iterations = ws.arap[request.elements];
    if (!iterations) {
      const auto t0 = Clock::now();
      iterations = std::make_unique<AnArapSolver>(unit_, cotan_weights_, laplacian_, request.elements);
      precompute_ms += ms_since(t0);
      report_setup(1.0);
    }
    bool rotational = false;
    if (isotropic) {
      iterations->set_identity_targets();
    } else {
      if (!ws.frames_source || !same_frames_source(*ws.frames_source, request.direction)) {
        SideFrames built = side_frames(ws.targets, request.direction);
        ws.frames_source.reset();  // until both are set (an allocation may fail)
        ws.frames = std::move(built);
        ++ws.frames_built;
        ws.frames_source = request.direction;
      }
      const SideFrames& frames = ws.frames;
      result.directions_filled = frames.frames.filled;
      rotational = request.transform.has_rotational_part();
      // A live preview of a scale takes the solver's scale targets, without a
      // 3x3 map per side (a commit takes the maps, as its replay does). A
      // slider or a typed amount: from the scale steps, built once for these
      // frames and weights and reused while the value changes. A screen
      // drag's direction follows the pointer, so its frames change with
      // every value: the targets directly, without steps (200k koala in
      // WASM, 117 -> 63 ms a value against the maps; from steps built for
      // one value, one more pass).
      // A shear's live preview likewise (linear in the shear), and a
      // rotation's and a twist's directly (Rodrigues' formula per side), for
      // the coupled rotations that need no polar targets: at 50k vertices in
      // WASM, set_targets was half of a shear's preview and 45 % of a
      // rotation's; a twist's took 39-60 ms, now 24-31.
      const bool coupled = rotational && request.rotations == RotationScheme::Coupled;
      const bool uniform = frames.su.size() == 0;  // no amounts per vertex
      const bool scale_preview = request.preview && request.transform.scales_only() && uniform;
      const bool shear_preview = request.preview && request.transform.shears_only() && uniform && coupled;
      const bool rotation_preview = request.preview && request.transform.rotates_only() && uniform && coupled;
      const bool twist_preview = request.preview && request.transform.twists_only() && uniform && coupled;
      const bool screen = request.direction.kind == DirectionSource::Kind::Screen;
      std::optional<Workspace::AffineSteps>& kept = scale_preview ? ws.scale_steps : ws.shear_steps;
      const bool steps_valid = kept && kept->elements == request.elements && kept->frames_built == ws.frames_built &&
                               kept->weights.size() == w.size() && kept->weights == w;
      if ((scale_preview || shear_preview) && !screen && !steps_valid) {
        if (scale_preview) {
          iterations->set_scale_steps(frames.frames, side_weights(unit_, w));
        } else {
          iterations->set_shear_steps(frames.frames, side_weights(unit_, w),
                                      shear_orientation(unit_, request.transform, w));
        }
        kept = Workspace::AffineSteps{request.elements, ws.frames_built, w};
      }
      const TransformSpec& spec = request.transform;
      if (scale_preview && screen) {
        iterations->set_scale_targets(frames.frames, side_weights(unit_, w), spec.su, spec.sv);
      } else if (scale_preview) {
        iterations->set_scale_targets(spec.su, spec.sv);
      } else if (shear_preview && screen) {
        iterations->set_shear_targets(frames.frames, side_weights(unit_, w),
                                      shear_orientation(unit_, spec, w), spec.shear);
      } else if (shear_preview) {
        iterations->set_shear_targets(spec.shear);
      } else if (rotation_preview) {
        const Positions& axis = spec.rotate_axis == RotateAxis::Normal ? frames.frames.n
                                : spec.rotate_axis == RotateAxis::U    ? frames.frames.u
                                                                       : frames.frames.v;
        iterations->set_rotation_targets(axis, side_weights(unit_, w), spec.rotate_degrees * kDegToRad);
      } else if (twist_preview) {
        iterations->set_twist_targets(frames.frames.u, side_weights(unit_, w), spec);
      } else {
        // Coupled rotations are fitted to the whole targets: no polar parts.
        iterations->set_targets(SideTargets(unit_, frames, spec, w), !coupled);
      }
    }
    std::string key = std::string(method_name(request.method)) + ":" +
                      std::to_string(static_cast<int>(request.elements));
    for (int p : gauge.pins) key += "," + std::to_string(p);
    // The paper's scheme applies a rotation incrementally, so it always starts
    // from the rest pose; the coupled scheme converges from anywhere.
    const bool stepped = rotational && request.rotations == RotationScheme::Steps;
    iterations->set_rotation_coupling(rotational && !stepped ? request.rotation_coupling : 0.0);
    const bool warm = request.warm_start && !stepped && key == ws.last_key && ws.last_V.rows() == n;
    result.V = warm ? ws.last_V : unit_.V;
    if (!warm) iterations->reset_rotations();
    if (isotropic) {
      for (int h : request.handles) result.V.row(h) = unit_.V.row(h) + request.handle_offset.transpose();
    }
    for (int p : request.pins) result.V.row(p) = unit_.V.row(p);
    const int steps = stepped ? request.rotation_steps : request.max_iterations;
    ConvergenceProgress solve_progress(steps, stepped ? -1.0 : request.tolerance);
    const auto on_iteration = [&](int done) {
      if (!progress_) return;
      const double energy = result.energy_history.empty() ? std::numeric_limits<double>::quiet_NaN()
                                                          : result.energy_history.back();
      progress_(ProgressStage::Solve, solve_progress.update(done, energy));
    };
    result.iterations = iterations->run(solver, result.V, steps, stepped ? -1.0 : request.tolerance,
                                        result.energy_history, request.final_energy,
                                        stepped ? Acceleration::None : request.acceleration,
                                        on_iteration);
    result.energy = result.energy_history.empty() ? 0.0 : result.energy_history.back();
    result.converged = stepped || iterations->settled() || result.iterations < steps;
    realign(unit_, gauge, affected, Alignment::Rigid, result.V);
    ws.last_key = key;
    ws.last_V = result.V;
  }

  result.factorizations = factorizations_;
  result.precompute_ms = precompute_ms;
  return result;
}

}  // namespace aniso
