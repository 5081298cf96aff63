#include "converge.h"

#include <algorithm>
#include <cstdio>
#include <exception>
#include <vector>

#include "anisoform/deformer.h"
#include "anisoform/error.h"
#include "anisoform/flatten.h"
#include "impls.h"

namespace aniso_bench {
namespace {

struct Converged {
  std::vector<double> iterations, ms;
  double energy = 0.0;
  bool converged = true;
};

// One cold solve to `tolerance` on a Deformer whose factorization is done
// already: only the iterations are timed.
void solve_once(aniso::Deformer& deformer, aniso::DeformRequest request, Converged& out) {
  request.warm_start = false;
  const double start = now_ms();
  const aniso::DeformResult result = deformer.deform(request);
  out.ms.push_back(now_ms() - start - result.precompute_ms);
  out.iterations.push_back(result.iterations);
  out.energy = result.energy;
  out.converged = out.converged && result.converged;
}

// The flattening's ARAP phase (no refinement) from the LSCM start, plain
// local/global then L-BFGS, interleaved run by run; the time is the whole
// flatten call (targets and metrics included, the same for both), so the
// ratio understates the iterations' own. The patch is the top half
// (problem.top_half: on the closed cylinders a cup, cap and tube); a mesh
// without a boundary there has nothing to flatten: a note, no row.
void run_flatten_convergence(const Problem& problem, double tolerance, int runs, int max_iterations) {
  aniso::FlattenOptions options;
  options.directions.global = problem.direction;
  options.su = 0.8;
  options.solver.tolerance = tolerance;
  options.solver.max_iterations = max_iterations;
  options.solver.refine = false;
  struct Variant {
    const char* name;
    bool accelerate;
    Converged result;
    std::vector<double> speedup;
  };
  std::vector<Variant> variants = {{"none", false, {}, {}}, {"lbfgs", true, {}, {}}};
  try {
    std::vector<char> top_half(problem.mesh.num_vertices());
    for (int i = 0; i < problem.mesh.num_vertices(); ++i) top_half[i] = problem.top_half[i] > 0.0;
    aniso::Flattener flattener(problem.mesh, top_half);
    for (int r = 0; r < runs; ++r) {
      for (Variant& v : variants) {
        options.solver.accelerate = v.accelerate;
        const double start = now_ms();
        const aniso::FlattenResult result = flattener.flatten(options);
        v.result.ms.push_back(now_ms() - start);
        v.result.iterations.push_back(result.metrics.iterations);
        v.result.energy = result.metrics.energy;
        v.result.converged = v.result.converged && result.metrics.converged;
        v.speedup.push_back(variants[0].result.ms.back() / v.result.ms.back());
      }
    }
  } catch (const aniso::Error& e) {
    std::fprintf(stderr, "converge %s flatten: skipped (%s)\n", problem.name.c_str(), e.what());
    return;
  }
  const int n = problem.mesh.num_vertices();
  for (const Variant& v : variants) {
    const Converged& c = v.result;
    std::printf("{\"mesh\":\"%s\",\"vertices\":%d,\"impl\":\"anisoform-flatten\",\"acceleration\":\"%s\",\"tolerance\":%g,"
                "\"iterations\":%.0f,\"converged\":%s,\"ms\":%.1f,\"energy\":%.10g}\n",
                problem.name.c_str(), n, v.name, tolerance, median_of(c.iterations), c.converged ? "true" : "false",
                median_of(c.ms), c.energy);
  }
  std::fflush(stdout);
  const Variant& plain = variants[0];
  const Variant& lbfgs = variants[1];
  std::fprintf(stderr,
               "converge %s anisoform-flatten lbfgs (%d vertices, tolerance %g, %d runs): iterations %.0f -> %.0f, "
               "time plain/lbfgs %.2f (goal >= 5), energy lbfgs/plain - 1 = %.2e\n",
               problem.name.c_str(), n, tolerance, runs, median_of(plain.result.iterations),
               median_of(lbfgs.result.iterations), median_of(lbfgs.speedup),
               lbfgs.result.energy / plain.result.energy - 1.0);
}

}  // namespace

int run_convergence(const Problem& problem, double tolerance, int runs, int max_iterations) {
  const int n = problem.mesh.num_vertices();
  struct Row {
    const char* impl;
    aniso::DeformRequest request;
  };
  const std::vector<Row> rows = {{"anisoform-arap", arap_handles_request(problem)},
                                 {"anisoform-anarap", stretch_request(problem, aniso::Method::AnArap)}};
  for (const Row& row : rows) {
    aniso::DeformRequest request = row.request;
    request.tolerance = tolerance;
    request.max_iterations = max_iterations;
    aniso::Deformer deformer(problem.mesh);
    {
      // Factorize and build the solver once, outside the timed solves.
      aniso::DeformRequest warmup = request;
      warmup.max_iterations = 1;
      deformer.deform(warmup);
    }
    // Plain local/global first, then each acceleration, interleaved run by run.
    struct Variant {
      const char* name;
      aniso::Acceleration acceleration;
      Converged result;
      std::vector<double> speedup;  // plain ms / this ms, per run
    };
    std::vector<Variant> variants = {{"none", aniso::Acceleration::None, {}, {}},
                                     {"anderson", aniso::Acceleration::Anderson, {}, {}},
                                     {"lbfgs", aniso::Acceleration::Lbfgs, {}, {}}};
    try {
      for (int r = 0; r < runs; ++r) {
        for (Variant& v : variants) {
          request.acceleration = v.acceleration;
          solve_once(deformer, request, v.result);
          v.speedup.push_back(variants[0].result.ms.back() / v.result.ms.back());
        }
      }
    } catch (const std::exception& e) {
      std::fprintf(stderr, "anisoform_bench: %s failed on %s: %s\n", row.impl, problem.name.c_str(), e.what());
      return 3;
    }
    for (const Variant& v : variants) {
      const Converged& c = v.result;
      std::printf("{\"mesh\":\"%s\",\"vertices\":%d,\"impl\":\"%s\",\"acceleration\":\"%s\",\"tolerance\":%g,"
                  "\"iterations\":%.0f,\"converged\":%s,\"ms\":%.1f,\"energy\":%.10g}\n",
                  problem.name.c_str(), n, row.impl, v.name, tolerance, median_of(c.iterations),
                  c.converged ? "true" : "false", median_of(c.ms), c.energy);
    }
    std::fflush(stdout);
    const Converged& plain = variants[0].result;
    for (std::size_t k = 1; k < variants.size(); ++k) {
      const Variant& v = variants[k];
      std::fprintf(stderr,
                   "converge %s %s %s (%d vertices, tolerance %g, %d runs): iterations %.0f -> %.0f, time plain/%s "
                   "%.2f (goal >= 5), energy %s/plain - 1 = %.2e\n",
                   problem.name.c_str(), row.impl, v.name, n, tolerance, runs, median_of(plain.iterations),
                   median_of(v.result.iterations), v.name, median_of(v.speedup), v.name,
                   v.result.energy / plain.energy - 1.0);
    }
  }
  run_flatten_convergence(problem, tolerance, runs, max_iterations);
  return 0;
}

}  // namespace aniso_bench
