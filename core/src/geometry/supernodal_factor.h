// The triangular sweeps of an LDL^T solve, by supernodes of the unit lower
// factor L (supernodal_ldlt.h builds it).
//
// A supernode is a run of consecutive columns c0..c0+w-1 whose patterns
// below the run are one row set R: each column's first entry is the next
// column, and it has one entry more than the next. Its values are a small
// unit lower triangle and a dense r-by-w block (r = |R|), kept here by rows,
// in groups of rows read together (supernodal_factor.cpp, the block layout).
// Why: the simplicial sweep reads a row index and updates one scattered row
// of the right-hand side per nonzero; here a row of R costs one index and
// one scattered update for all w columns, and the multiply-adds run over
// contiguous values. An ARAP iteration is mostly these sweeps (on the 50k
// cylinder they take 1.5 times less than the simplicial ones).
#pragma once

#include <cstddef>
#include <memory>
#include <utility>
#include <vector>

#include <Eigen/SparseCore>

namespace aniso {

class SupernodalFactor {
 public:
  SupernodalFactor() = default;
  // From the panels of a supernodal factorization (supernodal_ldlt.h):
  // supernode s covers columns first_column[s] .. first_column[s+1]-1, its
  // rows (its own w columns' first, then R, ascending) are
  // rows[row_offsets[s] .. row_offsets[s+1]-1], and its panel, column-major
  // with that many rows, starts at panels + panel_offsets[s] and holds L
  // below the diagonal.
  SupernodalFactor(int n, const std::vector<int>& first_column, const std::vector<int>& row_offsets,
                   const std::vector<int>& rows, const std::vector<std::size_t>& panel_offsets,
                   const double* panels);
  // The same, in this factor's memory (kept from one factorization to the
  // next: the flattening refinement factors once per step, and a new
  // factor's memory, 37 MB on the bunny's patch, came fresh from the system
  // every time under the sanitizers).
  void assign(int n, const std::vector<int>& first_column, const std::vector<int>& row_offsets,
              const std::vector<int>& rows, const std::vector<std::size_t>& panel_offsets, const double* panels);

  // Solves L D L^T x = b in place on y (n rows of 1, 2 or 3 `columns`,
  // row-major), with inv_d = 1 / diag(D).
  void solve(const Eigen::VectorXd& inv_d, double* y, int columns) const;

  int size() const { return n_; }
  int supernodes() const { return first_column_.empty() ? 0 : static_cast<int>(first_column_.size()) - 1; }

 private:
  template <int K>
  void sweeps(const Eigen::VectorXd& inv_d, double* y) const;
  // Writes supernode s's values from its panel (m rows: its own w
  // columns', then R's r = m - w, column-major) into values_ from `stored`,
  // and advances it past them.
  void store(int s, const int* R, int r, const double* panel, int m, std::size_t& stored);

  int n_ = 0;
  int widest_ = 0;
  std::vector<int> first_column_;    // supernode s: columns first_column_[s] .. first_column_[s+1]-1
  std::vector<int> row_start_;       // its rows R: rows_[row_start_[s] .. row_start_[s+1]-1]
  std::vector<int> rows_;
  std::vector<int> triangle_start_;  // its triangle, column by column (column k: the w-1-k entries below k)
  std::vector<int> block_start_;     // its r-by-w block, by groups of rows
  // Written once, value by value, by store(): an allocator that leaves a
  // resize's new values uninitialized instead of zeroing them first (the
  // flattening refinement builds a factor per step, and the zeroing was
  // 2 % of a WASM flatten).
  template <typename T>
  struct Uninitialized : std::allocator<T> {
    template <typename U>
    struct rebind {
      using other = Uninitialized<U>;
    };
    Uninitialized() = default;
    template <typename U>
    Uninitialized(const Uninitialized<U>&) {}
    template <typename U>
    void construct(U* p) {
      ::new (static_cast<void*>(p)) U;
    }
    template <typename U, typename... Args>
    void construct(U* p, Args&&... args) {
      ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
    }
  };
  std::vector<double, Uninitialized<double>> values_;
};

}  // namespace aniso
