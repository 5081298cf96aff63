#include "geometry/supernodal_ldlt.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstddef>
#include <memory>
#include <type_traits>

#include <Eigen/Dense>
#include <Eigen/OrderingMethods>

#include "base/product_kernel.h"
#include "geometry/nested_dissection.h"

namespace aniso {

// The symbolic factorization of C = P A P^T (upper triangle U, by columns):
// the elimination tree, each column's count of entries below the diagonal,
// the supernodes, and each supernode's rows.
struct SupernodalStructure {
  std::vector<int> parent, count;
  std::vector<int> first_column, supernode_of;  // supernode of each column
  std::vector<int> row_offsets, rows;           // per supernode: its own columns, then R
  std::vector<std::size_t> panel_offsets;       // per supernode: its m-by-w panel
};

namespace {

using Permutation = Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int>;

// Columns of a supernode factored together (factor_panels).
constexpr int kPanelBlock = 32;
// Kept analyses of at least this many rows also try nested dissection
// (SupernodalAnalysis): below it, AMD's fill is small either way.
constexpr int kDissectionFrom = 1000;

// A dense matrix in memory kept from one use to the next: an Eigen matrix
// reallocates whenever its size changes, and the factorization's scratch
// changes size with every supernode (for the flattening refinement's system,
// allocations and frees were 2.5 % of a WASM flatten).
template <typename Scalar>
class Scratch {
 public:
  using Shaped = Eigen::Map<Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>>;
  Shaped shaped(Eigen::Index rows, Eigen::Index cols) {
    if (memory_.size() < static_cast<std::size_t>(rows * cols)) memory_.resize(static_cast<std::size_t>(rows * cols));
    return Shaped(memory_.data(), rows, cols);
  }

 private:
  std::vector<Scalar> memory_;
};

// out = A B^H, A and B column blocks of panels (B's rows: out's columns),
// out in `memory`; for doubles by base/product_kernel.h, and with `lower`
// only as much as its lower triangle needs (the rest is left undefined).
template <typename BlockA, typename MatrixB, typename Scalar>
typename Scratch<Scalar>::Shaped product(const BlockA& A, const MatrixB& B, Scratch<Scalar>& memory,
                                         bool lower = false) {
  typename Scratch<Scalar>::Shaped out = memory.shaped(A.rows(), B.rows());
  if constexpr (std::is_same_v<Scalar, double>) {
    multiply_by_transpose(A.data(), static_cast<int>(A.outerStride()), B.data(), static_cast<int>(B.rows()),
                          static_cast<int>(A.rows()), static_cast<int>(B.rows()), static_cast<int>(A.cols()),
                          out.data(), static_cast<int>(A.rows()), lower);
  } else {
    out.noalias() = A * B.adjoint();
  }
  return out;
}

// C's upper triangle by columns.
template <typename Scalar>
Eigen::SparseMatrix<Scalar> permuted_upper(const Eigen::SparseMatrix<Scalar>& A, const Permutation& P) {
  Eigen::SparseMatrix<Scalar> U(A.rows(), A.cols());
  U.template selfadjointView<Eigen::Upper>() = A.template selfadjointView<Eigen::Lower>().twistedBy(P);
  return U;
}

// Visits the columns j < k with L(k, j) != 0 (row k's subtree of the
// elimination tree, Liu 1986), in no particular order.
template <typename Visit>
void row_pattern(const Eigen::SparseMatrix<double>& U, const std::vector<int>& parent, int k,
                 std::vector<int>& mark, const Visit& visit) {
  mark[k] = k;
  for (Eigen::SparseMatrix<double>::InnerIterator it(U, k); it; ++it) {
    for (int j = static_cast<int>(it.row()); j < k && mark[j] != k; j = parent[j]) {
      mark[j] = k;
      visit(j);
    }
  }
}

SupernodalStructure analyse(const Eigen::SparseMatrix<double>& U) {
  const int n = static_cast<int>(U.cols());
  SupernodalStructure s;
  // Elimination tree (Liu's algorithm with path compression).
  s.parent.assign(n, -1);
  std::vector<int> ancestor(n, -1);
  for (int k = 0; k < n; ++k) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(U, k); it; ++it) {
      for (int i = static_cast<int>(it.row()); i != -1 && i < k;) {
        const int next = ancestor[i];
        ancestor[i] = k;
        if (next == -1) s.parent[i] = k;
        i = next;
      }
    }
  }
  s.count.assign(n, 0);
  std::vector<int> mark(n, -1);
  for (int k = 0; k < n; ++k) row_pattern(U, s.parent, k, mark, [&](int j) { ++s.count[j]; });
  // Fundamental supernodes: column j + 1 continues j's when it is j's parent
  // and j has one entry more (j's pattern less row j + 1 lies in its
  // parent's, so equal counts make the patterns below equal).
  s.first_column.push_back(0);
  for (int j = 0; j + 1 < n; ++j) {
    if (!(s.parent[j] == j + 1 && s.count[j] == s.count[j + 1] + 1)) s.first_column.push_back(j + 1);
  }
  if (n > 0) s.first_column.push_back(n);
  const int supernodes = static_cast<int>(s.first_column.size()) - 1;
  s.supernode_of.resize(n);
  s.row_offsets.assign(1, 0);
  s.panel_offsets.assign(1, 0);
  for (int J = 0; J < supernodes; ++J) {
    const int c0 = s.first_column[J], w = s.first_column[J + 1] - c0;
    for (int j = c0; j < c0 + w; ++j) s.supernode_of[j] = J;
    const int m = s.count[c0] + 1;  // its first column, diagonal included
    s.row_offsets.push_back(s.row_offsets.back() + m);
    s.panel_offsets.push_back(s.panel_offsets.back() + static_cast<std::size_t>(m) * w);
  }
  // Each supernode's rows: its first column's pattern, ascending (rows k
  // arrive in order).
  s.rows.resize(s.row_offsets.back());
  std::vector<int> filled(s.row_offsets.begin(), s.row_offsets.end() - 1);
  for (int J = 0; J < supernodes; ++J) s.rows[filled[J]++] = s.first_column[J];
  std::fill(mark.begin(), mark.end(), -1);
  for (int k = 0; k < n; ++k) {
    row_pattern(U, s.parent, k, mark, [&](int j) {
      const int J = s.supernode_of[j];
      if (s.first_column[J] == j) s.rows[filled[J]++] = k;
    });
  }
  return s;
}

// The ordering as Eigen's SimplicialLDLT makes it (AMD on the full pattern
// of A's lower triangle, into P), and the analysis of P A P^T.
SupernodalStructure order_and_analyse(const Eigen::SparseMatrix<double>& A, Permutation& P) {
  Permutation Pinv;
  {
    const Eigen::SparseMatrix<double> full = A.selfadjointView<Eigen::Lower>();
    Eigen::AMDOrdering<int>()(full, Pinv);
  }
  P = Pinv.inverse();
  return analyse(permuted_upper(A, P));
}

// The work of a factorization with this structure, to compare orderings by:
// a column with c entries below the diagonal takes about c^2 multiply-adds.
double factor_work(const SupernodalStructure& s) {
  double work = 0.0;
  for (const int c : s.count) work += static_cast<double>(c) * c;
  return work;
}

}  // namespace

struct SupernodalSymbolic {
  Permutation P;
  SupernodalStructure s;
  bool nested_dissection = false;
  // C = P A P^T's lower triangle by columns, and for each of its entries the
  // entry of A it comes from: a factorization of new values gathers them
  // instead of permuting A again (the flattening refinement factors once
  // per step). Used when A is compressed with the analysed count of entries.
  // Both are scratch of factor(): one analysis factors one matrix at a time.
  Eigen::SparseMatrix<double> C;
  std::vector<int> source;
  Eigen::Index entries = -1;
  // The panels' memory, kept from one factorization to the next.
  std::vector<double> panels;
};

SupernodalAnalysis::SupernodalAnalysis(const Eigen::SparseMatrix<double>& A)
    : symbolic_(std::make_unique<SupernodalSymbolic>()) {
  SupernodalSymbolic& sym = *symbolic_;
  sym.s = order_and_analyse(A, sym.P);
  // A kept analysis factors many times (the flattening's refinement: once a
  // step, over a hundred times on a large patch), so the ordering may cost
  // more than AMD's: nested dissection is tried too, and the one whose
  // factorization takes fewer operations kept. On the refinement's systems
  // dissection saves a quarter to a half of the operations on most patches
  // (the koala's head: 1.85e9 -> 1.03e9 a factorization, its flatten 56 ->
  // 38 s natively); AMD stays ahead on small ones (the hand's, 1,618 rows).
  if (A.cols() >= kDissectionFrom) {
    Permutation dissection_inverse(static_cast<int>(A.cols()));
    const std::vector<int> order = nested_dissection_order(A);
    std::copy(order.begin(), order.end(), dissection_inverse.indices().data());
    const Permutation dissection = dissection_inverse.inverse();
    SupernodalStructure dissected = analyse(permuted_upper(A, dissection));
    if (factor_work(dissected) < factor_work(sym.s)) {
      sym.P = dissection;
      sym.s = std::move(dissected);
      sym.nested_dissection = true;
    }
  }
  if (!A.isCompressed()) return;
  // A's entries numbered (exactly: doubles hold integers to 2^53) and
  // permuted as factor_panels permutes values.
  Eigen::SparseMatrix<double> numbered = A;
  for (Eigen::Index k = 0; k < numbered.nonZeros(); ++k) numbered.valuePtr()[k] = static_cast<double>(k);
  sym.C = permuted_upper(numbered, sym.P).adjoint();
  sym.source.assign(sym.C.valuePtr(), sym.C.valuePtr() + sym.C.nonZeros());
  sym.entries = A.nonZeros();
}

SupernodalAnalysis::~SupernodalAnalysis() = default;

bool SupernodalAnalysis::nested_dissection() const { return symbolic_->nested_dissection; }

// factor_panels' return when a factorization in parts has more to do.
constexpr int kUnfinished = -2;

// A factorization in parts: factor_panels' loop between calls (outside the
// anonymous namespace: SupernodalPlan::Partial holds one).
struct PanelLoop {
  // Left-looking: the supernodes K whose rows reach supernode J wait in J's
  // list; next_row[K] is K's first row position not used yet.
  std::vector<int> head, next, next_row;
  int next_supernode = 0;
  double work_done = 0.0, next_report = 0.05;
};

namespace {

// The numeric factorization P A P^T = L D L^H on the analysed pattern, from
// C = P A P^T's lower triangle by columns, into panels (each supernode's
// m-by-w block of L, column-major, its rows as SupernodalStructure::rows) and
// the real pivots d. Returns the first column whose pivot fails the test
// (above pivot_floor, or for `any_sign` above it in magnitude), or -1; or,
// given `parts` (a factorization in parts), kUnfinished once the supernodes
// done reach the share `until` of the work (at least one a call), to go on
// from there at the next call.
template <typename Scalar>
int factor_panels(const SupernodalStructure& s, const Eigen::SparseMatrix<Scalar>& C, double pivot_floor,
                  bool any_sign, Scalar* panels, Eigen::VectorXd& d, const FactorProgress& progress = {},
                  PanelLoop* parts = nullptr, double until = 1.0) {
  using Matrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;
  using PanelOf = Eigen::Map<Matrix, 0, Eigen::OuterStride<>>;
  const int n = static_cast<int>(C.cols());
  const int supernodes = static_cast<int>(s.first_column.size()) - 1;
  PanelLoop whole;
  PanelLoop& loop = parts ? *parts : whole;
  if (loop.next_supernode == 0) {
    d.setZero(n);
    loop.head.assign(supernodes, -1);
    loop.next.assign(supernodes, -1);
    loop.next_row.assign(supernodes, 0);
  }
  std::vector<int>& head = loop.head;
  std::vector<int>& next = loop.next;
  std::vector<int>& next_row = loop.next_row;
  std::vector<int> local(n, -1);  // row -> its position in the current supernode
  std::vector<int> place;
  Scratch<Scalar> update_memory, scaled_memory, weighted_memory, column_memory;
  // Progress by the work done (factor_work), reported at each twentieth.
  const double total_work = progress || parts ? factor_work(s) : 0.0;
  double& work_done = loop.work_done;
  double& next_report = loop.next_report;
  const int first = loop.next_supernode;
  for (int J = first; J < supernodes; ++J) {
    // (Not at `until` 1: the last supernodes may add no work, and would be left undone.)
    if (parts && until < 1.0 && J > first && work_done >= until * total_work) {
      loop.next_supernode = J;
      return kUnfinished;
    }
    const int c0 = s.first_column[J], w = s.first_column[J + 1] - c0;
    const int m = s.row_offsets[J + 1] - s.row_offsets[J];
    const int* rows = s.rows.data() + s.row_offsets[J];
    for (int p = 0; p < m; ++p) local[rows[p]] = p;
    // Each panel is zeroed when its supernode comes, not all at once: the
    // memory is touched first where it is used.
    PanelOf X(panels + s.panel_offsets[J], m, w, Eigen::OuterStride<>(m));
    X.setZero();
    for (int k = 0; k < w; ++k) {
      for (typename Eigen::SparseMatrix<Scalar>::InnerIterator it(C, c0 + k); it; ++it) {
        X(local[it.row()], k) += it.value();
      }
    }
    // X -= L_K D_K L_K^H on the rows of K that reach J, for each K waiting.
    while (head[J] != -1) {
      const int K = head[J];
      head[J] = next[K];
      const int kw = s.first_column[K + 1] - s.first_column[K];
      const int km = s.row_offsets[K + 1] - s.row_offsets[K];
      const int* krows = s.rows.data() + s.row_offsets[K];
      const int p0 = next_row[K];
      int p1 = p0;
      while (p1 < km && krows[p1] < c0 + w) ++p1;
      const PanelOf LK(panels + s.panel_offsets[K], km, kw, Eigen::OuterStride<>(km));
      const auto dK = d.segment(s.first_column[K], kw).template cast<Scalar>();
      auto scaled = scaled_memory.shaped(p1 - p0, kw);
      scaled.noalias() = LK.middleRows(p0, p1 - p0) * dK.asDiagonal();
      // Only its lower triangle is subtracted below.
      const auto update = product(LK.middleRows(p0, km - p0), scaled, update_memory, true);
      // Each row of the update's place in J's panel, found once for all
      // its columns.
      const int reach = km - p0;
      place.resize(reach);
      for (int a = 0; a < reach; ++a) place[a] = local[krows[p0 + a]];
      for (int b = 0; b < p1 - p0; ++b) {
        Scalar* column = &X(0, krows[p0 + b] - c0);
        const Scalar* from = &update(0, b);
        for (int a = b; a < reach; ++a) column[place[a]] -= from[a];
      }
      next_row[K] = p1;
      if (p1 < km) {
        const int target = s.supernode_of[krows[p1]];
        next[K] = head[target];
        head[target] = K;
      }
    }
    // The panel's own LDL^H by blocks of kPanelBlock columns: the columns
    // before a block update it in one matrix product, then its columns are
    // factored one by one against each other. Column by column against all
    // the columns before, the wide supernodes at the top of the tree were
    // matrix-vector products, one double at a time in WASM.
    for (int k0 = 0; k0 < w; k0 += kPanelBlock) {
      const int k1 = std::min(w, k0 + kPanelBlock);
      if (k0 > 0) {
        auto scaled = scaled_memory.shaped(k1 - k0, k0);
        scaled.noalias() = X.block(k0, 0, k1 - k0, k0) * d.segment(c0, k0).template cast<Scalar>().asDiagonal();
        X.block(k0, k0, m - k0, k1 - k0) -= product(X.block(k0, 0, m - k0, k0), scaled, update_memory);
      }
      for (int k = k0; k < k1; ++k) {
        if (k > k0) {
          auto weighted = weighted_memory.shaped(k - k0, 1);
          weighted.noalias() =
              X.block(k, k0, 1, k - k0).adjoint().cwiseProduct(d.segment(c0 + k0, k - k0).template cast<Scalar>());
          if constexpr (std::is_same_v<Scalar, double>) {
            // The product kernel's last-column loop: each row's sum in
            // Eigen's order, eight rows at a time (Eigen's matrix-vector
            // product runs one double at a time in WASM).
            X.block(k, k, m - k, 1) -= product(X.block(k, k0, m - k, k - k0), weighted.transpose(), column_memory);
          } else {
            X.block(k, k, m - k, 1).noalias() -= X.block(k, k0, m - k, k - k0) * weighted;
          }
        }
        const double pivot = Eigen::numext::real(X(k, k));
        if (!((any_sign ? std::abs(pivot) : pivot) > pivot_floor)) return c0 + k;
        d[c0 + k] = pivot;
        // One division, then multiplications: a division per entry of L was
        // a tenth of this function's time.
        X.block(k + 1, k, m - k - 1, 1) *= Scalar(1.0 / pivot);
      }
    }
    if (w < m) {
      next_row[J] = w;
      const int target = s.supernode_of[rows[w]];
      next[J] = head[target];
      head[target] = J;
    }
    if (progress || parts) {
      for (int c = c0; c < c0 + w; ++c) work_done += static_cast<double>(s.count[c]) * s.count[c];
      if (progress && total_work > 0.0 && work_done >= next_report * total_work && J + 1 < supernodes) {
        const double share = std::floor(20.0 * work_done / total_work) / 20.0;
        progress(kAnalysedShare + (1.0 - kAnalysedShare) * share);
        next_report = share + 0.05;
      }
    }
  }
  loop.next_supernode = supernodes;
  return -1;
}

// P A P^T = L D L^T from C = P A P^T's lower triangle by columns, into
// `panels` (scratch of the structure's size), then the solves' layout, in
// `result`'s memory. Given `parts`, only up to the share `until` of the
// work (factor_panels): returns whether it is finished.
bool factor_lower(const SupernodalStructure& s, const Permutation& P, const Eigen::SparseMatrix<double>& C,
                  double pivot_floor, std::vector<double>& panels, SupernodalLdlt& result,
                  const FactorProgress& progress = {}, PanelLoop* parts = nullptr, double until = 1.0) {
  const int n = static_cast<int>(C.cols());
  if (!parts || parts->next_supernode == 0) {
    result.perm.assign(P.indices().data(), P.indices().data() + n);
    panels.resize(s.panel_offsets.back());
  }
  const int status = factor_panels(s, C, pivot_floor, false, panels.data(), result.d, progress, parts, until);
  if (status == kUnfinished) return false;
  result.bad_pivot = status;
  if (status < 0) result.L.assign(n, s.first_column, s.row_offsets, s.rows, s.panel_offsets, panels.data());
  return true;
}

}  // namespace

SupernodalLdlt SupernodalAnalysis::factor(const Eigen::SparseMatrix<double>& A, double pivot_floor) const {
  SupernodalLdlt result;
  factor(A, pivot_floor, result);
  return result;
}

void SupernodalAnalysis::factor(const Eigen::SparseMatrix<double>& A, double pivot_floor,
                                SupernodalLdlt& result) const {
  SupernodalSymbolic& sym = *symbolic_;
  if (!A.isCompressed() || A.nonZeros() != sym.entries) {
    factor_lower(sym.s, sym.P, permuted_upper(A, sym.P).adjoint(), pivot_floor, sym.panels, result);
    return;
  }
  const double* values = A.valuePtr();
  double* gathered = sym.C.valuePtr();
  for (std::size_t k = 0; k < sym.source.size(); ++k) gathered[k] = values[sym.source[k]];
  factor_lower(sym.s, sym.P, sym.C, pivot_floor, sym.panels, result);
}

struct SupernodalPlan::Pattern {
  Permutation P;
  SupernodalStructure s;
  // A's compressed pattern, to tell whether a matrix has it.
  Eigen::Index rows = 0;
  std::vector<int> outer, inner;
  // C's pattern, each value the number of the entry of A it comes from
  // (exact: doubles hold integers to 2^53); made at the first reuse.
  Eigen::SparseMatrix<double> numbered;

  bool fits(const Eigen::SparseMatrix<double>& A) const {
    return !outer.empty() && A.isCompressed() && A.rows() == rows && A.cols() == rows &&
           static_cast<std::size_t>(A.nonZeros()) == inner.size() &&
           std::equal(outer.begin(), outer.end(), A.outerIndexPtr()) &&
           std::equal(inner.begin(), inner.end(), A.innerIndexPtr());
  }
};

SupernodalPlan::SupernodalPlan(const Eigen::SparseMatrix<double>& A) { plan_afresh(A); }

SupernodalPlan::SupernodalPlan(const SupernodalPlan& earlier, const Eigen::SparseMatrix<double>& A) {
  Pattern& pattern = *earlier.pattern_;
  if (!pattern.fits(A)) {
    plan_afresh(A);
    return;
  }
  if (pattern.numbered.nonZeros() == 0) {
    Eigen::SparseMatrix<double> numbered = A;
    for (Eigen::Index k = 0; k < numbered.nonZeros(); ++k) numbered.valuePtr()[k] = static_cast<double>(k);
    pattern.numbered = permuted_upper(numbered, pattern.P).adjoint();
  }
  C_ = pattern.numbered;
  const double* values = A.valuePtr();
  double* gathered = C_.valuePtr();
  for (Eigen::Index k = 0; k < C_.nonZeros(); ++k) gathered[k] = values[static_cast<Eigen::Index>(gathered[k])];
  pattern_ = earlier.pattern_;
  reused_ = true;
}

void SupernodalPlan::plan_afresh(const Eigen::SparseMatrix<double>& A) {
  pattern_ = std::make_shared<Pattern>();
  pattern_->s = order_and_analyse(A, pattern_->P);
  C_ = permuted_upper(A, pattern_->P).adjoint();
  if (!A.isCompressed()) return;  // never fits: no reuse
  pattern_->rows = A.rows();
  pattern_->outer.assign(A.outerIndexPtr(), A.outerIndexPtr() + A.cols() + 1);
  pattern_->inner.assign(A.innerIndexPtr(), A.innerIndexPtr() + A.nonZeros());
}

// A factorization in parts (factor_until): its panels and loop between calls.
struct SupernodalPlan::Partial {
  std::vector<double> panels;
  PanelLoop loop;
  SupernodalLdlt result;
};

SupernodalPlan::~SupernodalPlan() = default;

bool SupernodalPlan::factor_until(double pivot_floor, double until, const FactorProgress& progress) {
  if (!partial_) partial_ = std::make_unique<Partial>();
  return factor_lower(pattern_->s, pattern_->P, C_, pivot_floor, partial_->panels, partial_->result, progress,
                      &partial_->loop, until);
}

SupernodalLdlt SupernodalPlan::take_factor() {
  SupernodalLdlt result = std::move(partial_->result);
  partial_.reset();
  return result;
}

void SupernodalPlan::release_values() {
  C_ = Eigen::SparseMatrix<double>();
  partial_.reset();
}

SupernodalLdlt supernodal_ldlt(const Eigen::SparseMatrix<double>& A, double pivot_floor,
                               const FactorProgress& progress) {
  SupernodalPlan plan(A);
  if (progress) progress(kAnalysedShare);
  plan.factor_until(pivot_floor, 1.0, progress);
  return plan.take_factor();
}

template <typename Scalar>
int supernodal_solve(const Eigen::SparseMatrix<Scalar>& A, double pivot_floor,
                     Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>& X) {
  using Matrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;
  using PanelOf = Eigen::Map<const Matrix, 0, Eigen::OuterStride<>>;
  const int n = static_cast<int>(A.cols());
  Permutation P;
  const SupernodalStructure s = order_and_analyse(A.real(), P);  // the pattern is all it reads
  const std::unique_ptr<Scalar[]> panels(new Scalar[s.panel_offsets.back()]);
  Eigen::VectorXd d;
  const int bad = factor_panels(s, Eigen::SparseMatrix<Scalar>(permuted_upper(A, P).adjoint()), pivot_floor, true,
                                panels.get(), d);
  if (bad >= 0) return bad;
  Matrix Y(n, X.cols());
  for (int i = 0; i < n; ++i) Y.row(P.indices()[i]) = X.row(i);
  const int supernodes = static_cast<int>(s.first_column.size()) - 1;
  Matrix t;
  for (int J = 0; J < supernodes; ++J) {  // L z = y
    const int c0 = s.first_column[J], w = s.first_column[J + 1] - c0;
    const int m = s.row_offsets[J + 1] - s.row_offsets[J];
    const int* rows = s.rows.data() + s.row_offsets[J];
    const PanelOf L(panels.get() + s.panel_offsets[J], m, w, Eigen::OuterStride<>(m));
    L.topRows(w).template triangularView<Eigen::UnitLower>().solveInPlace(Y.middleRows(c0, w));
    t.noalias() = L.bottomRows(m - w) * Y.middleRows(c0, w);
    for (int i = 0; i < m - w; ++i) Y.row(rows[w + i]) -= t.row(i);
  }
  for (int j = 0; j < n; ++j) Y.row(j) /= Scalar(d[j]);
  for (int J = supernodes - 1; J >= 0; --J) {  // L^H x = z
    const int c0 = s.first_column[J], w = s.first_column[J + 1] - c0;
    const int m = s.row_offsets[J + 1] - s.row_offsets[J];
    const int* rows = s.rows.data() + s.row_offsets[J];
    const PanelOf L(panels.get() + s.panel_offsets[J], m, w, Eigen::OuterStride<>(m));
    t.resize(m - w, Y.cols());
    for (int i = 0; i < m - w; ++i) t.row(i) = Y.row(rows[w + i]);
    Y.middleRows(c0, w).noalias() -= L.bottomRows(m - w).adjoint() * t;
    L.topRows(w).template triangularView<Eigen::UnitLower>().adjoint().solveInPlace(Y.middleRows(c0, w));
  }
  for (int i = 0; i < n; ++i) X.row(i) = Y.row(P.indices()[i]);
  return -1;
}

template int supernodal_solve<double>(const Eigen::SparseMatrix<double>&, double, Eigen::MatrixXd&);
template int supernodal_solve<std::complex<double>>(const Eigen::SparseMatrix<std::complex<double>>&, double,
                                                    Eigen::MatrixXcd&);

}  // namespace aniso
