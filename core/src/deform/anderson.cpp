#include "deform/anderson.h"

#include <algorithm>

#include <Eigen/Cholesky>

namespace aniso {

namespace {
// The most differences a mixer keeps (the window): its sums live on the stack.
constexpr int kMaxWindow = 8;
}  // namespace

template <typename State>
AndersonMixerOf<State>::AndersonMixerOf(int window)
    : window_(std::clamp(window, 1, kMaxWindow)), dg_(window_), df_(window_), gram_(window_, window_) {}

template <typename State>
bool AndersonMixerOf<State>::propose(const State& x, const State& g, State& proposal) {
  const Eigen::Index size = g.size();
  if (!has_last_) {
    last_g_ = g;
    last_f_ = g - x;
    has_last_ = true;
    proposal = g;
    return false;
  }
  // One pass over the state: f = g - x, the new differences of f and g into
  // the next slot, and their products with f and the kept differences (the
  // slot's old difference, the oldest, is dropped as it is overwritten). It
  // read the vectors some 60 times when each product was a pass of its own
  // (a coupled twist of the koala: 12 % of an iteration).
  const int s = next_;
  df_[s].resize(g.rows(), g.cols());
  dg_[s].resize(g.rows(), g.cols());
  next_ = (next_ + 1) % window_;
  count_ = std::min(count_ + 1, window_);
  const int m = count_;
  const double* kept[kMaxWindow];
  for (int a = 1; a < m; ++a) kept[a] = df_[slot(a)].data();
  double with_new[kMaxWindow] = {}, rhs[kMaxWindow] = {};
  const double *xs = x.data(), *gs = g.data();
  double *lf = last_f_.data(), *lg = last_g_.data(), *dfs = df_[s].data(), *dgs = dg_[s].data();
  for (Eigen::Index i = 0; i < size; ++i) {
    const double f = gs[i] - xs[i], df = f - lf[i];
    with_new[0] += df * df;
    rhs[0] += df * f;
    for (int a = 1; a < m; ++a) {
      with_new[a] += df * kept[a][i];
      rhs[a] += kept[a][i] * f;
    }
    dgs[i] = gs[i] - lg[i];
    dfs[i] = df;
    lf[i] = f;
    lg[i] = gs[i];
  }
  for (int a = 0; a < m; ++a) gram_(s, slot(a)) = gram_(slot(a), s) = with_new[a];
  // Normal equations of the small least-squares problem, with a relative
  // Tikhonov term so that nearly parallel differences stay well posed.
  Eigen::MatrixXd A(m, m);
  for (int a = 0; a < m; ++a) {
    for (int c = 0; c < m; ++c) A(a, c) = gram_(slot(a), slot(c));
  }
  const double scale = A.diagonal().maxCoeff();
  if (!(scale > 0.0)) {
    proposal = g;
    return false;
  }
  A.diagonal().array() += 1e-10 * scale;
  const Eigen::VectorXd theta = A.ldlt().solve(Eigen::Map<const Eigen::VectorXd>(rhs, m));
  if (!theta.allFinite()) {
    proposal = g;
    return false;
  }
  proposal.resize(g.rows(), g.cols());
  const double* mixed[kMaxWindow];
  for (int a = 0; a < m; ++a) mixed[a] = dg_[slot(a)].data();
  double* out = proposal.data();
  for (Eigen::Index i = 0; i < size; ++i) {
    double value = gs[i];
    for (int a = 0; a < m; ++a) value -= theta[a] * mixed[a][i];
    out[i] = value;
  }
  return true;
}

template class AndersonMixerOf<Positions>;
template class AndersonMixerOf<Eigen::Matrix<double, Eigen::Dynamic, 4, Eigen::RowMajor>>;

}  // namespace aniso
