// Principal curvatures and directions (Rusinkiewicz 2004, "Estimating
// curvatures and their derivatives on triangle meshes"), and the smoothed
// principal direction field of the paper's Fig. 8.
//
// "Min" and "max" are by magnitude: k_min is the principal curvature of least
// |k| (the direction that bends least, e.g. along a tube), k_max the one of
// greatest |k|. Ordered by signed value they would swap with the normals:
// with the faces wound the other way every k changes sign, and a tube's
// "min" direction would run around it instead of along it.
//
// Sign convention of the values: with outward (counter-clockwise) normals a
// convex surface has positive curvature (a sphere of radius R: k_min = k_max
// = 1/R); wound inwards, the same surface has -1/R.
#include "directions/curvature.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "anisoform/error.h"
#include "geometry/frames.h"
#include "mesh/topology.h"
#include "directions/direction_field_transport.h"
#include "directions/line_orientation.h"

namespace aniso {
namespace {

// Second fundamental form [[a, b], [b, c]] in some 2D tangent basis.
struct Tensor2 {
  double a = 0.0;
  double b = 0.0;
  double c = 0.0;
};

// Per-face tensor in the face basis (u, v) fitted by least squares to the
// change of the vertex normals along the three edges: II * (e.u, e.v) =
// (dn.u, dn.v) for every edge e with normal difference dn.
Tensor2 face_tensor(const std::array<Eigen::Vector3d, 3>& p, const std::array<Eigen::Vector3d, 3>& n,
                    const Eigen::Vector3d& u, const Eigen::Vector3d& v) {
  Eigen::Matrix3d normal_matrix = Eigen::Matrix3d::Zero();
  Eigen::Vector3d rhs = Eigen::Vector3d::Zero();
  for (int k = 0; k < 3; ++k) {
    const int from = (k + 1) % 3;
    const int to = (k + 2) % 3;
    const Eigen::Vector3d edge = p[to] - p[from];
    const Eigen::Vector3d dn = n[to] - n[from];
    const double eu = edge.dot(u);
    const double ev = edge.dot(v);
    const double dnu = dn.dot(u);
    const double dnv = dn.dot(v);
    // Rows of the overdetermined system in the unknowns (a, b, c).
    const Eigen::Vector3d row1(eu, ev, 0.0);  // a eu + b ev = dnu
    const Eigen::Vector3d row2(0.0, eu, ev);  // b eu + c ev = dnv
    normal_matrix += row1 * row1.transpose() + row2 * row2.transpose();
    rhs += row1 * dnu + row2 * dnv;
  }
  const Eigen::Vector3d abc = normal_matrix.ldlt().solve(rhs);
  return {abc[0], abc[1], abc[2]};
}

// Mixed Voronoi areas of the three corners (Meyer et al. 2003): the Voronoi
// region inside the triangle when it is not obtuse, else half the area for
// the obtuse corner and a quarter for the others. They sum to the triangle area.
std::array<double, 3> corner_areas(const std::array<Eigen::Vector3d, 3>& p) {
  const double area = 0.5 * (p[1] - p[0]).cross(p[2] - p[0]).norm();
  std::array<double, 3> cot{};
  std::array<double, 3> dot{};
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector3d a = p[(k + 1) % 3] - p[k];
    const Eigen::Vector3d b = p[(k + 2) % 3] - p[k];
    dot[k] = a.dot(b);
    cot[k] = dot[k] / a.cross(b).norm();
  }
  std::array<double, 3> result{};
  for (int k = 0; k < 3; ++k) {
    if (dot[k] < 0.0) {
      result = {0.25 * area, 0.25 * area, 0.25 * area};
      result[k] = 0.5 * area;
      return result;
    }
  }
  for (int k = 0; k < 3; ++k) {
    const int next = (k + 1) % 3;
    const int prev = (k + 2) % 3;
    // The edge k-next is opposite corner prev, the edge k-prev opposite next.
    result[k] = ((p[next] - p[k]).squaredNorm() * cot[prev] + (p[prev] - p[k]).squaredNorm() * cot[next]) / 8.0;
  }
  return result;
}

// The face tensor seen in a vertex basis: the vertex basis is first rotated
// into the face plane (its normal onto the face normal), then II is evaluated
// on the rotated basis vectors.
Tensor2 tensor_in_vertex_basis(const Tensor2& face, const Eigen::Vector3d& u, const Eigen::Vector3d& v,
                               const Eigen::Vector3d& face_normal, const field::TangentBasis& vertex) {
  const Eigen::Vector3d e1 = field::rotate_between_normals(vertex.e1, vertex.n, face_normal);
  const Eigen::Vector3d e2 = field::rotate_between_normals(vertex.e2, vertex.n, face_normal);
  const Eigen::Vector2d r1(e1.dot(u), e1.dot(v));
  const Eigen::Vector2d r2(e2.dot(u), e2.dot(v));
  Eigen::Matrix2d II;
  II << face.a, face.b, face.b, face.c;
  return {r1.dot(II * r1), r1.dot(II * r2), r2.dot(II * r2)};
}

bool finite_triangle(const std::array<Eigen::Vector3d, 3>& p, const std::array<Eigen::Vector3d, 3>& n) {
  for (int k = 0; k < 3; ++k) {
    if (!p[k].allFinite() || !n[k].allFinite()) return false;
  }
  return true;
}

std::vector<field::TangentBasis> vertex_bases(const Positions& normals) {
  std::vector<field::TangentBasis> bases(normals.rows());
  for (Eigen::Index i = 0; i < normals.rows(); ++i) bases[i] = field::tangent_basis(normals.row(i).transpose());
  return bases;
}

// Area-weighted mean of the face tensors around every vertex, in its basis.
std::vector<Tensor2> vertex_tensors(const Mesh& mesh, const Positions& normals,
                                    const std::vector<field::TangentBasis>& bases) {
  std::vector<Tensor2> sum(mesh.num_vertices());
  std::vector<double> weight(mesh.num_vertices(), 0.0);
  for (int t = 0; t < mesh.num_triangles(); ++t) {
    std::array<Eigen::Vector3d, 3> p;
    std::array<Eigen::Vector3d, 3> n;
    for (int k = 0; k < 3; ++k) {
      p[k] = mesh.V.row(mesh.F(t, k)).transpose();
      n[k] = normals.row(mesh.F(t, k)).transpose();
    }
    if (!finite_triangle(p, n)) continue;
    const Eigen::Vector3d cross = (p[1] - p[0]).cross(p[2] - p[0]);
    const double longest = std::max({(p[1] - p[0]).squaredNorm(), (p[2] - p[1]).squaredNorm(),
                                     (p[0] - p[2]).squaredNorm()});
    if (cross.norm() <= 1e-12 * longest) continue;  // zero area: no plane, no tensor
    const Eigen::Vector3d face_normal = cross.normalized();
    const Eigen::Vector3d u = (p[2] - p[1]).normalized();
    const Eigen::Vector3d v = face_normal.cross(u);
    const Tensor2 face = face_tensor(p, n, u, v);
    const std::array<double, 3> areas = corner_areas(p);
    for (int k = 0; k < 3; ++k) {
      const int vertex = mesh.F(t, k);
      const Tensor2 local = tensor_in_vertex_basis(face, u, v, face_normal, bases[vertex]);
      sum[vertex].a += areas[k] * local.a;
      sum[vertex].b += areas[k] * local.b;
      sum[vertex].c += areas[k] * local.c;
      weight[vertex] += areas[k];
    }
  }
  for (int i = 0; i < mesh.num_vertices(); ++i) {
    if (weight[i] > 0.0) sum[i] = {sum[i].a / weight[i], sum[i].b / weight[i], sum[i].c / weight[i]};
  }
  return sum;
}

// Applies `smoothing_steps` Jacobi steps of one-ring averaging to line values
// u (doubled angles, see direction_field_transport.h), each neighbour
// transported into the vertex's basis first.
void smooth_line_values(const Mesh& mesh, const VertexAdjacency& adjacency,
                        const std::vector<field::TangentBasis>& bases, int smoothing_steps,
                        std::vector<std::complex<double>>& u) {
  std::vector<std::complex<double>> transport(adjacency.neighbors.size());
  for (int i = 0; i < mesh.num_vertices(); ++i) {
    for (int k = adjacency.offsets[i]; k < adjacency.offsets[i + 1]; ++k) {
      transport[k] = field::line_transport(bases[adjacency.neighbors[k]], bases[i]);
    }
  }
  std::vector<std::complex<double>> next(u.size());
  for (int step = 0; step < smoothing_steps; ++step) {
    for (int i = 0; i < mesh.num_vertices(); ++i) {
      std::complex<double> total = u[i];
      for (int k = adjacency.offsets[i]; k < adjacency.offsets[i + 1]; ++k) {
        total += transport[k] * u[adjacency.neighbors[k]];
      }
      next[i] = total / double(1 + adjacency.offsets[i + 1] - adjacency.offsets[i]);
    }
    u.swap(next);
  }
}

// Principal curvatures and directions from the vertex tensors, each in its basis.
PrincipalCurvature principal_curvature_in(const Mesh& mesh, const Positions& normals,
                                          const std::vector<field::TangentBasis>& bases) {
  const std::vector<Tensor2> tensors = vertex_tensors(mesh, normals, bases);
  const int n = mesh.num_vertices();
  PrincipalCurvature result;
  result.min_direction.resize(n, 3);
  result.max_direction.resize(n, 3);
  result.k_min.resize(n);
  result.k_max.resize(n);
  for (int i = 0; i < n; ++i) {
    const Tensor2& II = tensors[i];
    // Closed-form eigen-decomposition of the symmetric 2x2 tensor.
    const double mean = 0.5 * (II.a + II.c);
    const double half_gap = std::hypot(0.5 * (II.a - II.c), II.b);
    // The eigenvector of the larger eigenvalue, mean + half_gap; the other
    // one, mean - half_gap, is across it.
    const double upper_angle = 0.5 * std::atan2(2.0 * II.b, II.a - II.c);
    const Eigen::Vector3d upper = std::cos(upper_angle) * bases[i].e1 + std::sin(upper_angle) * bases[i].e2;
    const Eigen::Vector3d lower = bases[i].n.cross(upper);
    const double k_upper = mean + half_gap;
    const double k_lower = mean - half_gap;
    // By magnitude, not by value (see the top of the file).
    const bool upper_bends_more = std::abs(k_upper) >= std::abs(k_lower);
    result.k_max[i] = upper_bends_more ? k_upper : k_lower;
    result.k_min[i] = upper_bends_more ? k_lower : k_upper;
    result.max_direction.row(i) = (upper_bends_more ? upper : lower).transpose();
    result.min_direction.row(i) = (upper_bends_more ? lower : upper).transpose();
  }
  return result;
}

// How much more the max direction bends than the min one: |k_max| - |k_min|,
// the magnitude gap that tells the two apart (0 at an umbilic point, and at a
// saddle bent equally both ways, whose two directions swap with the normals).
double magnitude_gap(const PrincipalCurvature& curvature, Eigen::Index i) {
  return std::abs(curvature.k_max[i]) - std::abs(curvature.k_min[i]);
}

// Curvature is 1 / length: a curvature below this over the mesh's size
// (its bounding-box diagonal) is flat.
constexpr double kFlatCurvatureTimesSize = 1e-6;

// A surface curved alike in every direction at every vertex (a plane, a
// sphere made exactly) has no principal direction: its "directions" would be
// the eigen-solver's arbitrary choice. The gap |k_max| - |k_min| is measured
// against the mesh's size (curvature is 1 / length).
void refuse_without_principal_directions(const Mesh& mesh, const PrincipalCurvature& curvature) {
  const Eigen::Index n = curvature.k_max.size();
  if (n == 0) return;
  const double size = shape_bounding_box(mesh).diagonal();
  double largest_gap = 0.0;
  for (Eigen::Index i = 0; i < n; ++i) {
    const double gap = magnitude_gap(curvature, i);
    if (std::isfinite(gap)) largest_gap = std::max(largest_gap, gap);
  }
  if (largest_gap * size > kFlatCurvatureTimesSize) return;
  fail(ErrorCode::BadParameter,
       "the surface has no principal curvature directions: it is curved alike in every direction at every vertex "
       "(flat, or a sphere), so curvature gives no direction; use an axis, a screen drag or a painted field");
}

}  // namespace

PrincipalCurvature principal_curvature(const Mesh& mesh) {
  const Positions normals = vertex_normals(mesh);
  return principal_curvature_in(mesh, normals, vertex_bases(normals));
}

std::vector<char> lacks_principal_direction(const Mesh& mesh) {
  const PrincipalCurvature curvature = principal_curvature(mesh);
  const double size = shape_bounding_box(mesh).diagonal();
  std::vector<char> lacking(mesh.num_vertices(), 0);
  for (int i = 0; i < mesh.num_vertices(); ++i) {
    const double total = std::abs(curvature.k_max[i]) + std::abs(curvature.k_min[i]);
    const bool flat = !(total * size > kFlatCurvatureTimesSize);
    lacking[i] = flat || !(magnitude_gap(curvature, i) > kUnreliableCurvatureAnisotropy * total);
  }
  return lacking;
}

std::string unreliable_curvature_warning(const std::vector<char>& lacking, const Eigen::VectorXd& weights) {
  int selected = 0, unreliable = 0;
  for (Eigen::Index i = 0; i < weights.size(); ++i) {
    if (!(weights[i] > 0.0)) continue;
    ++selected;
    if (lacking[static_cast<std::size_t>(i)]) ++unreliable;
  }
  if (selected == 0 || !(unreliable > kUnreliableCurvatureShare * selected)) return "";
  const int percent = static_cast<int>(std::lround(100.0 * unreliable / selected));
  return std::to_string(percent) + " % of the selected vertices (" + std::to_string(unreliable) + " of " +
         std::to_string(selected) +
         ") have no clear principal curvature direction (flat there, or curved about alike every way, "
         "as a sphere): the curvature direction there is the smoothing's or the triangulation's guess, "
         "not the shape's; an axis, a screen drag or arrows say it";
}

// Each vertex's line enters the averaging with weight |k_max| - |k_min|, its
// confidence: near-umbilic vertices, whose raw direction is noise, carry
// almost none and take the direction of their neighbours.
void validate_curvature_smoothing(int steps) {
  if (steps < 0 || steps > kMaxCurvatureSmoothing) {
    fail(ErrorCode::BadParameter, "curvature smoothing steps must be an integer from 0 to " +
                                      std::to_string(kMaxCurvatureSmoothing) + ", got " + std::to_string(steps));
  }
}

Positions curvature_direction_field(const Mesh& mesh, CurvatureDirection which, int smoothing_steps) {
  validate_curvature_smoothing(smoothing_steps);
  const Positions normals = vertex_normals(mesh);
  const std::vector<field::TangentBasis> bases = vertex_bases(normals);
  const PrincipalCurvature curvature = principal_curvature_in(mesh, normals, bases);
  refuse_without_principal_directions(mesh, curvature);
  const Positions& raw = which == CurvatureDirection::Min ? curvature.min_direction : curvature.max_direction;
  const VertexAdjacency adjacency = vertex_adjacency(mesh.F, mesh.num_vertices());
  Positions result = raw;
  if (smoothing_steps > 0) {
    std::vector<std::complex<double>> u(mesh.num_vertices());
    for (int i = 0; i < mesh.num_vertices(); ++i) {
      const double confidence = magnitude_gap(curvature, i);
      u[i] = std::isfinite(confidence) ? confidence * field::line_to_complex(raw.row(i).transpose(), bases[i])
                                       : std::complex<double>(0.0);
    }
    smooth_line_values(mesh, adjacency, bases, smoothing_steps, u);
    for (int i = 0; i < mesh.num_vertices(); ++i) {
      // A vertex no confident direction reached (a flat region) keeps its raw one.
      if (std::abs(u[i]) > 0.0) result.row(i) = field::complex_to_line(u[i], bases[i]).transpose();
    }
  }
  // The eigen-solver's signs are arbitrary from vertex to vertex (half of an
  // open cylinder's axial directions pointed +z, half -z), and a shear or a
  // rotation about cu/cv turns each vertex's way: the shape tore where signs
  // met. Signs agreeing across edges keep such transforms whole.
  orient_line_field(adjacency, std::vector<char>(mesh.num_vertices(), 0),
                    std::vector<char>(mesh.num_vertices(), 1), result);
  return result;
}

}  // namespace aniso
