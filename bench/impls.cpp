// The floor (Eigen's own SimplicialLDLT) and the three Anisoform solvers, each
// timed from a fresh start (a new Deformer per run), exactly as documented in
// bench/README.md.
#include "impls.h"

#include <algorithm>
#include <chrono>
#include <ctime>
#include <stdexcept>
#include <vector>

#include <Eigen/SparseCholesky>

#include "anisoform/deformer.h"
#include "anisoform/laplacian.h"

namespace aniso_bench {

namespace {
ClockKind g_clock = ClockKind::Wall;
}  // namespace

void set_clock(ClockKind kind) { g_clock = kind; }
ClockKind clock_kind() { return g_clock; }

double now_ms() {
  if (g_clock == ClockKind::Cpu) {
    timespec ts{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return 1e3 * static_cast<double>(ts.tv_sec) + 1e-6 * static_cast<double>(ts.tv_nsec);
  }
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

namespace {

using Stamp = double;
Stamp stamp() { return now_ms(); }
double ms_since(Stamp start) { return now_ms() - start; }

double mean_displacement(const aniso::Mesh& rest, const aniso::Positions& V) {
  return (V - rest.V).rowwise().norm().mean();
}

void require(bool ok, const char* what) {
  if (!ok) throw std::runtime_error(what);
}

// Iterative methods: a fresh Deformer, a first deform() of one iteration
// (cold: pays the factorization and every lazily built structure), then the
// request with its N iterations (warm start from the first result), timed
// around the call and divided by the iterations it ran.
Sample run_iterative(const Problem& problem, const aniso::DeformRequest& request) {
  Sample sample;
  aniso::Mesh copy = problem.mesh;
  const auto t0 = stamp();
  aniso::Deformer deformer(std::move(copy));
  sample.setup_ms = ms_since(t0);
  // The first call runs a single iteration: it is there for its precompute.
  aniso::DeformRequest warm_up = request;
  warm_up.max_iterations = 1;
  const auto t1 = stamp();
  const aniso::DeformResult first = deformer.deform(warm_up);
  const double first_ms = ms_since(t1);
  const auto t2 = stamp();
  const aniso::DeformResult second = deformer.deform(request);
  const double second_ms = ms_since(t2);
  require(second.factorizations == 1, "a second deform() refactored");
  require(second.iterations >= 1, "deform() ran no iteration");
  sample.iteration_ms = second_ms / second.iterations;
  // Wall: the first call's own precompute_ms. CPU: the Deformer's internal
  // stopwatch is wall time, so the precompute is what the first call cost
  // beyond its iterations at the warm per-iteration rate.
  const double first_precompute = clock_kind() == ClockKind::Wall
                                      ? first.precompute_ms
                                      : std::max(0.0, first_ms - first.iterations * sample.iteration_ms);
  sample.precompute_ms = sample.setup_ms + first_precompute;
  sample.first_call_ms = (first_ms - first_precompute) / std::max(first.iterations, 1);
  sample.iterations = second.iterations;
  sample.mean_displacement = mean_displacement(problem.mesh, second.V);
  return sample;
}


}  // namespace

double median_of(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const std::size_t m = v.size() / 2;
  return v.size() % 2 ? v[m] : 0.5 * (v[m - 1] + v[m]);
}

aniso::DeformRequest stretch_request(const Problem& problem, aniso::Method method) {
  aniso::DeformRequest request;
  request.method = method;
  request.selection = problem.top_half;
  request.direction.kind = aniso::DirectionSource::Kind::Global;
  request.direction.vector = problem.direction;
  request.transform.su = 1.5;
  return request;
}

aniso::DeformRequest twist_request(const Problem& problem) {
  aniso::DeformRequest request = stretch_request(problem, aniso::Method::AnArap);
  request.transform.su = 1.0;
  request.transform.twist = true;
  request.transform.twist_axis = problem.direction.normalized();
  // About the top half's weighted centroid, as the app and the CLI default to.
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  double weight = 0.0;
  for (int i = 0; i < problem.mesh.num_vertices(); ++i) {
    centroid += problem.top_half[i] * problem.mesh.V.row(i).transpose();
    weight += problem.top_half[i];
  }
  request.transform.twist_origin = centroid / weight;
  // Half a turn over the mesh's length along the axis.
  const Eigen::VectorXd along = problem.mesh.V * request.transform.twist_axis;
  request.transform.twist_degrees_per_unit = 180.0 / (along.maxCoeff() - along.minCoeff());
  return request;
}

aniso::DeformRequest arap_handles_request(const Problem& problem) {
  aniso::DeformRequest request;
  request.method = aniso::Method::Arap;
  request.pins = problem.fixed;
  request.handles = problem.moved;
  request.handle_offset = problem.offset;
  return request;
}

Sample run_eigen_ldlt(const Problem& problem, int solves) {
  const aniso::Mesh& mesh = problem.mesh;
  const int n = mesh.num_vertices();
  Sample sample;
  const auto t0 = stamp();
  const aniso::CotanWeights weights = aniso::cotangent_weights(mesh);
  const Eigen::SparseMatrix<double> L = aniso::cotangent_laplacian(mesh, weights);
  std::vector<int> free_of(n, 0);
  for (int p : problem.fixed) free_of[p] = -1;
  int nf = 0;
  for (int i = 0; i < n; ++i) {
    if (free_of[i] >= 0) free_of[i] = nf++;
  }
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(static_cast<std::size_t>(L.nonZeros()));
  for (int col = 0; col < L.outerSize(); ++col) {
    if (free_of[col] < 0) continue;
    for (Eigen::SparseMatrix<double>::InnerIterator it(L, col); it; ++it) {
      const int r = free_of[it.row()];
      if (r >= 0) triplets.emplace_back(r, free_of[col], it.value());
    }
  }
  Eigen::SparseMatrix<double> Lff(nf, nf);
  Lff.setFromTriplets(triplets.begin(), triplets.end());
  sample.setup_ms = ms_since(t0);
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt;  // AMD ordering (Eigen's default)
  ldlt.compute(Lff);
  sample.precompute_ms = ms_since(t0);
  require(ldlt.info() == Eigen::Success, "Eigen SimplicialLDLT failed");
  // Strictly lower nonzeros of L; ours factors the same matrix in the same (AMD) order.
  sample.factor_nonzeros = ldlt.matrixL().nestedExpression().nonZeros();

  Eigen::MatrixXd B(nf, 3);
  for (int i = 0; i < n; ++i) {
    if (free_of[i] >= 0) B.row(free_of[i]) = mesh.V.row(i);
  }
  Eigen::MatrixXd X(nf, 3);
  std::vector<double> times;
  for (int s = 0; s < solves; ++s) {
    const auto t = stamp();
    X = ldlt.solve(B);
    times.push_back(ms_since(t));
  }
  sample.first_call_ms = times.front();
  sample.iteration_ms = median_of(times);
  sample.iterations = 1;
  sample.mean_displacement = (Lff * X - B).norm() / std::max(B.norm(), 1e-300);  // residual
  return sample;
}

Sample run_anisoform_arap(const Problem& problem, int iterations) {
  aniso::DeformRequest request = arap_handles_request(problem);
  request.acceleration = aniso::Acceleration::None;  // like for like with CGAL's plain iterations
  request.max_iterations = iterations;
  request.tolerance = 0.0;
  return run_iterative(problem, request);
}

Sample run_anisoform_anarap(const Problem& problem, int iterations) {
  aniso::DeformRequest request = stretch_request(problem, aniso::Method::AnArap);
  request.acceleration = aniso::Acceleration::None;  // like for like with CGAL's plain iterations
  request.max_iterations = iterations;
  request.tolerance = 0.0;
  return run_iterative(problem, request);
}

// One change of amount: su alternates 1.6 / 1.5 after the first call; each
// deform() is timed whole (targets, right-hand side, solve, gauge), median.
Sample run_anisoform_andefgrad(const Problem& problem, int changes) {
  Sample sample;
  aniso::Mesh copy = problem.mesh;
  const auto t0 = stamp();
  aniso::Deformer deformer(std::move(copy));
  sample.setup_ms = ms_since(t0);
  aniso::DeformRequest request = stretch_request(problem, aniso::Method::AnDefGrad);
  const auto t1 = stamp();
  const aniso::DeformResult first = deformer.deform(request);
  const double first_ms = ms_since(t1);
  std::vector<double> times;
  aniso::DeformResult result;
  for (int c = 0; c < changes; ++c) {
    request.transform.su = c % 2 == 0 ? 1.6 : 1.5;
    const auto t = stamp();
    result = deformer.deform(request);
    times.push_back(ms_since(t));
  }
  require(result.factorizations == 1, "a change of amount refactored");
  sample.iteration_ms = median_of(times);
  // As in run_iterative: CPU mode charges the first call's excess over a change.
  const double first_precompute = clock_kind() == ClockKind::Wall
                                      ? first.precompute_ms
                                      : std::max(0.0, first_ms - sample.iteration_ms);
  sample.precompute_ms = sample.setup_ms + first_precompute;
  sample.first_call_ms = first_ms - first_precompute;
  sample.iterations = 1;
  sample.mean_displacement = mean_displacement(problem.mesh, result.V);
  return sample;
}

}  // namespace aniso_bench
