// The Flattener: keeps what depends only on the patch (charts, start maps, the
// one factorization) and runs a flattening per request, ours or the baseline.
#include <chrono>
#include <cmath>
#include <optional>

#include "anisoform/limits.h"
#include "anisoform/mesh_check.h"
#include "flatten/flatten_pipeline.h"

namespace aniso {

namespace {

// The local/global iterations' share of the progress bar before a refinement.
constexpr double kLocalGlobalShareBeforeRefinement = 0.02;

Eigen::VectorXd target_areas(const TriangleCharts& charts, const FlattenTargets& targets) {
  return charts.area.cwiseProduct(targets.su).cwiseProduct(targets.sv);
}

}  // namespace

struct Flattener::Impl {
  Mesh input;
  FlattenPatch patch;
  TriangleNeighbours neighbours{patch};
  TriangleCharts charts;
  std::unique_ptr<ArapFlattening> arap;
  Eigen::MatrixX2d conformal_start;
  std::optional<Eigen::MatrixX2d> fold_free_start;  // built the first time it is needed
  int non_manifold_edges = 0;  // the patch's, for the user's warning (flatten_problem)

  struct Solved {
    Eigen::MatrixX2d uv;
    ArapFlattenReport report;
    int iterations = 0;
    const char* initialization = "lscm";
  };

  ArapFlattenReport iterate_from(const Eigen::MatrixX2d& start, const FlattenTargets& targets,
                                 const ArapFlattenSettings& settings, Eigen::MatrixX2d& uv) const {
    uv = start;
    scale_to_area(patch, target_areas(charts, targets), uv);
    return arap->solve(targets, settings, uv);
  }

  const Eigen::MatrixX2d& tutte_start() {
    if (!fold_free_start) {
      fold_free_start.emplace();
      tutte_embedding(patch, charts, *fold_free_start);
    }
    return *fold_free_start;
  }

  // The maps the stretch refinement may start from: the local/global result
  // and the two start maps at the wanted area. Where the guard stalled, the
  // result holds triangles squeezed to nearly nothing, which block every
  // step of the refinement; a start map then does better (the refinement
  // takes the one with the lowest energy).
  std::vector<Eigen::MatrixX2d> refinement_starts(const Eigen::MatrixX2d& solved_uv,
                                                  const FlattenTargets& targets) {
    std::vector<Eigen::MatrixX2d> starts{solved_uv, conformal_start, tutte_start()};
    for (std::size_t k = 1; k < starts.size(); ++k) scale_to_area(patch, target_areas(charts, targets), starts[k]);
    return starts;
  }

  // ARAP from the conformal start; if folds remain (ARAP cannot be trusted to
  // undo folds it starts with), again from the fold-free start, guarded.
  Solved solve(const FlattenTargets& targets, const ArapFlattenSettings& settings) {
    Solved solved;
    solved.report = iterate_from(conformal_start, targets, settings, solved.uv);
    solved.iterations = solved.report.iterations;
    if (solved.report.folded == 0) return solved;
    Eigen::MatrixX2d uv;
    const ArapFlattenReport report = iterate_from(tutte_start(), targets, settings, uv);
    solved.iterations += report.iterations;
    if (report.folded <= solved.report.folded) {
      solved.uv = std::move(uv);
      solved.report = report;
      solved.initialization = "tutte";
    }
    return solved;
  }
};

Flattener::Flattener(const Mesh& mesh, const std::vector<char>& vertex_mask)
    : impl_(std::make_unique<Impl>()) {
  Impl& im = *impl_;
  im.input = mesh;
  im.patch = extract_flatten_patch(mesh, vertex_mask);
  im.charts = triangle_charts(im.patch.mesh);
  im.arap = std::make_unique<ArapFlattening>(im.patch, im.charts);
  const MeshReport report = check_mesh(im.patch.mesh);
  im.non_manifold_edges = report.non_manifold_edges;
  try {
    lscm_free_boundary(im.patch, im.charts, im.conformal_start);
  } catch (const Error& error) {
    // What leaves the conformal map's system singular (a deformation solves
    // through both): zero-area triangles, or pieces joined at a single vertex
    // (a selection's bowties), which turn about it freely. Say which, by the
    // input's numbering.
    if (error.code() != ErrorCode::Numerical) throw;
    const auto named = [&](auto&& wanted, const std::vector<int>& numbering) {
      std::string list;
      int count = 0;
      for (const Problem& problem : report.problems) {
        if (!wanted(problem.kind)) continue;
        if (count < 3) list += (count > 0 ? ", " : "") + std::to_string(numbering[problem.element]);
        ++count;
      }
      return list + (count > 3 ? " ..." : "");
    };
    if (report.degenerate_triangles > 0) {
      const std::string faces = named([](ProblemKind k) {
        return k == ProblemKind::ZeroAreaTriangle || k == ProblemKind::RepeatedCorner;
      }, im.patch.input_face);
      fail(ErrorCode::Numerical, std::string(error.what()) + ": the patch has " +
                                     std::to_string(report.degenerate_triangles) + " zero-area triangle(s) (faces " +
                                     faces + "): remove them, or flatten a selection without them");
    }
    if (report.non_manifold_vertices > 0) {
      const std::string vertices = named([](ProblemKind k) { return k == ProblemKind::NonManifoldVertex; },
                                         im.patch.input_vertex);
      fail(ErrorCode::Numerical, std::string(error.what()) + ": the patch's pieces meet at single vertices (" +
                                     std::to_string(report.non_manifold_vertices) + ": vertices " + vertices +
                                     "), about which they turn freely: select whole faces around them, or flatten "
                                     "the pieces one at a time");
    }
    throw;
  }
}

Flattener::~Flattener() = default;

const FlattenPatch& Flattener::patch() const { return impl_->patch; }
const TriangleCharts& Flattener::charts() const { return impl_->charts; }
int Flattener::factorizations() const { return impl_->arap->factorizations(); }

FlattenResult Flattener::flatten(const FlattenOptions& options) {
  const auto started = std::chrono::steady_clock::now();
  // The hosts' readers (op JSON, CLI) refuse these first, naming their field.
  check_iteration_count(options.solver.max_iterations, "flatten: maxIterations");
  if (!(options.solver.tolerance >= 0.0) || !std::isfinite(options.solver.tolerance)) {
    fail(ErrorCode::BadParameter, "flatten: the tolerance must be a finite number >= 0");
  }
  Impl& im = *impl_;
  const FlattenPatch& patch = im.patch;
  const Triangles& F = patch.mesh.F;

  FlattenResult result;
  result.targets = flatten_targets(im.input, patch, im.charts, im.neighbours, options.directions, options.su,
                                   options.sv);
  const bool baseline = options.method == FlattenMethod::UniformBaseline;
  // The baseline flattens the same field without compression first.
  const FlattenTargets solved_targets =
      baseline ? with_uniform_amounts(result.targets, 1.0, 1.0) : result.targets;
  const bool refining = !baseline && options.solver.refine;
  // The progress bar by stages: the local/global iterations, then, before a
  // refinement (where they are only its start, 2 % of the time or less on the
  // test patches), each of its stages by its share (refine_stage_outlook).
  std::vector<StagedProgress::Stage> stages{{1.0, options.solver.tolerance}};
  if (refining) {
    stages.front().share = kLocalGlobalShareBeforeRefinement;
    for (StagedProgress::Stage stage : refine_stage_outlook(options.solver.tolerance)) {
      stage.share *= 1.0 - kLocalGlobalShareBeforeRefinement;
      stages.push_back(stage);
    }
  }
  StagedProgress bar(std::move(stages), options.solver.max_iterations);
  ArapFlattenSettings local_global = options.solver;
  local_global.progress = nullptr;
  RefineProgress refine_progress;
  if (options.progress) {
    local_global.progress = [&](int iteration, double energy) {
      return options.progress(bar.update(0, iteration, energy));
    };
    refine_progress = [&](int stage, int iteration, double energy) {
      return options.progress(bar.update(1 + stage, iteration, energy));
    };
  }
  Impl::Solved solved = im.solve(solved_targets, local_global);
  bool converged = solved.report.converged;
  bool refined_ran = false;
  if (refining) {
    const StretchRefineReport refined =
        refine_stretch(patch, im.charts, solved_targets, im.arap->pinned(), options.solver, solved.iterations,
                       im.refinement_starts(solved.uv, solved_targets), solved.uv, refine_progress);
    if (refined.start >= 0) {
      refined_ran = true;
      solved.iterations += refined.iterations;
      converged = refined.converged;
      if (refined.start > 0) solved.initialization = refined.start == 1 ? "lscm" : "tutte";
    }
  }
  result.uv = std::move(solved.uv);

  // The grainline: where the wanted field runs on average in the pattern. For
  // the baseline it is measured on the isometric flattening and is its axis
  // of scaling.
  const TriangleStretch solved_stretch = measure_stretch(F, im.charts, solved_targets, result.uv);
  result.grainline = mean_pattern_directions(patch, im.charts, solved_stretch);
  if (baseline) apply_uniform_scale(patch, im.charts, result.targets, result.grainline, result.uv);
  align_grainlines(patch, result.grainline, result.uv);
  layout_components(patch, result.uv);
  result.stretch = measure_stretch(F, im.charts, result.targets, result.uv);

  FlattenMetrics& metrics = result.metrics;
  summarize_stretch(im.charts, result.targets, result.stretch, metrics);
  metrics.triangles = patch.mesh.num_triangles();
  metrics.vertices = patch.mesh.num_vertices();
  metrics.components = patch.num_components;
  metrics.boundary_loops = static_cast<int>(patch.boundary_loops.size());
  metrics.flipped = count_folded(F, im.charts, result.uv);
  metrics.outline_crossings = count_outline_crossings(patch, result.uv);
  metrics.non_manifold_edges = im.non_manifold_edges;
  metrics.reoriented_faces = patch.reoriented_faces;
  metrics.dropped_faces = patch.dropped_faces;
  metrics.iterations = solved.iterations;
  metrics.energy = solved.report.energy;
  metrics.converged = converged;
  metrics.refined = refined_ran;
  metrics.capped = !converged && solved.iterations >= options.solver.max_iterations;
  metrics.filled_directions = result.targets.filled_directions;
  metrics.near_normal_directions = result.targets.near_normal_directions;
  metrics.initialization = solved.initialization;
  metrics.method = baseline ? "uniform-baseline" : "anisotropic";
  metrics.suggested_cuts = find_cut_regions(patch, im.charts, im.neighbours, result.targets, result.stretch);
  metrics.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return result;
}

FlattenOutput flatten(const Mesh& mesh, const std::vector<char>& vertex_mask,
                      const FlattenOptions& options) {
  const auto started = std::chrono::steady_clock::now();
  Flattener flattener(mesh, vertex_mask);
  FlattenOutput output{flattener.patch(), flattener.flatten(options)};
  // The one-shot call's time includes the precomputation.
  output.result.metrics.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return output;
}

}  // namespace aniso
