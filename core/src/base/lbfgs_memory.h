// The memory of an L-BFGS iteration (Nocedal & Wright, Algorithm 7.4): the
// last few pairs of iterate changes s and gradient changes y, and the
// two-loop recursion that turns a gradient into the quasi-Newton direction
// -H g with a given initial inverse Hessian H0. One implementation for the
// AnARAP/ARAP iterations (deform/anarap_lbfgs.cpp) and the flattening's ARAP
// phase (flatten/flatten_arap.cpp), whose iterates are Eigen matrices of
// different shapes.
//
// The recursion's scalars need only the products of the pairs with each
// other, with the gradient and with H0's result (Byrd, Nocedal & Schnabel
// 1994 use the same products for their compact form): the products s_j . y_k
// (j < k) are kept as pairs come, so the direction takes four passes over
// the vectors (the products with g, -g - sum a y, the products with r0 =
// H0 q, r0 + sum c s) instead of one update of the direction per pair and
// loop (base/vector_kernels.h).
#pragma once

#include <cmath>
#include <cstddef>
#include <deque>
#include <utility>
#include <vector>

#include "base/vector_kernels.h"

namespace aniso {

template <class Matrix>
class LbfgsMemory {
 public:
  explicit LbfgsMemory(int capacity) : capacity_(capacity) {}

  bool empty() const { return steps_.empty(); }

  void clear() {
    steps_.clear();
    changes_.clear();
    curvatures_.clear();
    step_products_.clear();
    newest_products_pending_ = false;
  }

  // The pair of a step from iterate x0 to x1 with gradients g0 -> g1
  // (s = x1 - x0, y = g1 - g0), kept if its curvature s.y is clearly
  // positive (only such pairs keep H positive definite), dropping the oldest
  // when full. The gradients are L x - b with the Laplacian as H0: returns
  // the step's s.L s / s.y (L s = y + (b1 - b0) on the free rows, where s is
  // not zero), or 0 when the pair was not kept.
  // x0 may be of another matrix type with x1's size and storage order (the
  // flattening's iterate is n by 2 at compile time, its trial not).
  template <class Iterate>
  double push_step(const Iterate& x0, const Matrix& x1, const Matrix& g0, const Matrix& g1, const Matrix& b0,
                   const Matrix& b1) {
    static_assert(static_cast<bool>(Iterate::IsRowMajor) == static_cast<bool>(Matrix::IsRowMajor),
                  "x0 and x1 must store their entries in the same order");
    spare_step_.resize(x1.rows(), x1.cols());
    spare_change_.resize(x1.rows(), x1.cols());
    return keep_if_curved(step_pair(x1.data(), x0.data(), g1.data(), g0.data(), b1.data(), b0.data(),
                                    spare_step_.data(), spare_change_.data(), static_cast<std::size_t>(x1.size())));
  }

  // The same for a step s the caller holds, whose gradient change y the
  // caller writes with the products in a pass of its own (AnARAP takes the
  // new gradient in it): fill(y) writes y (s's shape) and returns s and y's
  // StepProducts. s's storage is taken (swapped with the memory's spare).
  template <class Fill>
  double push_step(Matrix& s, Fill&& fill) {
    spare_change_.resize(s.rows(), s.cols());
    const StepProducts p = fill(spare_change_);
    spare_step_.swap(s);
    return keep_if_curved(p);
  }

  // direction = -H gradient, with H0 = h0_scale M: `apply_h0(q, r)` sets
  // r = M q (r arrives as the caller's scratch matrix of q's shape). The
  // scale enters the recursion's scalars, not a pass over r.
  template <class ApplyH0>
  void direction(const Matrix& gradient, Matrix& direction, Matrix& scratch, ApplyH0&& apply_h0,
                 double h0_scale = 1.0) {
    const int m = static_cast<int>(steps_.size());
    const auto n = static_cast<std::size_t>(gradient.size());
    direction.resize(gradient.rows(), gradient.cols());
    std::vector<const double*>& s = step_data_;
    std::vector<const double*>& y = change_data_;
    s.resize(m);
    y.resize(m);
    for (int k = 0; k < m; ++k) {
      s[k] = steps_[k].data();
      y[k] = changes_[k].data();
    }
    // First loop: a_k = rho_k s_k . q_k with q_k = -g - sum_{j > k} a_j y_j,
    // from the products s_k . g (and, in the same pass, s_j . y_newest, the
    // newest pair's products if still to be taken).
    std::vector<double>& a = coefficients_;
    std::vector<double>& products = products_;
    a.resize(m);
    const double* targets[2] = {gradient.data(), m > 0 ? y[m - 1] : nullptr};
    const int num_targets = newest_products_pending_ ? 2 : 1;
    products.resize(static_cast<std::size_t>(m) * num_targets);
    dots_with(s.data(), m, targets, num_targets, products.data(), n);
    if (newest_products_pending_) {
      step_products_.back().assign(products.begin() + m, products.begin() + 2 * m - 1);
      newest_products_pending_ = false;
    }
    for (int k = m - 1; k >= 0; --k) {
      double projection = -products[k];
      for (int j = k + 1; j < m; ++j) projection -= a[j] * step_products_[j][k];
      a[k] = curvatures_[k] * projection;
    }
    negated_.resize(m);
    for (int k = 0; k < m; ++k) negated_[k] = -a[k];
    combine(direction.data(), -1.0, gradient.data(), y.data(), negated_.data(), m, n);
    // r0 = H0 q = h0_scale M q.
    apply_h0(direction, scratch);
    // Second loop: r_{k+1} = r_k + (a_k - rho_k y_k . r_k) s_k, with
    // y_k . r_k = y_k . r0 + sum_{j < k} c_j s_j . y_k.
    const double* r0 = scratch.data();
    dots_with(y.data(), m, &r0, 1, products.data(), n);
    std::vector<double>& c = negated_;
    for (int k = 0; k < m; ++k) {
      double along = h0_scale * products[k];
      for (int j = 0; j < k; ++j) along += c[j] * step_products_[k][j];
      c[k] = a[k] - curvatures_[k] * along;
    }
    combine(direction.data(), h0_scale, scratch.data(), s.data(), c.data(), m, n);
  }

 private:
  double keep_if_curved(const StepProducts& p) {
    if (!(p.sy > 1e-14 * std::sqrt(p.ss * p.yy))) return 0.0;
    keep(p.sy);
    return (p.sy + p.s_db) / p.sy;
  }

  // Keeps the spare pair as the newest; the oldest pair's storage becomes
  // the spare when the memory is full (no allocation once it is).
  void keep(double sy) {
    if (newest_products_pending_) {
      // Two pairs in a row without a direction between them: the last one's
      // products now, while the indices still hold (the same kernel as the
      // direction's pass, so the same products either way).
      const int m = static_cast<int>(steps_.size());
      std::vector<const double*>& s = step_data_;
      s.resize(m - 1);
      for (int j = 0; j + 1 < m; ++j) s[j] = steps_[j].data();
      const double* newest = changes_.back().data();
      std::vector<double>& column = step_products_.back();
      column.resize(m - 1);
      dots_with(s.data(), m - 1, &newest, 1, column.data(), static_cast<std::size_t>(changes_.back().size()));
    }
    Matrix step = std::move(spare_step_), change = std::move(spare_change_);
    if (static_cast<int>(steps_.size()) == capacity_) {
      spare_step_ = std::move(steps_.front());
      spare_change_ = std::move(changes_.front());
      steps_.pop_front();
      changes_.pop_front();
      curvatures_.pop_front();
      step_products_.pop_front();
      for (std::vector<double>& column : step_products_) column.erase(column.begin());
    }
    steps_.push_back(std::move(step));
    changes_.push_back(std::move(change));
    curvatures_.push_back(1.0 / sy);
    step_products_.emplace_back();
    newest_products_pending_ = true;
  }

  int capacity_;
  std::deque<Matrix> steps_, changes_;  // s_k, y_k
  std::deque<double> curvatures_;       // rho_k = 1 / (y_k . s_k)
  // step_products_[k][j] = s_j . y_k for j < k; the newest pair's are
  // computed with the next direction (its pass over the s_j), when pending.
  std::deque<std::vector<double>> step_products_;
  bool newest_products_pending_ = false;
  Matrix spare_step_, spare_change_;
  std::vector<const double*> step_data_, change_data_;
  std::vector<double> coefficients_, products_, negated_;
};

}  // namespace aniso
