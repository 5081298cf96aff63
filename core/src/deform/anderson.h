// Anderson acceleration of a fixed-point iteration x <- G(x) (Walker & Ni
// 2011; for local/global geometry solvers, Peng et al. 2018, "Anderson
// acceleration for geometry optimization and physics simulation"): from the
// last m+1 pairs (x_k, G(x_k)) it proposes
//   x_AA = G(x_k) - dG theta,  theta = argmin || f_k - dF theta ||,  f = G(x) - x,
// the combination of the recent steps whose residual is smallest. The caller
// keeps it only if its energy is lower than the last accepted one (the
// safeguard), and otherwise takes G(x_k) and calls reset().
#pragma once

#include <vector>

#include <Eigen/Core>

#include "anisoform/mesh.h"

namespace aniso {

class AndersonMixer {
 public:
  explicit AndersonMixer(int window) : window_(window) {}

  // x: the current iterate, g: G(x). Returns the proposal in `proposal`;
  // false when there is no history yet (the proposal is then g itself).
  bool propose(const Positions& x, const Positions& g, Positions& proposal);
  // Forgets the differences (after a rejected proposal); the last pair stays:
  // it is still a true (x, G(x)).
  void reset() { count_ = 0; }

 private:
  int window_;
  int count_ = 0;   // differences stored (at most window_)
  int next_ = 0;    // ring slot for the next difference
  bool has_last_ = false;
  Positions last_g_, last_f_;
  std::vector<Positions> dg_, df_;
};

}  // namespace aniso
