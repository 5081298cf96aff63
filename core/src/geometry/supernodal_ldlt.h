// A supernodal LDL^T factorization of a sparse symmetric positive definite
// matrix (left-looking, dense blocks; the method of CHOLMOD's supernodal
// factorization, Chen, Davis, Hager & Rajamanickam 2008), with Eigen's AMD
// ordering. Why not Eigen's SimplicialLDLT: its up-looking factorization
// updates one scattered entry per multiply-add and took 70 % of a first
// edit's set-up at 200k vertices; here the updates between supernodes are
// dense matrix products. A kept analysis (SupernodalAnalysis) orders by
// nested dissection where that takes fewer operations.
#pragma once

#include <functional>
#include <memory>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "geometry/supernodal_factor.h"

namespace aniso {

struct SupernodalLdlt {
  // P A P^T = L D L^T. perm[i]: the position of row i of A in the factor
  // (as Eigen's permutationP().indices()).
  std::vector<int> perm;
  Eigen::VectorXd d;
  SupernodalFactor L;
  // The first column (in factor order) whose pivot was not above the floor,
  // or -1; the factorization stops there (d is then incomplete, and L is
  // not that matrix's: empty, or a reused result's earlier factor).
  int bad_pivot = -1;
};

struct SupernodalSymbolic;

// What depends on A's pattern only: the ordering, the elimination tree and
// the supernodes with their rows. Kept, it factors new values of the same
// pattern without them (the flattening's Newton steps, one per step).
class SupernodalAnalysis {
 public:
  // A: n by n, its lower triangle (what lies above is ignored).
  explicit SupernodalAnalysis(const Eigen::SparseMatrix<double>& A);
  ~SupernodalAnalysis();
  SupernodalAnalysis(const SupernodalAnalysis&) = delete;
  SupernodalAnalysis& operator=(const SupernodalAnalysis&) = delete;

  // A with that pattern. pivot_floor: pivots at or below it stop the
  // factorization (bad_pivot). A compressed A's values are gathered into
  // the permuted order through a map made once, and the panels' memory is
  // reused: one analysis factors one matrix at a time (not thread-safe).
  SupernodalLdlt factor(const Eigen::SparseMatrix<double>& A, double pivot_floor) const;
  // The same into `result`, in its memory: a factorization of every step
  // (the flattening refinement's) reuses the last one's.
  void factor(const Eigen::SparseMatrix<double>& A, double pivot_floor, SupernodalLdlt& result) const;

  // Whether the ordering is nested dissection's (else AMD's): see the constructor.
  bool nested_dissection() const;

 private:
  std::unique_ptr<SupernodalSymbolic> symbolic_;
};

// How far a factorization has got, in (0, 1]: called with kAnalysedShare
// once the ordering and the analysis are done, then as the numeric
// factorization's work (sum of c^2 over its columns of c entries) passes each
// further twentieth, 1 last. Must not throw.
using FactorProgress = std::function<void(double)>;
// The share of a factorization the ordering and the analysis take: about a
// third of the 200k-vertex cylinder's in WASM (a profile of its
// factorizations: AMD 180 ms, the analysis and the permuted copy 270 ms, the
// numeric factorization 810 ms each).
inline constexpr double kAnalysedShare = 0.35;

// Analysis and factorization at once; `progress` (if set) hears how far it got.
SupernodalLdlt supernodal_ldlt(const Eigen::SparseMatrix<double>& A, double pivot_floor,
                               const FactorProgress& progress = {});

// The same in two calls, for a caller that answers other work between them
// (the app's background preparation, Deformer::prepare_step): the
// constructor orders (AMD) and analyses A and keeps it permuted, the share
// kAnalysedShare of the work; factor_until() does the rest, in parts.
class SupernodalPlan {
 public:
  explicit SupernodalPlan(const Eigen::SparseMatrix<double>& A);  // A's lower triangle, as supernodal_ldlt
  // A plan of A reusing the ordering and analysis of `earlier`'s matrix when
  // A has its pattern (the same mesh's Laplacian at another pose): only A's
  // values are gathered into the permuted order, and the factor is the same,
  // bit for bit, as a plan of its own would give (the same AMD ordering of
  // the same pattern). A matrix of another pattern is planned afresh.
  SupernodalPlan(const SupernodalPlan& earlier, const Eigen::SparseMatrix<double>& A);
  ~SupernodalPlan();
  SupernodalPlan(const SupernodalPlan&) = delete;
  SupernodalPlan& operator=(const SupernodalPlan&) = delete;

  // The numeric factorization in parts, for a caller that answers other
  // work between them: each call factors the supernodes up to the share
  // `until` of the numeric work (at least one; all at `until` 1) and returns
  // whether all are (or a pivot failed); then take_factor() gives
  // supernodal_ldlt's result, the same bit for bit in any number of parts.
  // Reports kAnalysedShare's successors to `progress`, as supernodal_ldlt.
  bool factor_until(double pivot_floor, double until, const FactorProgress& progress = {});
  SupernodalLdlt take_factor();
  // Frees the matrix's values once it is factored; the ordering and the
  // analysis stay, for later plans of the same pattern.
  void release_values();
  // Whether this plan reused an earlier one's ordering and analysis.
  bool reused() const { return reused_; }

 private:
  struct Pattern;
  struct Partial;
  void plan_afresh(const Eigen::SparseMatrix<double>& A);
  std::shared_ptr<Pattern> pattern_;  // shared with the plans that reuse it
  Eigen::SparseMatrix<double> C_;     // P A P^T's lower triangle by columns
  std::unique_ptr<Partial> partial_;  // a factorization in parts, between calls
  bool reused_ = false;
};

// Solves A X = B in place (X: B in, the solution out) for a Hermitian A (its
// lower triangle), real or complex, by L D L^H with pivots of either sign:
// the direction fields' systems. Returns -1, or the first column (in the
// factor's order) whose pivot is not above pivot_floor in magnitude (X is
// then unchanged). For double and std::complex<double>.
template <typename Scalar>
int supernodal_solve(const Eigen::SparseMatrix<Scalar>& A, double pivot_floor,
                     Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>& X);

}  // namespace aniso
