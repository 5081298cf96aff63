// Anderson acceleration of a fixed-point iteration x <- G(x) (Walker & Ni
// 2011; for local/global geometry solvers, Peng et al. 2018, "Anderson
// acceleration for geometry optimization and physics simulation"): from the
// last m+1 pairs (x_k, G(x_k)) it proposes
//   x_AA = G(x_k) - dG theta,  theta = argmin || f_k - dF theta ||,  f = G(x) - x,
// the combination of the recent steps whose residual is smallest. The caller
// keeps it only if its energy is lower than the last accepted one (the
// safeguard), and otherwise takes G(x_k) and calls reset().
//
// The state is a dense row-major matrix: the positions (AnARAP and ARAP,
// whose rotations follow from them), or the rotations as quaternions (coupled
// rotations, which carry the iteration's state: anarap.cpp).
#pragma once

#include <vector>

#include <Eigen/Core>

#include "anisoform/mesh.h"

namespace aniso {

template <typename State>
class AndersonMixerOf {
 public:
  using StateType = State;
  explicit AndersonMixerOf(int window);

  // x: the current iterate, g: G(x). Returns the proposal in `proposal`;
  // false when there is no history yet (the proposal is then g itself).
  bool propose(const State& x, const State& g, State& proposal);
  // Forgets the differences (after a rejected proposal); the last pair stays:
  // it is still a true (x, G(x)).
  void reset() { count_ = 0; }

 private:
  // Slot of the a-th newest difference (a = 0: the one just added).
  int slot(int age) const { return (next_ - 1 - age + 2 * window_) % window_; }

  int window_;
  int count_ = 0;   // differences stored (at most window_)
  int next_ = 0;    // ring slot for the next difference
  bool has_last_ = false;
  State last_g_, last_f_;
  std::vector<State> dg_, df_;
  // df_a . df_c by slot, kept as the differences come: each new one adds a
  // row rather than the whole Gram matrix being made again.
  Eigen::MatrixXd gram_;
};

using AndersonMixer = AndersonMixerOf<Positions>;
// Unit quaternions, one per row, in Eigen's coefficient order (x, y, z, w).
using RotationMixer = AndersonMixerOf<Eigen::Matrix<double, Eigen::Dynamic, 4, Eigen::RowMajor>>;

extern template class AndersonMixerOf<Positions>;
extern template class AndersonMixerOf<Eigen::Matrix<double, Eigen::Dynamic, 4, Eigen::RowMajor>>;

}  // namespace aniso
