// anisoform_bench --converge TOL: time to converge, plain local/global against
// Anderson acceleration (issue 11, goal 1), for ARAP and AnARAP on the
// standard problem (impls.h). One JSON line per method and acceleration:
//   {"mesh":..., "vertices":..., "impl":..., "acceleration":..., "tolerance":...,
//    "iterations":..., "converged":..., "ms":..., "energy":...}
// (medians over the runs of iterations and ms; the energy of the last run),
// then per method the same-run ratios plain/accelerated on stderr.
#pragma once

#include "problems.h"

namespace aniso_bench {

// Returns the process exit status (0, or 3 when a solve failed).
int run_convergence(const Problem& problem, double tolerance, int runs, int max_iterations);

}  // namespace aniso_bench
