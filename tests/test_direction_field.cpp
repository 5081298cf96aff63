// Direction constraints and their propagation: exact oracles on the flat
// square (constant fields, linear interpolation of doubled angles and of
// amounts), tangency on curved meshes, line-field sign invariance, regions,
// errors and speed.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <vector>

#include <Eigen/Geometry>

#include "anisoform/direction_field.h"
#include "anisoform/error.h"
#include "geometry/frames.h"
#include "anisoform/laplacian.h"
#include "test_support.h"

using aniso::DirectionConstraint;

namespace {

using aniso::test::kPi;

using aniso::test::bad_parameter_message;

DirectionConstraint constraint(int vertex, const Eigen::Vector3d& direction) {
  DirectionConstraint c;
  c.vertex = vertex;
  c.direction = direction;
  return c;
}

DirectionConstraint constraint_with_amounts(int vertex, const Eigen::Vector3d& direction, double su,
                                            double sv) {
  DirectionConstraint c = constraint(vertex, direction);
  c.su = su;
  c.sv = sv;
  c.has_amounts = true;
  return c;
}

// A flat mesh in the plane y = 0 bounded by an axis-aligned rectangle;
// in-plane coordinates are x and z.
struct FlatSquare {
  aniso::Mesh mesh;
  aniso::BoundingBox box;

  bool on_side_x(int i, double x) const { return std::abs(mesh.V(i, 0) - x) < 1e-9; }
  bool on_boundary(int i) const {
    return on_side_x(i, box.min.x()) || on_side_x(i, box.max.x()) ||
           std::abs(mesh.V(i, 2) - box.min.z()) < 1e-9 || std::abs(mesh.V(i, 2) - box.max.z()) < 1e-9;
  }
  double t_of(int i) const { return (mesh.V(i, 0) - box.min.x()) / (box.max.x() - box.min.x()); }
};

// open/plane.off: a flat square in the plane y = 0.
FlatSquare plane_off() {
  FlatSquare square;
  square.mesh = aniso::test::load("open/plane.off");
  square.box = aniso::bounding_box(square.mesh.V);
  return square;
}

// A flat rectangle [0, n] x [0, m sqrt(3)/2] in the plane y = 0, made of
// equilateral triangles with half-triangles closing the left and right sides,
// so all four sides are straight and every edge weight is clearly positive
// (plane.off's right-angled grid has edges whose weights cancel to zero).
FlatSquare equilateral_rectangle(int n, int m) {
  FlatSquare flat;
  std::vector<std::vector<int>> rows(m + 1);
  std::vector<Eigen::Vector3d> points;
  for (int j = 0; j <= m; ++j) {
    std::vector<double> xs;
    if (j % 2 == 0) {
      for (int i = 0; i <= n; ++i) xs.push_back(i);
    } else {
      xs.push_back(0.0);
      for (int i = 0; i < n; ++i) xs.push_back(i + 0.5);
      xs.push_back(n);
    }
    for (double x : xs) {
      rows[j].push_back(static_cast<int>(points.size()));
      points.emplace_back(x, 0.0, j * std::sqrt(3.0) / 2.0);
    }
  }
  std::vector<Eigen::Vector3i> triangles;
  for (int j = 0; j < m; ++j) {
    // Zip the two rows together from left to right.
    const std::vector<int>& below = rows[j];
    const std::vector<int>& above = rows[j + 1];
    std::size_t a = 0, b = 0;
    while (a + 1 < below.size() || b + 1 < above.size()) {
      // The row whose next vertex comes first; on a tie (the right side),
      // the one lagging behind, which avoids a 120-degree triangle.
      const bool advance_below =
          b + 1 == above.size() ||
          (a + 1 < below.size() && std::make_pair(points[below[a + 1]].x(), points[below[a]].x()) <
                                       std::make_pair(points[above[b + 1]].x(), points[above[b]].x()));
      if (advance_below) {
        triangles.emplace_back(below[a], above[b], below[a + 1]);
        ++a;
      } else {
        triangles.emplace_back(below[a], above[b], above[b + 1]);
        ++b;
      }
    }
  }
  flat.mesh.V.resize(points.size(), 3);
  for (std::size_t i = 0; i < points.size(); ++i) flat.mesh.V.row(i) = points[i].transpose();
  flat.mesh.F.resize(triangles.size(), 3);
  for (std::size_t t = 0; t < triangles.size(); ++t) flat.mesh.F.row(t) = triangles[t].transpose();
  flat.box = aniso::bounding_box(flat.mesh.V);
  const Eigen::SparseMatrix<double> L =
      aniso::cotangent_laplacian(flat.mesh, aniso::cotangent_weights(flat.mesh));
  for (int k = 0; k < L.outerSize(); ++k) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(L, k); it; ++it) {
      if (it.row() != it.col()) REQUIRE(it.value() < 0.0);  // every edge weight positive
    }
  }
  return flat;
}

// A tangent direction at vertex i that is well away from the normal.
Eigen::Vector3d some_tangent(const aniso::Positions& normals, int i, const Eigen::Vector3d& hint) {
  const Eigen::Vector3d n = normals.row(i).transpose();
  Eigen::Vector3d d = hint - hint.dot(n) * n;
  if (d.norm() < 0.3) d = n.cross(Eigen::Vector3d(hint.y(), hint.z(), hint.x()));
  return d.normalized() + 0.4 * n;  // deliberately not tangent: it must be projected
}

}  // namespace

TEST_CASE("field: parse_direction_constraints reads indices, directions and optional amounts", "[field]") {
  const auto constraints = aniso::parse_direction_constraints(
      "# arrows\n12 1 0 0\n\n13 0 1 0 0.8\r\n14 0 0 1 0.8 1.2 # both amounts\n", "arrows.txt");
  REQUIRE(constraints.size() == 3);
  CHECK(constraints[0].vertex == 12);
  CHECK(constraints[0].direction == Eigen::Vector3d(1, 0, 0));
  CHECK_FALSE(constraints[0].has_amounts);
  CHECK(constraints[1].has_amounts);
  CHECK(constraints[1].su == 0.8);
  CHECK(constraints[1].sv == 1.0);
  CHECK(constraints[2].vertex == 14);
  CHECK(constraints[2].su == 0.8);
  CHECK(constraints[2].sv == 1.2);
}

TEST_CASE("field: constraint parse errors name the file and line", "[field]") {
  auto parse = [](const std::string& text) { aniso::parse_direction_constraints(text, "arrows.txt"); };
  CHECK_THAT(bad_parameter_message([&] { parse("1 1 0 0\n2 1 0\n"); }),
             Catch::Contains("arrows.txt line 2: expected INDEX DX DY DZ [SU [SV]], got 3 values"));
  CHECK_THAT(bad_parameter_message([&] { parse("1 1 0 0 1 1 1\n"); }), Catch::Contains("got 7 values"));
  CHECK_THAT(bad_parameter_message([&] { parse("1.5 1 0 0\n"); }),
             Catch::Contains("line 1: INDEX must be a non-negative integer, got '1.5'"));
  CHECK_THAT(bad_parameter_message([&] { parse("\n\n3 1 nan 0\n"); }),
             Catch::Contains("line 3: DY: 'nan' is not a finite number"));
  CHECK_THAT(bad_parameter_message([&] { parse("3 1 0 0 0.9x\n"); }), Catch::Contains("SU: '0.9x' is not a number"));
  // strtod would read hex floats; the one number grammar (strict_number.h) does not.
  CHECK_THAT(bad_parameter_message([&] { parse("3 1 0 0\n4 0x1p0 0 0\n"); }),
             Catch::Contains("arrows.txt line 2: DX: '0x1p0' is a hexadecimal number"));
  CHECK_THAT(bad_parameter_message([&] { parse("3 1 0 0 1e999\n"); }), Catch::Contains("SU: '1e999' is out of range"));
  CHECK_THAT(bad_parameter_message([&] { parse("3 0 0 0\n"); }), Catch::Contains("line 1: the direction is zero"));
  CHECK_THAT(bad_parameter_message([&] { parse("3 1 0 0 1\n4 1 0 0 0\n"); }),
             Catch::Contains("arrows.txt line 2: SU must be positive, got 0"));
  CHECK_THAT(bad_parameter_message([&] { parse("3 1 0 0 1 -1\n"); }),
             Catch::Contains("arrows.txt line 1: SV must be positive, got -1"));
}

TEST_CASE("field: two equal constraints on a flat square give that direction everywhere", "[field]") {
  const FlatSquare square = plane_off();
  const Eigen::Vector3d wanted = Eigen::Vector3d(1, 0, 0.5).normalized();
  const auto field = aniso::propagate_direction_field(square.mesh, {constraint(0, wanted), constraint(500, wanted)});
  for (int i = 0; i < square.mesh.num_vertices(); ++i) {
    REQUIRE(field.direction.row(i).dot(wanted) > 1.0 - 1e-6);  // same line and same sign
  }
  CHECK(field.su == Eigen::VectorXd::Ones(square.mesh.num_vertices()));
  CHECK(field.sv == Eigen::VectorXd::Ones(square.mesh.num_vertices()));
}

TEST_CASE("field: opposite sides 60 degrees apart interpolate the doubled angle linearly", "[field]") {
  // With Dirichlet values on the sides x = min and x = max, the smoothest line
  // field on a flat square is exactly linear in x in the doubled-angle
  // representation: u(t) = (1 - t) + t exp(2i phi). (At 90 degrees the two
  // doubled values are opposite and the field has a singular line half-way:
  // both turning senses are equally smooth.)
  const FlatSquare square = equilateral_rectangle(20, 20);
  const double phi = 60.0 * kPi / 180.0;
  const Eigen::Vector3d left(1, 0, 0);
  const Eigen::Vector3d right(std::cos(phi), 0, std::sin(phi));
  std::vector<DirectionConstraint> constraints;
  for (int i = 0; i < square.mesh.num_vertices(); ++i) {
    if (square.on_side_x(i, square.box.min.x())) constraints.push_back(constraint(i, left));
    if (square.on_side_x(i, square.box.max.x())) constraints.push_back(constraint(i, right));
  }
  REQUIRE(constraints.size() > 20);
  const auto field = aniso::propagate_direction_field(square.mesh, constraints);

  std::vector<std::pair<double, double>> angle_by_t;
  for (int i = 0; i < square.mesh.num_vertices(); ++i) {
    const double t = square.t_of(i);
    const double expected_angle = 0.5 * std::arg((1.0 - t) + t * std::polar(1.0, 2.0 * phi));
    const Eigen::Vector3d expected(std::cos(expected_angle), 0, std::sin(expected_angle));
    REQUIRE(std::abs(field.direction.row(i).dot(expected)) > 1.0 - 1e-9);
    angle_by_t.emplace_back(t, std::atan2(field.direction(i, 2), field.direction(i, 0)));
  }
  // Along the way from one side to the other the angle only grows.
  std::sort(angle_by_t.begin(), angle_by_t.end());
  for (std::size_t k = 1; k < angle_by_t.size(); ++k) {
    if (angle_by_t[k].first > angle_by_t[k - 1].first + 1e-9) {
      REQUIRE(angle_by_t[k].second >= angle_by_t[k - 1].second - 1e-9);
    }
  }
  CHECK(angle_by_t.front().second == Approx(0.0).margin(1e-12));
  CHECK(angle_by_t.back().second == Approx(phi).margin(1e-12));
}

TEST_CASE("field: on curved meshes every direction is a unit tangent", "[field]") {
  for (const char* name : {"closed/spot_triangulated.obj", "open/hemisphere.obj", "closed/knot1.off"}) {
    INFO(name);
    const aniso::Mesh mesh = aniso::test::load(name);
    const aniso::Positions normals = aniso::vertex_normals(mesh);
    const int n = mesh.num_vertices();
    const std::vector<DirectionConstraint> constraints = {
        constraint(0, some_tangent(normals, 0, Eigen::Vector3d::UnitX())),
        constraint(n / 2, some_tangent(normals, n / 2, Eigen::Vector3d::UnitY())),
        constraint(n - 1, some_tangent(normals, n - 1, Eigen::Vector3d::UnitZ()))};
    const auto field = aniso::propagate_direction_field(mesh, constraints);
    for (int i = 0; i < n; ++i) {
      REQUIRE(field.direction.row(i).norm() == Approx(1.0).margin(1e-12));
      REQUIRE(std::abs(field.direction.row(i).dot(normals.row(i))) < 1e-9);
    }
  }
}

// An open cylinder of radius 1 around the z axis: `rings` rings of `around`
// vertices, one unit apart, with aligned (untwisted) rings.
aniso::Mesh open_cylinder(int around, int rings) {
  aniso::Mesh mesh;
  mesh.V.resize(around * rings, 3);
  for (int j = 0; j < rings; ++j) {
    for (int k = 0; k < around; ++k) {
      const double angle = 2.0 * kPi * k / around;
      mesh.V.row(j * around + k) << std::cos(angle), std::sin(angle), j;
    }
  }
  mesh.F.resize(2 * around * (rings - 1), 3);
  int t = 0;
  for (int j = 0; j + 1 < rings; ++j) {
    for (int k = 0; k < around; ++k) {
      const int a = j * around + k, b = j * around + (k + 1) % around;
      const int c = a + around, d = b + around;
      mesh.F.row(t++) << a, b, d;
      mesh.F.row(t++) << a, d, c;
    }
  }
  return mesh;
}

TEST_CASE("field: on a cylinder a helical field is parallel, so two constraints reproduce it", "[field]") {
  // Transport between the tangent planes of a cylinder is a rotation about its
  // axis, so the field at a fixed angle to the axis has zero connection
  // Laplacian energy: it is reproduced exactly, which fails if the transport
  // is applied the wrong way round.
  const aniso::Mesh mesh = open_cylinder(24, 12);
  const aniso::Positions normals = aniso::vertex_normals(mesh);
  const double tilt = 30.0 * kPi / 180.0;
  auto helix = [&](int i) {
    const Eigen::Vector3d n = normals.row(i).transpose();
    const Eigen::Vector3d around = Eigen::Vector3d::UnitZ().cross(n).normalized();
    return Eigen::Vector3d(std::cos(tilt) * Eigen::Vector3d::UnitZ() + std::sin(tilt) * around);
  };
  const auto field = aniso::propagate_direction_field(mesh, {constraint(3, helix(3)), constraint(200, helix(200))});
  for (int i = 0; i < mesh.num_vertices(); ++i) {
    REQUIRE(std::abs(field.direction.row(i).dot(helix(i))) > 1.0 - 1e-9);
  }
}

TEST_CASE("field: flipping a constraint's sign gives the same line field", "[field]") {
  const aniso::Mesh mesh = aniso::test::load("closed/spot_triangulated.obj");
  const aniso::Positions normals = aniso::vertex_normals(mesh);
  std::vector<DirectionConstraint> constraints = {
      constraint(100, some_tangent(normals, 100, Eigen::Vector3d::UnitX())),
      constraint(2000, some_tangent(normals, 2000, Eigen::Vector3d::UnitY()))};
  const auto field = aniso::propagate_direction_field(mesh, constraints);
  constraints[1].direction *= -1.0;
  const auto flipped = aniso::propagate_direction_field(mesh, constraints);
  for (int i = 0; i < mesh.num_vertices(); ++i) {
    REQUIRE(std::abs(field.direction.row(i).dot(flipped.direction.row(i))) > 1.0 - 1e-12);
  }
  // The constrained vertices keep the sign they were given.
  CHECK(flipped.direction.row(2000).dot(constraints[1].direction) > 0.0);
}

// Amounts given on the whole boundary from a linear function; returns the
// largest deviation from that function over the mesh.
double linear_amounts_error(const FlatSquare& square) {
  // Lifted so that both stay positive, as amounts must (validate_scale).
  const double lift = 1.0 + 2.0 * square.mesh.V.cwiseAbs().maxCoeff();
  auto su_of = [&](int i) { return lift + 0.5 * square.mesh.V(i, 0) - 0.25 * square.mesh.V(i, 2); };
  auto sv_of = [&](int i) { return lift - square.mesh.V(i, 2) + 0.1 * square.mesh.V(i, 0); };
  std::vector<DirectionConstraint> constraints;
  for (int i = 0; i < square.mesh.num_vertices(); ++i) {
    if (square.on_boundary(i)) {
      constraints.push_back(constraint_with_amounts(i, Eigen::Vector3d::UnitX(), su_of(i), sv_of(i)));
    }
  }
  REQUIRE(constraints.size() >= 80);
  REQUIRE(int(constraints.size()) < square.mesh.num_vertices() / 2);
  const auto field = aniso::propagate_direction_field(square.mesh, constraints);
  double error = 0.0;
  for (int i = 0; i < square.mesh.num_vertices(); ++i) {
    error = std::max({error, std::abs(field.su[i] - su_of(i)), std::abs(field.sv[i] - sv_of(i))});
  }
  return error;
}

TEST_CASE("field: harmonic amounts reproduce a linear function on a flat mesh", "[field]") {
  // The cotangent Laplacian has linear precision on flat meshes...
  CHECK(linear_amounts_error(equilateral_rectangle(20, 20)) < 1e-9);
  // ...exactly where laplacian.h raised no edge weight to its floor (rule 2);
  // plane.off's right-angled grid has cancelling weights it may raise.
  const FlatSquare plane = plane_off();
  const bool floored = aniso::cotangent_weights(plane.mesh).raised_edges > 0;
  CHECK(linear_amounts_error(plane) < (floored ? 1e-4 : 1e-9));
}

TEST_CASE("field: amounts obey the maximum principle on a mesh with non-negative weights", "[field]") {
  // The principle needs every edge weight >= 0 (equilateral_rectangle checks
  // that); with obtuse triangles a cotangent Laplacian can over- or undershoot.
  const FlatSquare flat = equilateral_rectangle(24, 20);
  const std::vector<int> vertices = {30, 200, 260, 411, 477};
  const std::vector<double> su = {0.7, 1.3, 0.9, 1.1, 1.0};
  std::vector<DirectionConstraint> constraints;
  for (std::size_t k = 0; k < vertices.size(); ++k) {
    constraints.push_back(constraint_with_amounts(vertices[k], Eigen::Vector3d::UnitZ(), su[k], 2.0 - su[k]));
  }
  const auto field = aniso::propagate_direction_field(flat.mesh, constraints);
  CHECK(field.su.minCoeff() == 0.7);  // the extremes are the held values
  CHECK(field.su.maxCoeff() == 1.3);
  CHECK(field.sv.minCoeff() == Approx(0.7).epsilon(1e-15));
  CHECK(field.sv.maxCoeff() == Approx(1.3).epsilon(1e-15));
  // Away from the constraints the values lie strictly inside.
  int strictly_inside = 0;
  for (int i = 0; i < flat.mesh.num_vertices(); ++i) {
    if (field.su[i] > 0.7 && field.su[i] < 1.3) ++strictly_inside;
  }
  CHECK(strictly_inside == flat.mesh.num_vertices() - 2);
}

TEST_CASE("field: a region limits the field, and a part without constraints gets no direction", "[field]") {
  const FlatSquare square = plane_off();
  const int n = square.mesh.num_vertices();
  const double width = square.box.max.x() - square.box.min.x();
  // Two separate strips: the left one constrained, the right one not.
  std::vector<char> mask(n, 0);
  int left_vertex = -1;
  for (int i = 0; i < n; ++i) {
    const double t = square.t_of(i);
    if (t < 0.3) {
      mask[i] = 1;
      left_vertex = i;
    }
    if (t > 0.6) mask[i] = 1;
  }
  REQUIRE(width > 0);
  const auto field = aniso::propagate_direction_field(
      square.mesh, {constraint_with_amounts(left_vertex, Eigen::Vector3d::UnitZ(), 0.5, 0.5)}, &mask);
  for (int i = 0; i < n; ++i) {
    const double t = square.t_of(i);
    if (t < 0.3) {
      REQUIRE(std::abs(field.direction(i, 2)) == Approx(1.0).margin(1e-9));
      REQUIRE(field.su[i] == Approx(0.5).margin(1e-12));
    } else {
      REQUIRE(field.direction.row(i).norm() == 0.0);  // outside, or in the unconstrained strip
      REQUIRE(field.su[i] == 1.0);
      REQUIRE(field.sv[i] == 1.0);
    }
  }
}

TEST_CASE("field: with every region vertex constrained the directions are used as given", "[field]") {
  const aniso::Mesh mesh = aniso::test::load("closed/spot_triangulated.obj");
  const aniso::Positions normals = aniso::vertex_normals(mesh);
  std::vector<char> mask(mesh.num_vertices(), 0);
  std::vector<DirectionConstraint> constraints;
  for (int i : {5, 6, 7, 900}) {
    mask[i] = 1;
    constraints.push_back(constraint(i, some_tangent(normals, i, Eigen::Vector3d(1, 2, 3))));
  }
  const auto field = aniso::propagate_direction_field(mesh, constraints, &mask);
  for (const DirectionConstraint& c : constraints) {
    const Eigen::Vector3d n = normals.row(c.vertex).transpose();
    const Eigen::Vector3d projected = (c.direction - c.direction.dot(n) * n).normalized();
    CHECK((field.direction.row(c.vertex).transpose() - projected).norm() < 1e-12);
  }
  CHECK(field.direction.rowwise().norm().sum() == Approx(4.0));
}

TEST_CASE("field: bad constraints are refused, naming the constraint and vertex", "[field]") {
  const aniso::Mesh mesh = aniso::test::load("closed/spot_triangulated.obj");
  const aniso::Positions normals = aniso::vertex_normals(mesh);
  const Eigen::Vector3d tangent = some_tangent(normals, 3, Eigen::Vector3d::UnitX());
  auto propagate = [&](std::vector<DirectionConstraint> constraints, const std::vector<char>* mask = nullptr) {
    aniso::propagate_direction_field(mesh, constraints, mask);
  };
  CHECK_THAT(bad_parameter_message([&] { propagate({constraint(3, tangent), constraint(2930, tangent)}); }),
             Catch::Contains("direction constraint 2 (vertex 2930): vertex index out of range, the mesh has 2930"));
  CHECK_THAT(bad_parameter_message([&] { propagate({constraint(-1, tangent)}); }),
             Catch::Contains("vertex index out of range"));
  CHECK_THAT(bad_parameter_message([&] { propagate({constraint(3, normals.row(3).transpose() * 2.0)}); }),
             Catch::Contains("direction constraint 1 (vertex 3): the direction") &&
                 Catch::Contains("is (nearly) parallel to the surface normal"));
  CHECK_THAT(bad_parameter_message([&] {
               propagate({constraint(3, Eigen::Vector3d(std::numeric_limits<double>::quiet_NaN(), 0, 0))});
             }),
             Catch::Contains("(vertex 3): the direction is not finite"));
  CHECK_THAT(bad_parameter_message([&] { propagate({constraint(3, Eigen::Vector3d::Zero())}); }),
             Catch::Contains("is zero"));
  CHECK_THAT(bad_parameter_message([&] {
               propagate({constraint_with_amounts(3, tangent, std::numeric_limits<double>::infinity(), 1)});
             }),
             Catch::Contains("direction constraint 1 (vertex 3): su must be a finite number"));
  // Amounts follow the rule of the global scale (validate_scale): > 0.
  CHECK_THAT(bad_parameter_message([&] { propagate({constraint_with_amounts(3, tangent, 0, 1)}); }),
             Catch::Contains("direction constraint 1 (vertex 3): su must be positive, got 0"));
  CHECK_THAT(bad_parameter_message([&] {
               propagate({constraint(5, tangent), constraint_with_amounts(3, tangent, 1, -1)});
             }),
             Catch::Contains("direction constraint 2 (vertex 3): sv must be positive, got -1"));
  CHECK_THAT(bad_parameter_message([&] { propagate({constraint(3, tangent), constraint(3, tangent)}); }),
             Catch::Contains("direction constraint 2 (vertex 3): the vertex is already constrained by constraint 1"));
  std::vector<char> mask(mesh.num_vertices(), 0);
  CHECK_THAT(bad_parameter_message([&] { propagate({constraint(3, tangent)}, &mask); }),
             Catch::Contains("(vertex 3): the vertex is outside the selected region"));
  mask.resize(10);
  CHECK_THAT(bad_parameter_message([&] { propagate({constraint(3, tangent)}, &mask); }),
             Catch::Contains("region mask has 10 entries, the mesh has 2930 vertices"));
}
