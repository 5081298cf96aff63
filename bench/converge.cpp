#include "converge.h"

#include <algorithm>
#include <cstdio>
#include <exception>
#include <optional>
#include <vector>

#include "anisoform/deformer.h"
#include "anisoform/error.h"
#include "anisoform/flatten.h"
#include "flatten/flatten_pipeline.h"
#include "impls.h"

namespace aniso_bench {
namespace {

struct Converged {
  std::vector<double> iterations, ms;
  double energy = 0.0;
  std::vector<double> energy_history;  // the last run's
  bool converged = true;
};

// The first iteration (1-based) whose energy is at most `target`, or 0.
int first_iteration_at(const std::vector<double>& history, double target) {
  for (std::size_t k = 0; k < history.size(); ++k) {
    if (history[k] <= target) return static_cast<int>(k) + 1;
  }
  return 0;
}

// One cold solve to `tolerance` on a Deformer whose factorization is done
// already: only the iterations are timed.
void solve_once(aniso::Deformer& deformer, aniso::DeformRequest request, Converged& out) {
  request.warm_start = false;
  const double start = now_ms();
  const aniso::DeformResult result = deformer.deform(request);
  out.ms.push_back(now_ms() - start - result.precompute_ms);
  out.iterations.push_back(result.iterations);
  out.energy = result.energy;
  out.energy_history = result.energy_history;
  out.converged = out.converged && result.converged;
}

// The flattened patch of the convergence rows: the top half, as a vertex mask.
std::vector<char> top_half_mask(const Problem& problem) {
  std::vector<char> mask(problem.mesh.num_vertices());
  for (int i = 0; i < problem.mesh.num_vertices(); ++i) mask[i] = problem.top_half[i] > 0.0;
  return mask;
}

// A note when a run stopped short of the tolerance (the fold guard blocked
// it, on a patch that does not flatten as one piece, or the cap came): its
// row then says where it stopped, not where it converges.
void note_unconverged(const std::string& mesh, const char* row, bool plain_converged, bool lbfgs_converged) {
  if (plain_converged && lbfgs_converged) return;
  const char* which = !plain_converged && !lbfgs_converged ? "neither run"
                      : !plain_converged                    ? "the plain run"
                                                            : "the lbfgs run";
  std::fprintf(stderr,
               "converge %s %s: %s reached the tolerance (stopped by the fold guard or the cap): the ratios compare "
               "where the runs stopped\n",
               mesh.c_str(), row, which);
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
  std::optional<aniso::Flattener> flattener;
  try {
    flattener.emplace(problem.mesh, top_half_mask(problem));
    for (int r = 0; r < runs; ++r) {
      for (Variant& v : variants) {
        options.solver.accelerate = v.accelerate;
        const double start = now_ms();
        const aniso::FlattenResult result = flattener->flatten(options);
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
  note_unconverged(problem.name, "anisoform-flatten", plain.result.converged, lbfgs.result.converged);

  // As for the deformations: L-BFGS timed to the energy the plain run ended
  // at. The flatten call reports no history, so the iteration cap that gets
  // there is probed first (untimed), from 1 up.
  options.solver.accelerate = true;
  options.solver.tolerance = 0.0;
  int at = 0;
  std::vector<double> ms, speedup;
  double energy = 0.0;
  try {
    for (int cap = 1; cap <= median_of(lbfgs.result.iterations) && at == 0; ++cap) {
      options.solver.max_iterations = cap;
      if (flattener->flatten(options).metrics.energy <= plain.result.energy) at = cap;
    }
    if (at == 0) {
      std::fprintf(stderr,
                   "converge %s anisoform-flatten lbfgs never reached the plain run's energy (%.10g; it ended at "
                   "%.10g)\n",
                   problem.name.c_str(), plain.result.energy, lbfgs.result.energy);
      return;
    }
    options.solver.max_iterations = at;
    for (int r = 0; r < runs; ++r) {
      const double start = now_ms();
      energy = flattener->flatten(options).metrics.energy;
      ms.push_back(now_ms() - start);
      speedup.push_back(plain.result.ms[r] / ms.back());
    }
  } catch (const aniso::Error& e) {
    std::fprintf(stderr, "converge %s flatten to the plain run's energy: skipped (%s)\n", problem.name.c_str(),
                 e.what());
    return;
  }
  std::printf("{\"mesh\":\"%s\",\"vertices\":%d,\"impl\":\"anisoform-flatten\",\"acceleration\":\"lbfgs\","
              "\"to\":\"plain-energy\",\"iterations\":%d,\"ms\":%.1f,\"energy\":%.10g}\n",
              problem.name.c_str(), n, at, median_of(ms), energy);
  std::fflush(stdout);
  std::fprintf(stderr,
               "converge %s anisoform-flatten lbfgs to the plain run's energy (%.10g): iterations %.0f -> %d, time "
               "plain/lbfgs %.2f (goal >= 5)\n",
               problem.name.c_str(), plain.result.energy, median_of(plain.result.iterations), at, median_of(speedup));
}

// The flattening's iterations alone, as the deformation rows time theirs:
// the patch (problem.top_half), its charts, targets and LSCM start at the
// wanted area and the factorization are made once, untimed (the flatten
// call above makes the same ones, but its time also holds the targets and
// the metrics); ArapFlattening::solve then runs plain and L-BFGS from that
// start, interleaved run by run, to the tolerance and (L-BFGS, capped at
// the first iteration its history shows there) to the plain run's energy.
void run_flatten_iterations(const Problem& problem, double tolerance, int runs, int max_iterations) {
  try {
    const aniso::FlattenPatch patch = aniso::extract_flatten_patch(problem.mesh, top_half_mask(problem));
    const aniso::TriangleCharts charts = aniso::triangle_charts(patch.mesh);
    aniso::FlattenDirections directions;
    directions.global = problem.direction;
    const aniso::FlattenTargets targets = aniso::flatten_targets(
        problem.mesh, patch, charts, aniso::TriangleNeighbours(patch), directions, 0.8, 1.0);
    Eigen::MatrixX2d start;
    aniso::lscm_free_boundary(patch, charts, start);
    aniso::scale_to_area(patch, charts.area.cwiseProduct(targets.su).cwiseProduct(targets.sv), start);
    const aniso::ArapFlattening arap(patch, charts);
    aniso::ArapFlattenSettings settings;
    settings.tolerance = tolerance;
    settings.max_iterations = max_iterations;
    const auto solve = [&](bool accelerate, Converged& out) {
      settings.accelerate = accelerate;
      Eigen::MatrixX2d uv = start;
      const double begun = now_ms();
      const aniso::ArapFlattenReport report = arap.solve(targets, settings, uv);
      out.ms.push_back(now_ms() - begun);
      out.iterations.push_back(report.iterations);
      out.energy = report.energy;
      out.energy_history.assign(report.energy_history.begin() + 1, report.energy_history.end());
      out.converged = out.converged && report.converged;
    };
    Converged plain, lbfgs, to_energy;
    std::vector<double> speedup;
    for (int r = 0; r < runs; ++r) {
      solve(false, plain);
      solve(true, lbfgs);
      speedup.push_back(plain.ms.back() / lbfgs.ms.back());
    }
    const int vertices = problem.mesh.num_vertices();
    for (const auto& [name, c] : {std::pair<const char*, const Converged&>{"none", plain}, {"lbfgs", lbfgs}}) {
      std::printf("{\"mesh\":\"%s\",\"vertices\":%d,\"impl\":\"anisoform-flatten\",\"phase\":\"iterations\","
                  "\"acceleration\":\"%s\",\"tolerance\":%g,\"iterations\":%.0f,\"converged\":%s,\"ms\":%.2f,"
                  "\"energy\":%.10g}\n",
                  problem.name.c_str(), vertices, name, tolerance, median_of(c.iterations),
                  c.converged ? "true" : "false", median_of(c.ms), c.energy);
    }
    std::fprintf(stderr,
                 "converge %s anisoform-flatten iterations only, lbfgs (%d patch vertices, tolerance %g, %d runs): "
                 "iterations %.0f -> %.0f, time plain/lbfgs %.2f (goal >= 5)\n",
                 problem.name.c_str(), patch.mesh.num_vertices(), tolerance, runs, median_of(plain.iterations),
                 median_of(lbfgs.iterations), median_of(speedup));
    note_unconverged(problem.name, "anisoform-flatten iterations only", plain.converged, lbfgs.converged);
    const int at = first_iteration_at(lbfgs.energy_history, plain.energy);
    if (at == 0) {
      std::fprintf(stderr, "converge %s anisoform-flatten iterations only: lbfgs never reached the plain run's energy\n",
                   problem.name.c_str());
      std::fflush(stdout);
      return;
    }
    settings.tolerance = 0.0;
    settings.max_iterations = at;
    speedup.clear();
    for (int r = 0; r < runs; ++r) {
      solve(true, to_energy);
      speedup.push_back(plain.ms[r] / to_energy.ms.back());
    }
    std::printf("{\"mesh\":\"%s\",\"vertices\":%d,\"impl\":\"anisoform-flatten\",\"phase\":\"iterations\","
                "\"acceleration\":\"lbfgs\",\"to\":\"plain-energy\",\"iterations\":%d,\"ms\":%.2f,\"energy\":%.10g}\n",
                problem.name.c_str(), vertices, at, median_of(to_energy.ms), to_energy.energy);
    std::fflush(stdout);
    std::fprintf(stderr,
                 "converge %s anisoform-flatten iterations only, lbfgs to the plain run's energy: iterations %.0f -> %d, "
                 "time plain/lbfgs %.2f (goal >= 5)\n",
                 problem.name.c_str(), median_of(plain.iterations), at, median_of(speedup));
  } catch (const aniso::Error& e) {
    std::fprintf(stderr, "converge %s flatten iterations: skipped (%s)\n", problem.name.c_str(), e.what());
  }
}

}  // namespace

bool is_convergence_row(const std::string& name) {
  return name == "anisoform-arap" || name == "anisoform-anarap" || name == "anisoform-anarap-twist" ||
         name == "anisoform-flatten";
}

int run_convergence(const Problem& problem, double tolerance, int runs, int max_iterations,
                    const std::set<std::string>& only) {
  const auto wanted = [&only](const char* name) { return only.empty() || only.count(name) > 0; };
  const int n = problem.mesh.num_vertices();
  struct Row {
    const char* impl;
    aniso::DeformRequest request;
  };
  const std::vector<Row> rows = {{"anisoform-arap", arap_handles_request(problem)},
                                 {"anisoform-anarap", stretch_request(problem, aniso::Method::AnArap)},
                                 {"anisoform-anarap-twist", twist_request(problem)}};
  for (const Row& row : rows) {
    if (!wanted(row.impl)) continue;
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
    // The same tolerance leaves the plain iterations above the accelerated
    // energy (they crawl: each change is small long before the minimum), so
    // also: the accelerated solve timed to the energy the plain one ended at,
    // i.e. to the same result.
    for (std::size_t k = 1; k < variants.size(); ++k) {
      const Variant& v = variants[k];
      const int at = first_iteration_at(v.result.energy_history, plain.energy);
      if (at == 0) {
        // No row: it stalled or settled in another local minimum (README,
        // Accelerated iterations).
        std::fprintf(stderr, "converge %s %s %s never reached the plain run's energy (%.10g; it ended at %.10g)\n",
                     problem.name.c_str(), row.impl, v.name, plain.energy, v.result.energy);
        continue;
      }
      aniso::DeformRequest to_energy = request;
      to_energy.acceleration = v.acceleration;
      to_energy.max_iterations = at;
      to_energy.tolerance = 0.0;
      Converged timed;
      std::vector<double> speedup;
      try {
        for (int r = 0; r < runs; ++r) {
          solve_once(deformer, to_energy, timed);
          speedup.push_back(plain.ms[r] / timed.ms.back());
        }
      } catch (const std::exception& e) {
        std::fprintf(stderr, "anisoform_bench: %s failed on %s: %s\n", row.impl, problem.name.c_str(), e.what());
        return 3;
      }
      std::printf("{\"mesh\":\"%s\",\"vertices\":%d,\"impl\":\"%s\",\"acceleration\":\"%s\",\"to\":\"plain-energy\","
                  "\"iterations\":%d,\"ms\":%.1f,\"energy\":%.10g}\n",
                  problem.name.c_str(), n, row.impl, v.name, at, median_of(timed.ms), timed.energy);
      std::fprintf(stderr,
                   "converge %s %s %s to the plain run's energy (%.10g): iterations %.0f -> %d, time plain/%s %.2f "
                   "(goal >= 5)\n",
                   problem.name.c_str(), row.impl, v.name, plain.energy, median_of(plain.iterations), at, v.name,
                   median_of(speedup));
    }
    std::fflush(stdout);
  }
  if (wanted("anisoform-flatten")) {
    run_flatten_convergence(problem, tolerance, runs, max_iterations);
    run_flatten_iterations(problem, tolerance, runs, max_iterations);
  }
  return 0;
}

}  // namespace aniso_bench
