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
    recent_.clear();
    first_change_ = -1.0;
  } else {
    recent_.push_back(energy);
    if (static_cast<int>(recent_.size()) > window_ + 1) recent_.erase(recent_.begin());
    const double before = recent_.front();
    const int steps = static_cast<int>(recent_.size()) - 1;
    if (tolerance_ > 0.0 && steps > 0 && before > 0.0) {
      const double change = std::abs(before - energy) / (before * steps);
      if (first_change_ < 0.0) {
        if (change > 0.0) first_change_ = change;
      } else if (first_change_ > tolerance_ && change > 0.0) {
        const double fallen = std::log(first_change_ / change) / std::log(first_change_ / tolerance_);
        fraction = std::max(fraction, std::min(fallen, kBeforeTheEnd));
      }
    }
  }
  reported_ = std::max(reported_, std::clamp(fraction, 0.0, 1.0));
  return reported_;
}

double StagedProgress::update(int stage, int done, double energy) {
  const double used = cap_ > 0 ? static_cast<double>(done) / cap_ : 0.0;
  if (stages_.empty()) {
    reported_ = std::max(reported_, std::clamp(used, 0.0, 1.0));
    return reported_;
  }
  stage = std::clamp(stage, 0, static_cast<int>(stages_.size()) - 1);
  if (stage != stage_) {
    stage_start_ = 0.0;
    for (int k = 0; k < stage; ++k) stage_start_ += stages_[k].share;
    within_ = ConvergenceProgress(0, stages_[stage].end_change, stages_[stage].window);
    stage_ = stage;
  }
  const double fraction = std::max(stage_start_ + stages_[stage].share * within_.update(done, energy), used);
  reported_ = std::max(reported_, std::clamp(fraction, 0.0, 1.0));
  return reported_;
}

}  // namespace aniso
