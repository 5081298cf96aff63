// The one factorization every solver shares: the cotangent Laplacian with some
// vertices pinned (held at given positions), factored once by sparse LDL^T and
// reused for every iteration, amount and direction. Only a new mesh or a new
// pin set refactors; `factorizations()` counts them so tests can check that.
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <vector>

#include <Eigen/Sparse>

#include "anisoform/mesh.h"

namespace aniso {

class SupernodalPlan;  // geometry/supernodal_ldlt.h

// The orderings and analyses of one mesh's Laplacian, by pin set, kept for
// its later poses: a new pose's Laplacian has the same pattern, so its
// factorization reuses them (SupernodalPlan) and skips a third of the work,
// with the same factor bit for bit. A Session shares one among the Deformers
// of its mesh's poses.
struct LaplacianPatterns {
  std::map<std::vector<int>, std::shared_ptr<SupernodalPlan>> by_pins;
};

class LaplacianSolver {
 public:
  // L: #V by #V symmetric positive semidefinite; pinned: vertex indices held
  // fixed (each free component must contain at least one, else the solve is
  // singular: Error(Numerical) names a vertex of the unpinned component).
  // `progress` (if set) hears how far the factorization has got (FactorProgress,
  // geometry/supernodal_ldlt.h).
  LaplacianSolver(const Eigen::SparseMatrix<double>& L, std::vector<int> pinned,
                  const std::function<void(double)>& progress = {});
  // The same in two calls, for a caller that answers other work between
  // them (Deformer::prepare_step): this constructor checks the pins and
  // orders and analyses L's free block (FactorProgress's kAnalysedShare of
  // the work); factorize() does the rest. Solve only once it has.
  // `earlier`: a plan of the same L's pattern to reuse (LaplacianPatterns), or null.
  struct Deferred {};
  LaplacianSolver(const Eigen::SparseMatrix<double>& L, std::vector<int> pinned, Deferred,
                  const SupernodalPlan* earlier = nullptr);
  void factorize(const std::function<void(double)>& progress = {});
  // factorize() in parts: up to the share `until` of the numeric work (at
  // least a supernode); returns whether it is done. The same factor, bit
  // for bit, in any number of parts.
  bool factorize_until(double until, const std::function<void(double)>& progress = {});
  // Until factorize(): the ordering and analysis of the free block, for a
  // LaplacianPatterns to keep (factorize() frees its values; null after).
  const std::shared_ptr<SupernodalPlan>& plan() const;
  ~LaplacianSolver();
  LaplacianSolver(const LaplacianSolver&) = delete;
  LaplacianSolver& operator=(const LaplacianSolver&) = delete;

  // Solves L x = b on the free rows with x fixed on the pinned rows.
  // b: #V by k (rows of pinned vertices ignored); x: #V by k, pinned rows are
  // read as the pinned values, free rows are written.
  void solve(const Eigen::Ref<const Eigen::MatrixXd>& b, Eigen::Ref<Eigen::MatrixXd> x) const;

  // Row-major #V by 3 convenience for positions.
  void solve(const Positions& b, Positions& x) const;

  const std::vector<int>& pinned() const { return pinned_; }
  int num_vertices() const { return n_; }

  struct Impl;

 private:
  void plan(const Eigen::SparseMatrix<double>& L, const SupernodalPlan* earlier);

  std::unique_ptr<Impl> impl_;
  std::vector<int> pinned_;
  int n_ = 0;
};

}  // namespace aniso
