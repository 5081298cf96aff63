// The solver for one rest pose: a rest mesh, its cotangent weights and the
// factorizations shared by every call, and one entry point that runs any
// method on any selection, direction source and transform (a DeformRequest,
// deform_request.h). The editing state around it (the current mesh, its
// selection, undo) is the Session's (session.h); the CLI, the Session and the
// benchmark all deform through this class.
//
// Gauge (METHOD §7): with no user pins, one vertex per component (and every
// unreferenced vertex) is pinned inside the solver, and the result is moved so
// that the unaffected part (weight 0) best matches its rest position: a rigid
// fit for AnARAP and ARAP, a translation for AnDefGrad and linear. If every
// vertex is affected the centroid is kept. With user pins, nothing is moved.
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "anisoform/deform_request.h"
#include "anisoform/laplacian.h"
#include "anisoform/mesh.h"
#include "anisoform/progress.h"

namespace aniso {

class LaplacianSolver;           // geometry/laplacian_solver.h (internal)
struct LaplacianPatterns;        // the same

class Deformer {
 public:
  // Checks the mesh (Error(BadMesh) unless solvable). The rest is lazy: the
  // unit copy, its cotangent weights and Laplacian at the first deform(),
  // factorizations once per pin set. Why: a commit makes a new rest pose,
  // and building them (a fifth of a second at 200k vertices in WASM) held
  // up the commit's result; now the next edit, or the app's background
  // preparation after the commit, builds them.
  // `patterns`: the orderings of this mesh's Laplacian kept from its other
  // poses (a Session's), reused by this one's factorizations and added to.
  explicit Deformer(Mesh rest, std::shared_ptr<LaplacianPatterns> patterns = nullptr);
  ~Deformer();

  DeformResult deform(const DeformRequest& request);

  // The set-up a first AnARAP edit of this rest pose does before its first
  // iteration, one part per call, so that a host with one thread (the
  // browser's solver worker) answers other calls between the parts: the
  // unit-size copy with its weights and Laplacian; the workspace; the
  // factorization for no user pins (its ordering and analysis, then its
  // numeric part in four); the AnARAP iterations' structures. Each part is what
  // deform() would otherwise build itself, so results do not change.
  // Reports ProgressStage::Factorize with the share of the whole set-up
  // done, and returns it: 1 when nothing is left (a call is then free).
  double prepare_step();

  // Factorizations and a deform's iterations report here (none by default).
  void set_progress(ProgressFn progress) { progress_ = std::move(progress); }

  const Mesh& rest() const { return rest_; }
  int factorizations() const { return factorizations_; }

  // Frees what deform() keeps only to be quicker next time: the
  // factorizations and the solvers' workspace, the bulk of a factorized
  // Deformer's memory (the warm start goes with it; the unit-size copy and
  // its Laplacian stay). The next deform() builds what it needs again.
  // Returns whether anything was held. A Session calls it when memory runs
  // out (session.h).
  bool release_memory() noexcept;

 private:
  struct Workspace;
  void prepare();  // unit_, order_, rank_, cotan_weights_, laplacian_ (once)
  // The factorization for `pins`, made once; its progress is reported on
  // the set-up's scale (progress.h).
  const LaplacianSolver& solver_for(std::vector<int> pins, double* precompute_ms);
  // Reports a factorization's own progress as the Factorize stage's share
  // from kSetupWorkspaceShare to kSetupFactorizedShare.
  std::function<void(double)> factorize_progress() const;
  void report_setup(double share) const;  // the Factorize stage at `share`
  std::vector<int> unpinned_gauge_pins() const;  // the pins of an edit with no user pins
  // A LaplacianSolver for `pins`, ordered and analysed (reusing patterns_), not yet factorized.
  std::unique_ptr<LaplacianSolver> planned_solver(const std::vector<int>& pins);
  DeformResult deform_unit(const DeformRequest& request);  // on unit_, in its units
  // The rest pose as the result of an edit that moves nothing (moves_nothing).
  DeformResult rest_result(const DeformRequest& request, const Eigen::VectorXd& weights) const;

  Mesh rest_;
  // rest_ less origin_ (its bounding box's centre, rounded to a multiple of
  // scale_), divided by scale_, a power of two near its bounding-box diagonal:
  // every solve runs on this unit-size copy about the origin (limits.h
  // kMaxCoordinate): a result does not depend on where the mesh is or on its
  // units. Points (twist origin) are mapped on the way in, lengths (handle
  // offset, twist rate) scaled. Its
  // vertices are renumbered breadth-first (order_[k]: the input vertex that
  // is its vertex k; rank_ the inverse), its faces sorted by their lowest vertex: the
  // iterations read each vertex's neighbours, and in a file's own numbering
  // (a subdivided mesh's new vertices come last) those reads were scattered
  // over the whole mesh (the 200k koala: an ARAP iteration 67 -> 50 ms).
  // Requests are renumbered on the way in, results on the way out.
  Mesh unit_;
  std::vector<int> order_, rank_;
  double scale_ = 1.0;
  Eigen::Vector3d origin_ = Eigen::Vector3d::Zero();
  double diagonal_ = 0.0;
  CotanWeights cotan_weights_;
  Eigen::SparseMatrix<double> laplacian_;
  bool prepared_ = false;
  std::map<std::vector<int>, std::unique_ptr<LaplacianSolver>> solvers_;
  // A factorization prepare_step() has ordered and analysed but not yet
  // finished: solver_for() finishes it if its pins are asked for first.
  std::vector<int> planned_pins_;
  std::unique_ptr<LaplacianSolver> planned_;
  int planned_parts_ = 0;  // of its numeric factorization, done by prepare_step()
  std::shared_ptr<LaplacianPatterns> patterns_;
  int factorizations_ = 0;
  std::unique_ptr<Workspace> workspace_;
  ProgressFn progress_;
};

}  // namespace aniso
