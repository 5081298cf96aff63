// The memory of an L-BFGS iteration (Nocedal & Wright, Algorithm 7.4): the
// last few pairs of iterate changes s and gradient changes y, and the
// two-loop recursion that turns a gradient into the quasi-Newton direction
// -H g with a given initial inverse Hessian H0. One implementation for the
// AnARAP/ARAP iterations (deform/anarap_lbfgs.cpp) and the flattening's ARAP
// phase (flatten/flatten_arap.cpp), whose iterates are Eigen matrices of
// different shapes.
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
  }

  static double dot(const Matrix& a, const Matrix& b) {
    return aniso::dot(a.data(), b.data(), static_cast<std::size_t>(a.size()));
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
    Matrix s(x1.rows(), x1.cols()), y(x1.rows(), x1.cols());
    const StepProducts p = step_pair(x1.data(), x0.data(), g1.data(), g0.data(), b1.data(), b0.data(), s.data(),
                                     y.data(), static_cast<std::size_t>(s.size()));
    if (!(p.sy > 1e-14 * std::sqrt(p.ss * p.yy))) return 0.0;
    keep(std::move(s), std::move(y), p.sy);
    return (p.sy + p.s_db) / p.sy;
  }

  // direction = -H gradient. `apply_h0(q, r)` sets r = H0 q (r arrives as
  // the caller's scratch matrix of q's shape). Each update of the direction
  // also takes the dot product the next step of its loop needs (axpy_dot).
  template <class ApplyH0>
  void direction(const Matrix& gradient, Matrix& direction, Matrix& scratch, ApplyH0&& apply_h0) {
    const int m = static_cast<int>(steps_.size());
    const auto n = static_cast<std::size_t>(gradient.size());
    direction = -gradient;
    coefficients_.resize(steps_.size());
    double projection = m > 0 ? dot(steps_[m - 1], direction) : 0.0;  // s_k . q
    for (int k = m - 1; k >= 0; --k) {
      coefficients_[k] = curvatures_[k] * projection;
      projection = axpy_dot(direction.data(), -coefficients_[k], changes_[k].data(),
                            k > 0 ? steps_[k - 1].data() : nullptr, n);
    }
    apply_h0(direction, scratch);
    direction.swap(scratch);
    double along = m > 0 ? dot(changes_[0], direction) : 0.0;  // y_k . r
    for (int k = 0; k < m; ++k) {
      along = axpy_dot(direction.data(), coefficients_[k] - curvatures_[k] * along, steps_[k].data(),
                       k + 1 < m ? changes_[k + 1].data() : nullptr, n);
    }
  }

 private:
  void keep(Matrix s, Matrix y, double sy) {
    if (static_cast<int>(steps_.size()) == capacity_) {
      steps_.pop_front();
      changes_.pop_front();
      curvatures_.pop_front();
    }
    steps_.push_back(std::move(s));
    changes_.push_back(std::move(y));
    curvatures_.push_back(1.0 / sy);
  }

  int capacity_;
  std::deque<Matrix> steps_, changes_;  // s_k, y_k
  std::deque<double> curvatures_;       // 1 / (y_k . s_k)
  std::vector<double> coefficients_;
};

}  // namespace aniso
