// The peer: CGAL::Surface_mesh_deformation (Debian libcgal-dev 5.5,
// header-only, GPL: compiled into this benchmark only) with its default
// deformation tag SPOKES_AND_RIMS, its default solver (Eigen SparseLU with
// COLAMD) and its default closest-rotation traits (Eigen polar).
//
// Same problem as anisoform-arap: region of interest = every vertex; control
// vertices = the 5 % highest (target: rest + offset) and the 5 % lowest
// (target: rest, i.e. fixed).
//   precompute_ms: construction of the deformation object (halfedge weights),
//                  ROI and control insertion, preprocess() (region of
//                  solution, Laplacian assembly and LU factorization).
//   iteration_ms:  deform(N, 0) (tolerance 0: no energy evaluation) divided
//                  by N, after a first deform(1, 0) that warms up, exactly as
//                  the anisoform rows time a warm-started second call.
// Building the CGAL Surface_mesh from our Mesh is outside all timing.
#include "impls.h"

#include <stdexcept>
#include <vector>

#if defined(ANISO_HAVE_CGAL)
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_deformation.h>
#endif

namespace aniso_bench {

#if defined(ANISO_HAVE_CGAL)

namespace {

using Kernel = CGAL::Simple_cartesian<double>;
using Point = Kernel::Point_3;
using SurfaceMesh = CGAL::Surface_mesh<Point>;
using VertexIndex = SurfaceMesh::Vertex_index;
using Deformation = CGAL::Surface_mesh_deformation<SurfaceMesh, CGAL::Default, CGAL::Default,
                                                   CGAL::SPOKES_AND_RIMS>;
double ms_since(double start) { return now_ms() - start; }

SurfaceMesh to_cgal(const aniso::Mesh& mesh) {
  SurfaceMesh sm;
  sm.reserve(static_cast<SurfaceMesh::size_type>(mesh.num_vertices()),
             static_cast<SurfaceMesh::size_type>(3 * mesh.num_triangles() / 2),
             static_cast<SurfaceMesh::size_type>(mesh.num_triangles()));
  for (int i = 0; i < mesh.num_vertices(); ++i) sm.add_vertex(Point(mesh.V(i, 0), mesh.V(i, 1), mesh.V(i, 2)));
  for (int t = 0; t < mesh.num_triangles(); ++t) {
    const auto f = sm.add_face(VertexIndex(mesh.F(t, 0)), VertexIndex(mesh.F(t, 1)), VertexIndex(mesh.F(t, 2)));
    if (f == SurfaceMesh::null_face()) {
      throw std::runtime_error("CGAL Surface_mesh rejects triangle " + std::to_string(t) +
                               " (non-manifold or inconsistently oriented mesh)");
    }
  }
  return sm;
}

}  // namespace

bool have_cgal() { return true; }

Sample run_cgal_arap(const Problem& problem, int iterations) {
  SurfaceMesh sm = to_cgal(problem.mesh);
  Sample sample;
  const auto t0 = now_ms();
  Deformation deformation(sm);
  std::vector<VertexIndex> all;
  all.reserve(sm.number_of_vertices());
  for (VertexIndex v : sm.vertices()) all.push_back(v);
  deformation.insert_roi_vertices(all.begin(), all.end());
  for (int i : problem.moved) deformation.insert_control_vertex(VertexIndex(i));
  for (int i : problem.fixed) deformation.insert_control_vertex(VertexIndex(i));
  sample.setup_ms = ms_since(t0);
  if (!deformation.preprocess()) throw std::runtime_error("CGAL preprocess() failed");
  sample.precompute_ms = ms_since(t0);

  const Kernel::Vector_3 offset(problem.offset.x(), problem.offset.y(), problem.offset.z());
  for (int i : problem.moved) {
    deformation.set_target_position(VertexIndex(i), sm.point(VertexIndex(i)) + offset);
  }
  const auto t1 = now_ms();
  deformation.deform(1, 0.0);
  sample.first_call_ms = ms_since(t1);
  const auto t2 = now_ms();
  deformation.deform(static_cast<unsigned>(iterations), 0.0);
  sample.iteration_ms = ms_since(t2) / iterations;
  sample.iterations = iterations;

  double total = 0.0;
  for (int i = 0; i < problem.mesh.num_vertices(); ++i) {
    const Point& p = sm.point(VertexIndex(i));
    total += (Eigen::Vector3d(p.x(), p.y(), p.z()) - problem.mesh.V.row(i).transpose()).norm();
  }
  sample.mean_displacement = total / problem.mesh.num_vertices();
  return sample;
}

#else

bool have_cgal() { return false; }

Sample run_cgal_arap(const Problem&, int) { throw std::runtime_error("built without CGAL"); }

#endif

}  // namespace aniso_bench
