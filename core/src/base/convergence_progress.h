// The progress fraction of iterations that end at a cap or when the relative
// energy change falls below a tolerance (a deform's AnARAP/ARAP iterations, a
// flattening's): the larger of the share of the cap used and how far the
// change has fallen, on a log scale, from the first one towards the
// tolerance. Why: counted against the cap alone, a solve that converged at a
// sixth of it (the hemisphere's flattening: 82 of 500) showed a bar stuck at
// 16 % that then jumped to the end. The energy change falls about
// geometrically (linearly on the log scale) as the iterations converge.
#pragma once

#include <utility>
#include <vector>

namespace aniso {

class ConvergenceProgress {
 public:
  // tolerance <= 0: the iterations run to the cap; the fraction is the cap's
  // share. window: the change measured is the mean relative change per
  // iteration over the last `window` iterations (1: the last one's), for
  // iterations that end where such a mean falls below the tolerance.
  ConvergenceProgress(int cap, double tolerance, int window = 1)
      : cap_(cap), tolerance_(tolerance), window_(window < 1 ? 1 : window) {}

  // After iteration `done` (1, 2, ...) with energy `energy`: a fraction in
  // [0, 1], never below one returned before; 1 only at the cap (the caller
  // reports 1 when the iterations end earlier). A non-finite energy counts
  // only against the cap, and the log scale starts again after it (a stage
  // whose energy is another function's can begin so).
  double update(int done, double energy);

 private:
  int cap_;
  double tolerance_;
  int window_;
  std::vector<double> recent_;  // this stage's last window_ + 1 energies, oldest first
  double first_change_ = -1.0;  // first relative change of this stage; < 0: none yet
  double reported_ = 0.0;
};

// The progress fraction of iterations in stages run one after the other,
// each with an energy of its own and a relative energy change at which it
// ends about (a flattening's local/global iterations, then its refinement's
// stages): stage k fills its share of the bar by ConvergenceProgress's log
// scale, from its first change towards its end change (each change a mean
// over the stage's window), after the shares of the stages before it. The
// share of the iteration cap used is the floor.
class StagedProgress {
 public:
  struct Stage {
    double share;       // of the whole bar (the shares sum to 1)
    double end_change;  // <= 0: the stage fills its share only as the cap is used
    int window = 1;     // iterations per change (ConvergenceProgress)
  };
  StagedProgress(std::vector<Stage> stages, int cap) : stages_(std::move(stages)), cap_(cap) {}

  // After iteration `done` of all (1, 2, ...), in stage `stage`, with that
  // stage's energy: a fraction in [0, 1], never below one returned before.
  double update(int stage, int done, double energy);

 private:
  std::vector<Stage> stages_;
  int cap_;
  int stage_ = -1;
  double stage_start_ = 0.0;  // the shares of the stages before stage_
  ConvergenceProgress within_{0, 0.0};  // the current stage's, without the cap
  double reported_ = 0.0;
};

}  // namespace aniso
