// The progress fraction of iterations that end at a cap or when the relative
// energy change falls below a tolerance (a deform's AnARAP/ARAP iterations, a
// flattening's): the larger of the share of the cap used and how far the
// change has fallen, on a log scale, from the first one towards the
// tolerance. Why: counted against the cap alone, a solve that converged at a
// sixth of it (the hemisphere's flattening: 82 of 500) showed a bar stuck at
// 16 % that then jumped to the end. The energy change falls about
// geometrically (linearly on the log scale) as the iterations converge.
#pragma once

namespace aniso {

class ConvergenceProgress {
 public:
  // tolerance <= 0: the iterations run to the cap; the fraction is the cap's share.
  ConvergenceProgress(int cap, double tolerance) : cap_(cap), tolerance_(tolerance) {}

  // After iteration `done` (1, 2, ...) with energy `energy`: a fraction in
  // [0, 1], never below one returned before; 1 only at the cap (the caller
  // reports 1 when the iterations end earlier). A non-finite energy counts
  // only against the cap, and the log scale starts again after it (a
  // flattening's local/global iterations before its refinement report NaN).
  double update(int done, double energy);

 private:
  int cap_;
  double tolerance_;
  double previous_ = -1.0;      // last energy; < 0: none yet in this stage
  double first_change_ = -1.0;  // first relative change of this stage; < 0: none yet
  double reported_ = 0.0;
};

}  // namespace aniso
