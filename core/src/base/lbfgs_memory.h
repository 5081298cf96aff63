// The memory of an L-BFGS iteration (Nocedal & Wright, Algorithm 7.4): the
// last few pairs of iterate changes s and gradient changes y, and the
// two-loop recursion that turns a gradient into the quasi-Newton direction
// -H g with a given initial inverse Hessian H0. One implementation for the
// AnARAP/ARAP iterations (deform/anarap_lbfgs.cpp) and the flattening's ARAP
// phase (flatten/flatten_arap.cpp), whose iterates are Eigen matrices of
// different shapes.
#pragma once

#include <cmath>
#include <deque>
#include <utility>
#include <vector>

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

  static double dot(const Matrix& a, const Matrix& b) { return (a.array() * b.array()).sum(); }

  // Keeps the pair if its curvature s.y = `sy` is clearly positive (only such
  // pairs keep H positive definite), dropping the oldest when full. Returns
  // whether it was kept.
  bool push(Matrix s, Matrix y, double sy) {
    if (!(sy > 1e-14 * std::sqrt(dot(s, s) * dot(y, y)))) return false;
    if (static_cast<int>(steps_.size()) == capacity_) {
      steps_.pop_front();
      changes_.pop_front();
      curvatures_.pop_front();
    }
    steps_.push_back(std::move(s));
    changes_.push_back(std::move(y));
    curvatures_.push_back(1.0 / sy);
    return true;
  }

  // direction = -H gradient. `apply_h0(q, r)` sets r = H0 q (r arrives as
  // the caller's scratch matrix of q's shape).
  template <class ApplyH0>
  void direction(const Matrix& gradient, Matrix& direction, Matrix& scratch, ApplyH0&& apply_h0) {
    direction = -gradient;
    coefficients_.resize(steps_.size());
    for (int k = static_cast<int>(steps_.size()) - 1; k >= 0; --k) {
      coefficients_[k] = curvatures_[k] * dot(steps_[k], direction);
      direction -= coefficients_[k] * changes_[k];
    }
    apply_h0(direction, scratch);
    direction.swap(scratch);
    for (std::size_t k = 0; k < steps_.size(); ++k) {
      direction += (coefficients_[k] - curvatures_[k] * dot(changes_[k], direction)) * steps_[k];
    }
  }

 private:
  int capacity_;
  std::deque<Matrix> steps_, changes_;  // s_k, y_k
  std::deque<double> curvatures_;       // 1 / (y_k . s_k)
  std::vector<double> coefficients_;
};

}  // namespace aniso
