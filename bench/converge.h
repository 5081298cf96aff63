// anisoform_bench --converge TOL: time to converge, plain local/global against
// Anderson acceleration and L-BFGS (issue 11, goal 1), for ARAP and AnARAP on
// the standard problem (impls.h), and plain against L-BFGS for the
// flattening. One JSON line per method and acceleration:
//   {"mesh":..., "vertices":..., "impl":..., "acceleration":..., "tolerance":...,
//    "iterations":..., "converged":..., "ms":..., "energy":...}
// (medians over the runs of iterations and ms; the energy of the last run),
// then per method the same-run ratios plain/accelerated on stderr; then each
// accelerated solve timed to the plain run's final energy ("to":
// "plain-energy" rows, bench/README.md).
#pragma once

#include <set>
#include <string>

#include "problems.h"

namespace aniso_bench {

// Whether `name` is one of the rows run_convergence can run.
bool is_convergence_row(const std::string& name);

// Returns the process exit status (0, or 3 when a solve failed). With `only`
// not empty, just the rows it names.
int run_convergence(const Problem& problem, double tolerance, int runs, int max_iterations,
                    const std::set<std::string>& only);

}  // namespace aniso_bench
