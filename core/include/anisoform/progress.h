// How far a long call has got, for a host's progress bar.
#pragma once

#include <functional>

namespace aniso {

enum class ProgressStage {
  Load,       // reading, checking and preparing a new mesh
  Factorize,  // the solver's set-up for a rest pose and its pins (kSetup* below)
  Solve,      // a deform's iterations
  Flatten,    // a flattening's iterations
};

// The Factorize stage's shares of a rest pose's set-up, one scale whether
// Session::prepare_step runs its parts one at a time in the background or an
// edit runs what is left of them at once (so that an edit coming during the
// preparation carries its progress on instead of starting again from 0):
// the unit-size copy and its Laplacian end at kSetupLaplacianShare, the
// workspace at kSetupWorkspaceShare, the factorization (by its work, from
// kSetupWorkspaceShare) at kSetupFactorizedShare, the iterations'
// structures at 1 (in the background preparation at kSetupStructuresShare,
// and its warm-up of a preview's work at 1). Shares of the 200k-vertex
// koala's set-up in WASM.
inline constexpr double kSetupLaplacianShare = 0.3;
inline constexpr double kSetupWorkspaceShare = 0.35;
inline constexpr double kSetupFactorizedShare = 0.95;
inline constexpr double kSetupStructuresShare = 0.97;

// "load", "factorize", "solve", "flatten".
const char* progress_stage_name(ProgressStage stage);

// Called from inside the work, on the caller's thread, with the fraction of
// the stage done in [0, 1], never falling. An iterative stage reports the
// larger of the share of its iteration cap used and how far its energy
// change has fallen towards the tolerance (base/convergence_progress.h), so
// it may end early below 1; the call then reports 1 when it is done.
using ProgressFn = std::function<void(ProgressStage stage, double fraction)>;

}  // namespace aniso
