// How far a long call has got, for a host's progress bar.
#pragma once

#include <functional>

namespace aniso {

enum class ProgressStage {
  Load,       // reading, checking and preparing a new mesh
  Factorize,  // the Laplacian's factorization for a set of pinned vertices (by work done)
  Solve,      // a deform's iterations
  Flatten,    // a flattening's iterations
};

// "load", "factorize", "solve", "flatten".
const char* progress_stage_name(ProgressStage stage);

// Called from inside the work, on the caller's thread, with the fraction of
// the stage done in [0, 1], never falling. An iterative stage reports the
// larger of the share of its iteration cap used and how far its energy
// change has fallen towards the tolerance (base/convergence_progress.h), so
// it may end early below 1; the call then reports 1 when it is done.
using ProgressFn = std::function<void(ProgressStage stage, double fraction)>;

}  // namespace aniso
