#include "base/convergence_progress.h"

#include <algorithm>
#include <cmath>

namespace aniso {

namespace {

// The energy change's share stays below 1: only the cap, or the caller
// when the iterations end, reports 1.
constexpr double kBeforeTheEnd = 0.99;

}  // namespace

double ConvergenceProgress::update(int done, double energy) {
  double fraction = cap_ > 0 ? static_cast<double>(done) / cap_ : 0.0;
  if (!std::isfinite(energy)) {
    previous_ = first_change_ = -1.0;
  } else {
    if (tolerance_ > 0.0 && previous_ > 0.0) {
      const double change = std::abs(previous_ - energy) / previous_;
      if (first_change_ < 0.0) {
        if (change > 0.0) first_change_ = change;
      } else if (first_change_ > tolerance_ && change > 0.0) {
        const double fallen = std::log(first_change_ / change) / std::log(first_change_ / tolerance_);
        fraction = std::max(fraction, std::min(fallen, kBeforeTheEnd));
      }
    }
    previous_ = energy;
  }
  reported_ = std::max(reported_, std::clamp(fraction, 0.0, 1.0));
  return reported_;
}

}  // namespace aniso
