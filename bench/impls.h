// One timing sample per implementation and run. Everything here is the
// benchmark's own code; the CGAL peer (GPL) is compiled only into the
// benchmark executable, never into anisoform_core or the WASM module.
#pragma once

#include <string>
#include <vector>

#include "anisoform/deformer.h"
#include "problems.h"

namespace aniso_bench {

// What the benchmark's own stopwatches read: wall time (default, steady_clock)
// or this thread's CPU time (--clock cpu: robust on a loaded shared machine,
// since time spent waiting for a core is not counted; all timed code is
// single-threaded).
enum class ClockKind { Wall, Cpu };
void set_clock(ClockKind kind);
ClockKind clock_kind();
double now_ms();

struct Sample {
  double precompute_ms = 0.0;  // from the mesh to ready-to-iterate
  double iteration_ms = 0.0;   // per iteration (AnDefGrad: per change of amount)
  long factor_nonzeros = 0;    // nnz of the factor L below its diagonal (the floor's row only)
  // Diagnostics (stderr with --verbose only).
  double setup_ms = 0.0;       // part of precompute: construction before any solve
  double first_call_ms = 0.0;  // the first deform call's iterations, per iteration
  int iterations = 0;          // iterations in the timed call
  double mean_displacement = 0.0;  // mean |v' - v| after the timed call
};

// The median (0 for none): every row of the benchmark reports medians.
double median_of(std::vector<double> v);

// The standard edits: AnARAP/AnDefGrad stretch the top half by 1.5 along the
// long axis; ARAP moves the top 5 % by `offset` with the bottom 5 % held.
aniso::DeformRequest stretch_request(const Problem& problem, aniso::Method method);
aniso::DeformRequest arap_handles_request(const Problem& problem);
// AnARAP twisting the top half about the long axis (coupled rotations).
aniso::DeformRequest twist_request(const Problem& problem);

Sample run_eigen_ldlt(const Problem& problem, int solves);
Sample run_anisoform_arap(const Problem& problem, int iterations);
Sample run_anisoform_anarap(const Problem& problem, int iterations);
Sample run_anisoform_andefgrad(const Problem& problem, int changes);

// False when the benchmark was built without CGAL (the row is then left out).
bool have_cgal();
Sample run_cgal_arap(const Problem& problem, int iterations);

}  // namespace aniso_bench
