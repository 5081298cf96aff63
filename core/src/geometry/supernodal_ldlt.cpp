#include "geometry/supernodal_ldlt.h"

#include <algorithm>
#include <cstddef>
#include <memory>

#include <Eigen/Dense>
#include <Eigen/OrderingMethods>

namespace aniso {

namespace {

using Panel = Eigen::Map<Eigen::MatrixXd, 0, Eigen::OuterStride<>>;
using Permutation = Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int>;

// The symbolic factorization of C = P A P^T (upper triangle U, by columns):
// the elimination tree, each column's count of entries below the diagonal,
// the supernodes, and each supernode's rows.
struct Symbolic {
  std::vector<int> parent, count;
  std::vector<int> first_column, supernode_of;  // supernode of each column
  std::vector<int> row_offsets, rows;           // per supernode: its own columns, then R
  std::vector<std::size_t> panel_offsets;       // per supernode: its m-by-w panel
};

// C's upper triangle by columns.
Eigen::SparseMatrix<double> permuted_upper(const Eigen::SparseMatrix<double>& A, const Permutation& P) {
  Eigen::SparseMatrix<double> U(A.rows(), A.cols());
  U.selfadjointView<Eigen::Upper>() = A.selfadjointView<Eigen::Lower>().twistedBy(P);
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

Symbolic analyse(const Eigen::SparseMatrix<double>& U) {
  const int n = static_cast<int>(U.cols());
  Symbolic s;
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
  // Fundamental supernodes, by the rule SupernodalFactor uses on a factor.
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

}  // namespace

struct SupernodalSymbolic {
  Permutation P;
  Symbolic s;
  Eigen::SparseMatrix<double> pattern;  // A's lower triangle as analysed (values unused)
};

SupernodalAnalysis::SupernodalAnalysis(const Eigen::SparseMatrix<double>& A)
    : symbolic_(std::make_unique<SupernodalSymbolic>()) {
  SupernodalSymbolic& sym = *symbolic_;
  sym.pattern = A.triangularView<Eigen::Lower>();
  // The ordering as Eigen's SimplicialLDLT makes it (AMD on the full pattern).
  Permutation Pinv;
  {
    const Eigen::SparseMatrix<double> full = A.selfadjointView<Eigen::Lower>();
    Eigen::AMDOrdering<int>()(full, Pinv);
  }
  sym.P = Pinv.inverse();
  sym.s = analyse(permuted_upper(A, sym.P));
}

SupernodalAnalysis::~SupernodalAnalysis() = default;

bool SupernodalAnalysis::matches(const Eigen::SparseMatrix<double>& A) const {
  const Eigen::SparseMatrix<double> lower = A.triangularView<Eigen::Lower>();
  const Eigen::SparseMatrix<double>& pattern = symbolic_->pattern;
  return lower.rows() == pattern.rows() && lower.cols() == pattern.cols() &&
         lower.nonZeros() == pattern.nonZeros() &&
         std::equal(lower.outerIndexPtr(), lower.outerIndexPtr() + lower.cols() + 1, pattern.outerIndexPtr()) &&
         std::equal(lower.innerIndexPtr(), lower.innerIndexPtr() + lower.nonZeros(), pattern.innerIndexPtr());
}

SupernodalLdlt supernodal_ldlt(const Eigen::SparseMatrix<double>& A, double pivot_floor) {
  return SupernodalAnalysis(A).factor(A, pivot_floor);
}

SupernodalLdlt SupernodalAnalysis::factor(const Eigen::SparseMatrix<double>& A, double pivot_floor) const {
  const Symbolic& s = symbolic_->s;
  const Permutation& P = symbolic_->P;
  const int n = static_cast<int>(A.cols());
  SupernodalLdlt result;
  result.perm.assign(P.indices().data(), P.indices().data() + n);
  const Eigen::SparseMatrix<double> C = permuted_upper(A, P).transpose();  // the lower triangle, by columns
  const int supernodes = static_cast<int>(s.first_column.size()) - 1;

  // Each panel is zeroed when its supernode comes, not all at once: the
  // memory is touched first where it is used.
  const std::unique_ptr<double[]> panels(new double[s.panel_offsets.back()]);
  result.d.setZero(n);
  // Left-looking: the supernodes K whose rows reach supernode J wait in J's
  // list; next_row[K] is K's first row position not used yet.
  std::vector<int> head(supernodes, -1), next(supernodes, -1), next_row(supernodes, 0);
  std::vector<int> local(n, -1);  // row -> its position in the current supernode
  Eigen::MatrixXd update, scaled;
  for (int J = 0; J < supernodes; ++J) {
    const int c0 = s.first_column[J], w = s.first_column[J + 1] - c0;
    const int m = s.row_offsets[J + 1] - s.row_offsets[J];
    const int* rows = s.rows.data() + s.row_offsets[J];
    for (int p = 0; p < m; ++p) local[rows[p]] = p;
    Panel X(panels.get() + s.panel_offsets[J], m, w, Eigen::OuterStride<>(m));
    X.setZero();
    for (int k = 0; k < w; ++k) {
      for (Eigen::SparseMatrix<double>::InnerIterator it(C, c0 + k); it; ++it) X(local[it.row()], k) += it.value();
    }
    // X -= L_K D_K L_K^T on the rows of K that reach J, for each K waiting.
    while (head[J] != -1) {
      const int K = head[J];
      head[J] = next[K];
      const int kw = s.first_column[K + 1] - s.first_column[K];
      const int km = s.row_offsets[K + 1] - s.row_offsets[K];
      const int* krows = s.rows.data() + s.row_offsets[K];
      const int p0 = next_row[K];
      int p1 = p0;
      while (p1 < km && krows[p1] < c0 + w) ++p1;
      const Panel LK(panels.get() + s.panel_offsets[K], km, kw, Eigen::OuterStride<>(km));
      const auto dK = result.d.segment(s.first_column[K], kw);
      scaled.noalias() = LK.middleRows(p0, p1 - p0) * dK.asDiagonal();
      update.noalias() = LK.middleRows(p0, km - p0) * scaled.transpose();
      for (int b = 0; b < p1 - p0; ++b) {
        const int column = krows[p0 + b] - c0;
        for (int a = b; a < km - p0; ++a) X(local[krows[p0 + a]], column) -= update(a, b);
      }
      next_row[K] = p1;
      if (p1 < km) {
        const int target = s.supernode_of[krows[p1]];
        next[K] = head[target];
        head[target] = K;
      }
    }
    // The panel's own LDL^T, column by column.
    for (int k = 0; k < w; ++k) {
      if (k > 0) {
        const Eigen::VectorXd weighted = X.block(k, 0, 1, k).transpose().cwiseProduct(result.d.segment(c0, k));
        X.block(k, k, m - k, 1).noalias() -= X.block(k, 0, m - k, k) * weighted;
      }
      const double pivot = X(k, k);
      if (!(pivot > pivot_floor)) {
        result.bad_pivot = c0 + k;
        return result;
      }
      result.d[c0 + k] = pivot;
      X.block(k + 1, k, m - k - 1, 1) /= pivot;
    }
    if (w < m) {
      next_row[J] = w;
      const int target = s.supernode_of[rows[w]];
      next[J] = head[target];
      head[target] = J;
    }
  }
  result.L = SupernodalFactor(n, s.first_column, s.row_offsets, s.rows, s.panel_offsets, panels.get());
  return result;
}

}  // namespace aniso
