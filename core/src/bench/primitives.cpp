#include "bench/primitives.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "anisoform/error.h"
#include "base/math_constants.h"

namespace aniso {
namespace {

// A circle of vertices: the first vertex index, the vertex count and the angle
// of the first vertex (the others follow counter-clockwise seen from +z).
struct Ring {
  int first = 0;
  int count = 0;
  double start_angle = 0.0;
  double step() const { return 2.0 * kPi / count; }
};

class CylinderBuilder {
 public:
  Ring add_ring(int count, double radius, double z, double start_angle) {
    Ring ring{static_cast<int>(vertices_.size()), count, start_angle};
    for (int i = 0; i < count; ++i) {
      const double angle = start_angle + i * ring.step();
      vertices_.push_back({radius * std::cos(angle), radius * std::sin(angle), z});
    }
    return ring;
  }

  int add_vertex(double x, double y, double z) {
    vertices_.push_back({x, y, z});
    return static_cast<int>(vertices_.size()) - 1;
  }

  // Triangulates the band between two rings by merging them in angle order
  // (each step advances along the ring whose next vertex comes first), which
  // works for rings of different counts. With flip = false the triangles face
  // the direction of (tangent of `a`) x (from `a` towards `b`).
  void zip(const Ring& a, const Ring& b, bool flip) {
    // Start `b` at its vertex nearest in angle to the first vertex of `a`.
    const double offset = std::remainder(b.start_angle - a.start_angle, b.step());
    const int b_start = static_cast<int>(
        std::lround((a.start_angle + offset - b.start_angle) / b.step()));
    auto a_vertex = [&](int i) { return a.first + i % a.count; };
    auto b_vertex = [&](int j) {
      return b.first + ((b_start + j) % b.count + b.count) % b.count;
    };
    auto a_angle = [&](int i) { return i * a.step(); };
    auto b_angle = [&](int j) { return offset + j * b.step(); };
    int i = 0, j = 0;
    while (i < a.count || j < b.count) {
      const bool advance_a =
          j == b.count || (i < a.count && a_angle(i + 1) <= b_angle(j + 1));
      if (advance_a) {
        add_triangle(a_vertex(i), a_vertex(i + 1), b_vertex(j), flip);
        ++i;
      } else {
        add_triangle(a_vertex(i), b_vertex(j + 1), b_vertex(j), flip);
        ++j;
      }
    }
  }

  void fan(const Ring& ring, int centre, bool flip) {
    for (int i = 0; i < ring.count; ++i)
      add_triangle(ring.first + i, ring.first + (i + 1) % ring.count, centre, flip);
  }

  Mesh build() const {
    Mesh mesh;
    mesh.V.resize(static_cast<Eigen::Index>(vertices_.size()), 3);
    for (size_t v = 0; v < vertices_.size(); ++v)
      mesh.V.row(static_cast<Eigen::Index>(v)) = vertices_[v];
    mesh.F.resize(static_cast<Eigen::Index>(triangles_.size()), 3);
    for (size_t f = 0; f < triangles_.size(); ++f)
      mesh.F.row(static_cast<Eigen::Index>(f)) = triangles_[f];
    return mesh;
  }

 private:
  void add_triangle(int a, int b, int c, bool flip) {
    if (flip) std::swap(b, c);
    triangles_.push_back({a, b, c});
  }

  std::vector<Eigen::RowVector3d> vertices_;
  std::vector<Eigen::RowVector3i> triangles_;
};

// Concentric rings from just inside `rim` towards the axis, then the centre
// vertex. The top cap faces +z; the bottom one is flipped to face -z.
void add_cap(CylinderBuilder& builder, const Ring& rim, double radius, double z,
             double edge, bool is_top) {
  const double row_spacing = edge * std::sqrt(3.0) / 2.0;
  const int inner_rings = std::max(0, static_cast<int>(std::lround(radius / row_spacing)) - 1);
  const double ring_spacing = radius / (inner_rings + 1);
  Ring outer = rim;
  for (int k = 1; k <= inner_rings; ++k) {
    const double ring_radius = radius - k * ring_spacing;
    const int count = std::max(3, static_cast<int>(std::lround(2.0 * kPi * ring_radius / edge)));
    // Rotating each ring by half a step keeps the band triangles close to equilateral.
    const Ring inner = builder.add_ring(count, ring_radius, z, outer.start_angle + 0.5 * outer.step());
    builder.zip(outer, inner, !is_top);
    outer = inner;
  }
  builder.fan(outer, builder.add_vertex(0.0, 0.0, z), !is_top);
}

}  // namespace

Mesh capped_cylinder(int approx_vertices, double radius, double height) {
  if (approx_vertices < 16)
    fail(ErrorCode::BadParameter, "capped_cylinder needs at least 16 vertices, got " +
                                      std::to_string(approx_vertices));
  if (!(radius > 0.0) || !(height > 0.0))
    fail(ErrorCode::BadParameter, "capped_cylinder needs a positive radius and height");

  // An equilateral mesh has about one vertex per (sqrt(3)/2) edge^2 of area.
  const double area = 2.0 * kPi * radius * (height + radius);
  const double edge = std::sqrt(area / (approx_vertices * std::sqrt(3.0) / 2.0));
  const int around = std::max(3, static_cast<int>(std::lround(2.0 * kPi * radius / edge)));
  const int rings = std::max(2, static_cast<int>(std::lround(height / (edge * std::sqrt(3.0) / 2.0))) + 1);

  CylinderBuilder builder;
  std::vector<Ring> side;
  for (int j = 0; j < rings; ++j) {
    const double z = -0.5 * height + height * j / (rings - 1);
    const double start_angle = (j % 2) * 0.5 * (2.0 * kPi / around);
    side.push_back(builder.add_ring(around, radius, z, start_angle));
  }
  for (int j = 0; j + 1 < rings; ++j) builder.zip(side[j], side[j + 1], false);
  add_cap(builder, side.front(), radius, -0.5 * height, edge, false);
  add_cap(builder, side.back(), radius, 0.5 * height, edge, true);
  return builder.build();
}

}  // namespace aniso
