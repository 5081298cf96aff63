// Factor once, solve many. The free-free block of L is factored by supernodes
// (supernodal_ldlt.h, AMD ordering); solves sweep the factor by supernodes
// too (supernodal_factor.h), once for all right-hand side columns together.
// An ARAP iteration is mostly these sweeps.
#include "geometry/laplacian_solver.h"

#include <algorithm>
#include <cstddef>
#include <memory>
#include <string>
#include <utility>

#include "anisoform/error.h"
#include "geometry/supernodal_factor.h"
#include "geometry/supernodal_ldlt.h"

namespace aniso {

struct LaplacianSolver::Impl {
  std::vector<int> free_of;        // vertex -> free index or -1
  std::vector<int> free_vertices;  // free index -> vertex
  std::vector<int> pinned_index;   // vertex -> pinned index or -1
  // The solves' gathers and scatters, in factor order: the vertex at each
  // position, and for the positions coupled to pinned vertices (the band
  // along the pins) those vertices and L's entries. Why not L_fc times all
  // pinned values: that product is a dense free-by-k temporary, allocated,
  // zeroed and read back at every solve, where only the band has entries.
  std::vector<int> vertex_at;
  std::vector<int> band_positions, band_offsets, band_vertices;
  std::vector<double> band_values;
  // The factor L D L^T of P L_ff P^T: L by supernodes and 1 / D.
  SupernodalFactor factor;
  Eigen::VectorXd inv_d;
  // Until factorize(): the ordered and analysed free block, the free-pinned
  // block and the pivot floor.
  std::shared_ptr<SupernodalPlan> plan;
  Eigen::SparseMatrix<double, Eigen::RowMajor> L_fc;
  double pivot_floor = 0.0;
  bool factorized = false;
};

namespace {

// Every connected component of L's graph needs a pinned vertex, else L_ff is
// singular; say which component (by its lowest vertex) before factorizing.
void require_pin_per_component(const Eigen::SparseMatrix<double>& L, const std::vector<int>& pinned_index) {
  const int n = static_cast<int>(L.rows());
  std::vector<char> seen(n, 0);
  std::vector<int> stack;
  for (int start = 0; start < n; ++start) {
    if (seen[start]) continue;
    bool has_pin = false;
    seen[start] = 1;
    stack.assign(1, start);
    while (!stack.empty()) {
      const int i = stack.back();
      stack.pop_back();
      has_pin = has_pin || pinned_index[i] >= 0;
      for (Eigen::SparseMatrix<double>::InnerIterator it(L, i); it; ++it) {
        const int j = static_cast<int>(it.row());
        if (!seen[j]) {
          seen[j] = 1;
          stack.push_back(j);
        }
      }
    }
    if (!has_pin) {
      fail(ErrorCode::Numerical, "the mesh component containing vertex " + std::to_string(start) +
                                     " has no pinned vertex, so its position is undetermined");
    }
  }
}

}  // namespace

LaplacianSolver::LaplacianSolver(const Eigen::SparseMatrix<double>& L, std::vector<int> pinned,
                                 const std::function<void(double)>& progress)
    : LaplacianSolver(L, std::move(pinned), Deferred{}) {
  if (progress) progress(kAnalysedShare);
  factorize(progress);
}

LaplacianSolver::LaplacianSolver(const Eigen::SparseMatrix<double>& L, std::vector<int> pinned, Deferred,
                                 const SupernodalPlan* earlier)
    : impl_(std::make_unique<Impl>()), pinned_(std::move(pinned)), n_(static_cast<int>(L.rows())) {
  std::sort(pinned_.begin(), pinned_.end());
  pinned_.erase(std::unique(pinned_.begin(), pinned_.end()), pinned_.end());
  Impl& im = *impl_;
  im.free_of.assign(n_, -1);
  im.pinned_index.assign(n_, -1);
  for (std::size_t k = 0; k < pinned_.size(); ++k) {
    if (pinned_[k] < 0 || pinned_[k] >= n_) {
      fail(ErrorCode::BadParameter, "pinned vertex " + std::to_string(pinned_[k]) +
                                        " is out of range (the mesh has " + std::to_string(n_) + " vertices)");
    }
    im.pinned_index[pinned_[k]] = static_cast<int>(k);
  }
  for (int i = 0; i < n_; ++i) {
    if (im.pinned_index[i] < 0) {
      im.free_of[i] = static_cast<int>(im.free_vertices.size());
      im.free_vertices.push_back(i);
    }
  }
  require_pin_per_component(L, im.pinned_index);
  plan(L, earlier);
}

void LaplacianSolver::plan(const Eigen::SparseMatrix<double>& L, const SupernodalPlan* earlier) {
  Impl& im = *impl_;
  const int nf = static_cast<int>(im.free_vertices.size());
  const int nc = static_cast<int>(pinned_.size());
  std::vector<Eigen::Triplet<double>> ff, fc;
  ff.reserve(static_cast<std::size_t>(L.nonZeros()));
  for (int col = 0; col < L.outerSize(); ++col) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(L, col); it; ++it) {
      const int r = static_cast<int>(it.row());
      const int fr = im.free_of[r];
      if (fr < 0) continue;
      const int fcol = im.free_of[col];
      if (fcol >= 0) {
        if (fr >= fcol) ff.emplace_back(fr, fcol, it.value());  // lower triangle is enough
      } else {
        fc.emplace_back(fr, im.pinned_index[col], it.value());
      }
    }
  }
  Eigen::SparseMatrix<double> Lff(nf, nf);
  Lff.setFromTriplets(ff.begin(), ff.end());
  im.L_fc.resize(nf, nc);
  im.L_fc.setFromTriplets(fc.begin(), fc.end());
  if (nf == 0) return;
  im.pivot_floor = 1e-13 * Lff.diagonal().cwiseAbs().maxCoeff();
  im.plan = earlier ? std::make_shared<SupernodalPlan>(*earlier, Lff) : std::make_shared<SupernodalPlan>(Lff);
}

const std::shared_ptr<SupernodalPlan>& LaplacianSolver::plan() const { return impl_->plan; }

void LaplacianSolver::factorize(const std::function<void(double)>& progress) { factorize_until(1.0, progress); }

bool LaplacianSolver::factorize_until(double until, const std::function<void(double)>& progress) {
  Impl& im = *impl_;
  if (im.factorized) return true;
  const int nf = static_cast<int>(im.free_vertices.size());
  if (nf == 0) {
    im.factorized = true;
    return true;
  }
  if (!im.plan->factor_until(im.pivot_floor, until, progress)) return false;
  SupernodalLdlt ldlt = im.plan->take_factor();
  // The factor is of P L_ff P^T: free index i sits at position ldlt.perm[i].
  std::vector<int> perm(nf);
  for (int i = 0; i < nf; ++i) perm[ldlt.perm[i]] = i;
  if (ldlt.bad_pivot >= 0) {  // the solver keeps its last factorization
    fail(ErrorCode::Numerical,
         "the Laplacian is singular near vertex " + std::to_string(im.free_vertices[perm[ldlt.bad_pivot]]) +
             ": its component has no pinned vertex or only degenerate triangles");
  }
  im.vertex_at.resize(nf);
  im.band_positions.clear();
  im.band_offsets.assign(1, 0);
  im.band_vertices.clear();
  im.band_values.clear();
  for (int pos = 0; pos < nf; ++pos) {
    im.vertex_at[pos] = im.free_vertices[perm[pos]];
    Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(im.L_fc, perm[pos]);
    if (!it) continue;
    for (; it; ++it) {  // ascending pinned index: the order the sum is taken in
      im.band_vertices.push_back(pinned_[static_cast<std::size_t>(it.col())]);
      im.band_values.push_back(it.value());
    }
    im.band_positions.push_back(pos);
    im.band_offsets.push_back(static_cast<int>(im.band_vertices.size()));
  }
  im.inv_d = ldlt.d.cwiseInverse();
  im.factor = std::move(ldlt.L);
  // The plan goes (a LaplacianPatterns may keep its ordering, without the values).
  im.plan->release_values();
  im.plan.reset();
  im.L_fc = {};
  im.factorized = true;
  return true;
}

LaplacianSolver::~LaplacianSolver() = default;

// The shared body of both solve() overloads; B and X are #V by k dense
// matrices of any storage order.
template <typename B, typename X>
void solve_pinned(const LaplacianSolver::Impl& im, const B& b, X& x) {
  const int nf = static_cast<int>(im.free_vertices.size());
  const int k = static_cast<int>(b.cols());
  if (nf == 0) return;
  using RowMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  // Right-hand side of the free rows in factor order, minus the pinned columns' contribution.
  RowMatrix rhs(nf, k);
  // Positions (#V by 3, row-major) are gathered and scattered by pointer:
  // Eigen's row copies of a runtime width k cost as much again in WASM
  // (koala 200k: 7 % of an L-BFGS iteration, a fifth of the solve's own).
  constexpr bool rows_of_three = B::IsRowMajor && X::IsRowMajor && B::ColsAtCompileTime == 3 &&
                                 X::ColsAtCompileTime == 3;
  if constexpr (rows_of_three) {
    const double* from = b.data();
    double* to = rhs.data();
    for (int pos = 0; pos < nf; ++pos) {
      const double* row = from + 3 * static_cast<std::ptrdiff_t>(im.vertex_at[pos]);
      to[3 * pos] = row[0];
      to[3 * pos + 1] = row[1];
      to[3 * pos + 2] = row[2];
    }
  } else {
    for (int pos = 0; pos < nf; ++pos) rhs.row(pos) = b.row(im.vertex_at[pos]);
  }
  Eigen::RowVectorXd coupled(k);
  for (std::size_t r = 0; r < im.band_positions.size(); ++r) {
    coupled.setZero();
    for (int e = im.band_offsets[r]; e < im.band_offsets[r + 1]; ++e) {
      coupled += im.band_values[e] * x.row(im.band_vertices[e]);
    }
    rhs.row(im.band_positions[r]) -= coupled;
  }
  if (k >= 1 && k <= 3) {
    im.factor.solve(im.inv_d, rhs.data(), k);
  } else {
    for (int c = 0; c < k; ++c) {
      Eigen::VectorXd col = rhs.col(c);
      im.factor.solve(im.inv_d, col.data(), 1);
      rhs.col(c) = col;
    }
  }
  if constexpr (rows_of_three) {
    const double* from = rhs.data();
    double* to = x.data();
    for (int pos = 0; pos < nf; ++pos) {
      double* row = to + 3 * static_cast<std::ptrdiff_t>(im.vertex_at[pos]);
      row[0] = from[3 * pos];
      row[1] = from[3 * pos + 1];
      row[2] = from[3 * pos + 2];
    }
  } else {
    for (int pos = 0; pos < nf; ++pos) x.row(im.vertex_at[pos]) = rhs.row(pos);
  }
}

void LaplacianSolver::solve(const Eigen::Ref<const Eigen::MatrixXd>& b,
                            Eigen::Ref<Eigen::MatrixXd> x) const {
  solve_pinned(*impl_, b, x);
}

void LaplacianSolver::solve(const Positions& b, Positions& x) const {
  solve_pinned(*impl_, b, x);
}

}  // namespace aniso
