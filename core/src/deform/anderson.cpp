#include "deform/anderson.h"

#include <algorithm>

#include <Eigen/Cholesky>

#include "base/simd_pair.h"
#include "base/vector_kernels.h"

namespace aniso {

namespace {
// The most differences a mixer keeps (the window): its sums live on the stack.
constexpr int kMaxWindow = 8;

// The new differences' pass (propose's first loop) for M kept differences
// (the new one's slot first): f = g - x, df = f - last_f and dg = g - last_g
// written, last_f and last_g advanced, and the products df . kept[a] and
// kept[a] . f (kept[0] = df) summed, each in a vector register, a pair of
// elements at a time (elements i mod 2, the lanes added at the end, then an
// odd tail). With M known at compile time the sums stay in registers: as a
// loop over a runtime count they went through memory, and the pass was 17 %
// of an accelerated coupled twist's iteration (cyl50k, natively).
template <int M>
void difference_pass(const double* x, const double* g, double* last_f, double* last_g, double* df_out,
                     double* dg_out, const double* const* kept, double* with_new, double* rhs, std::size_t n) {
  Pair gram[M] = {}, along[M] = {};
  std::size_t i = 0;
  for (; i + 2 <= n; i += 2) {
    const Pair gi = load_pair(g + i), f = gi - load_pair(x + i), df = f - load_pair(last_f + i);
    store_pair(dg_out + i, gi - load_pair(last_g + i));
    store_pair(df_out + i, df);
    store_pair(last_f + i, f);
    store_pair(last_g + i, gi);
    gram[0] += df * df;
    along[0] += df * f;
#pragma GCC unroll 8
    for (int a = 1; a < M; ++a) {
      const Pair k = load_pair(kept[a] + i);
      gram[a] += df * k;
      along[a] += k * f;
    }
  }
  for (int a = 0; a < M; ++a) {
    with_new[a] = gram[a][0] + gram[a][1];
    rhs[a] = along[a][0] + along[a][1];
  }
  for (; i < n; ++i) {
    const double f = g[i] - x[i], df = f - last_f[i];
    with_new[0] += df * df;
    rhs[0] += df * f;
    for (int a = 1; a < M; ++a) {
      with_new[a] += df * kept[a][i];
      rhs[a] += kept[a][i] * f;
    }
    dg_out[i] = g[i] - last_g[i];
    df_out[i] = df;
    last_f[i] = f;
    last_g[i] = g[i];
  }
}

using DifferencePass = void (*)(const double*, const double*, double*, double*, double*, double*,
                                const double* const*, double*, double*, std::size_t);
constexpr DifferencePass kDifferencePass[kMaxWindow] = {
    difference_pass<1>, difference_pass<2>, difference_pass<3>, difference_pass<4>,
    difference_pass<5>, difference_pass<6>, difference_pass<7>, difference_pass<8>};
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
  // One pass over the state (difference_pass): f = g - x, the new
  // differences of f and g into the next slot, and their products with f and
  // the kept differences (the slot's old difference, the oldest, is dropped
  // as it is overwritten). It read the vectors some 60 times when each
  // product was a pass of its own (a coupled twist of the koala: 12 % of an
  // iteration).
  const int s = next_;
  df_[s].resize(g.rows(), g.cols());
  dg_[s].resize(g.rows(), g.cols());
  next_ = (next_ + 1) % window_;
  count_ = std::min(count_ + 1, window_);
  const int m = count_;
  const double* kept[kMaxWindow] = {df_[s].data()};
  for (int a = 1; a < m; ++a) kept[a] = df_[slot(a)].data();
  double with_new[kMaxWindow] = {}, rhs[kMaxWindow] = {};
  const double* gs = g.data();
  kDifferencePass[m - 1](x.data(), gs, last_f_.data(), last_g_.data(), df_[s].data(), dg_[s].data(), kept, with_new,
                         rhs, static_cast<std::size_t>(size));
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
  double minus_theta[kMaxWindow];
  for (int a = 0; a < m; ++a) {
    mixed[a] = dg_[slot(a)].data();
    minus_theta[a] = -theta[a];
  }
  combine(proposal.data(), 1.0, gs, mixed, minus_theta, m, static_cast<std::size_t>(size));
  return true;
}

template class AndersonMixerOf<Positions>;
template class AndersonMixerOf<Eigen::Matrix<double, Eigen::Dynamic, 4, Eigen::RowMajor>>;

}  // namespace aniso
