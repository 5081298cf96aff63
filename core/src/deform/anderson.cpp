#include "deform/anderson.h"

#include <Eigen/Cholesky>

namespace aniso {

bool AndersonMixer::propose(const Positions& x, const Positions& g, Positions& proposal) {
  const Positions f = g - x;
  if (dg_.empty()) {
    dg_.resize(static_cast<std::size_t>(window_));
    df_.resize(static_cast<std::size_t>(window_));
  }
  bool mixed = false;
  if (has_last_) {
    dg_[next_] = g - last_g_;
    df_[next_] = f - last_f_;
    next_ = (next_ + 1) % window_;
    count_ = std::min(count_ + 1, window_);
    // Normal equations of the small least-squares problem, with a relative
    // Tikhonov term so that nearly parallel differences stay well posed.
    const int m = count_;
    Eigen::MatrixXd A(m, m);
    Eigen::VectorXd rhs(m);
    for (int a = 0; a < m; ++a) {
      const int sa = (next_ - 1 - a + 2 * window_) % window_;
      rhs[a] = (df_[sa].array() * f.array()).sum();
      for (int c = 0; c <= a; ++c) {
        const int sc = (next_ - 1 - c + 2 * window_) % window_;
        A(a, c) = A(c, a) = (df_[sa].array() * df_[sc].array()).sum();
      }
    }
    const double scale = A.diagonal().maxCoeff();
    if (scale > 0.0) {
      A.diagonal().array() += 1e-10 * scale;
      const Eigen::VectorXd theta = A.ldlt().solve(rhs);
      if (theta.allFinite()) {
        proposal = g;
        for (int a = 0; a < m; ++a) proposal -= theta[a] * dg_[(next_ - 1 - a + 2 * window_) % window_];
        mixed = true;
      }
    }
  }
  last_g_ = g;
  last_f_ = f;
  has_last_ = true;
  if (!mixed) proposal = g;
  return mixed;
}

}  // namespace aniso
