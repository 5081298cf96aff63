// Polygon triangulation by ear clipping in the polygon's best-fit plane.
//
// The polygon is projected onto the plane of its Newell normal, where it winds
// counter-clockwise; an ear is a convex corner whose triangle holds no other
// corner. Corners at the same position as the ear's own corners are ignored in
// that test, so a polygon whose hole is joined by a doubled bridge edge
// triangulates like the hole-free polygon it stands for. Only reflex corners
// can lie inside an ear, so only they are tested: convex polygons take linear
// time.
//
// Ear clipping can find no ear on self-intersecting or non-planar input. Then
// collinear (flat) ears are accepted, and failing that, the remaining corners
// are fanned: the result always has #corners-2 triangles, in the polygon's
// winding.
//
// Ear clipping is O(n^2) at worst (n corners, many of them reflex). The work
// (corner visits and point-in-triangle tests) is therefore capped at
// kWorkPerCorner * n * log2(n): ordinary polygons (convex, or a few reflex
// corners) finish well within it, and a pathological one (thousands of reflex
// corners) gets the rest of its corners fanned: O(n log n) whatever the input,
// at the price of overlapping triangles only on such polygons.
#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include <Eigen/Geometry>

#include "anisoform/error.h"
#include "anisoform/mesh_check.h"

namespace aniso {

namespace {

// Work allowed per corner and per doubling of the corner count before the
// rest of a polygon is fanned (see the top of the file).
constexpr long long kWorkPerCorner = 64;

long long ear_clipping_budget(std::size_t corners) {
  const double n = static_cast<double>(corners);
  return static_cast<long long>(kWorkPerCorner * n * std::max(1.0, std::log2(n)));
}

struct Point2 {
  double x, y;
};

// Twice the signed area of (a, b, c): > 0 when counter-clockwise.
double orient(const Point2& a, const Point2& b, const Point2& c) {
  return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}

bool same_position(const Point2& a, const Point2& b) { return a.x == b.x && a.y == b.y; }

class EarClipper {
 public:
  EarClipper(std::vector<Point2> points, const std::vector<int>& polygon)
      : points_(std::move(points)), polygon_(polygon), budget_(ear_clipping_budget(polygon.size())) {
    const int n = static_cast<int>(points_.size());
    prev_.resize(n);
    next_.resize(n);
    reflex_.assign(n, 0);
    for (int i = 0; i < n; ++i) {
      prev_[i] = (i + n - 1) % n;
      next_[i] = (i + 1) % n;
    }
    // Areas below this are "flat": relative to the polygon's extent squared.
    double extent = 0;
    for (const Point2& p : points_) extent = std::max({extent, std::abs(p.x), std::abs(p.y)});
    flat_tolerance_ = 1e-14 * extent * extent;
    for (int i = 0; i < n; ++i) update_reflex(i);
  }

  std::vector<std::array<int, 3>> run() {
    int remaining = static_cast<int>(points_.size());
    int corner = 0;
    int misses = 0;
    bool accept_flat = false;
    while (remaining > 3 && work_ < budget_) {
      ++work_;
      if (is_ear(corner, accept_flat)) {
        const int after = next_[corner];
        clip(corner);
        --remaining;
        corner = after;
        misses = 0;
        accept_flat = false;
        continue;
      }
      corner = next_[corner];
      if (++misses < remaining) continue;
      if (accept_flat) break;  // no ear at all: fan what is left
      accept_flat = true;
      misses = 0;
    }
    fan_rest(corner);
    return std::move(triangles_);
  }

 private:
  double corner_orientation(int i) const {
    return orient(points_[prev_[i]], points_[i], points_[next_[i]]);
  }

  void update_reflex(int i) {
    const bool was_reflex = reflex_[i];
    // Flat corners count as reflex: they may sit on an ear's edge.
    reflex_[i] = corner_orientation(i) <= flat_tolerance_;
    if (reflex_[i] && !was_reflex) reflex_list_.push_back(i);
  }

  bool is_ear(int b, bool accept_flat) {
    const int a = prev_[b];
    const int c = next_[b];
    const double area = corner_orientation(b);
    if (!(area > flat_tolerance_) && !(accept_flat && area >= -flat_tolerance_)) return false;
    const Point2& pa = points_[a];
    const Point2& pb = points_[b];
    const Point2& pc = points_[c];
    for (const int r : reflex_list_) {
      ++work_;
      if (!reflex_[r] || removed(r) || r == a || r == b || r == c) continue;
      const Point2& p = points_[r];
      if (same_position(p, pa) || same_position(p, pb) || same_position(p, pc)) continue;
      if (orient(pa, pb, p) >= 0 && orient(pb, pc, p) >= 0 && orient(pc, pa, p) >= 0) return false;
    }
    return true;
  }

  bool removed(int i) const { return next_[i] == -1; }

  void clip(int b) {
    const int a = prev_[b];
    const int c = next_[b];
    triangles_.push_back({polygon_[a], polygon_[b], polygon_[c]});
    next_[a] = c;
    prev_[c] = a;
    next_[b] = prev_[b] = -1;
    reflex_[b] = 0;
    update_reflex(a);
    update_reflex(c);
  }

  void fan_rest(int start) {
    for (int i = next_[start]; next_[i] != start; i = next_[i]) {
      triangles_.push_back({polygon_[start], polygon_[i], polygon_[next_[i]]});
    }
  }

  std::vector<Point2> points_;
  const std::vector<int>& polygon_;
  std::vector<int> prev_, next_;
  std::vector<char> reflex_;
  std::vector<int> reflex_list_;  // every corner that was ever reflex; check reflex_ too
  std::vector<std::array<int, 3>> triangles_;
  double flat_tolerance_ = 0;
  long long budget_;
  long long work_ = 0;
};

// Sum of the polygon's edge cross products: its area-weighted normal, also
// for non-planar polygons.
Eigen::Vector3d newell_normal(const Positions& V, const std::vector<int>& polygon) {
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  const Eigen::RowVector3d origin = V.row(polygon[0]);
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const Eigen::Vector3d p = (V.row(polygon[i]) - origin).transpose();
    const Eigen::Vector3d q = (V.row(polygon[(i + 1) % polygon.size()]) - origin).transpose();
    normal += p.cross(q);
  }
  return normal;
}

std::vector<std::array<int, 3>> fan(const std::vector<int>& polygon) {
  std::vector<std::array<int, 3>> triangles;
  for (std::size_t i = 1; i + 1 < polygon.size(); ++i) triangles.push_back({polygon[0], polygon[i], polygon[i + 1]});
  return triangles;
}

}  // namespace

std::vector<std::array<int, 3>> triangulate_polygon(const Positions& V, const std::vector<int>& polygon) {
  if (polygon.size() < 3) {
    fail(ErrorCode::BadFile, "a polygon needs at least 3 corners; this one has " +
                                 std::to_string(polygon.size()));
  }
  for (const int index : polygon) {
    if (index < 0 || index >= V.rows()) {
      fail(ErrorCode::BadFile, "a polygon references vertex " + std::to_string(index) +
                                   ", but there are " + std::to_string(V.rows()) + " vertices");
    }
  }
  if (polygon.size() == 3) return {{polygon[0], polygon[1], polygon[2]}};

  const Eigen::Vector3d normal = newell_normal(V, polygon);
  const double length = normal.norm();
  // No plane (all corners collinear or coincident) or non-finite corners: any
  // triangulation is degenerate, the fan is as good as another.
  if (!(length > 0) || !std::isfinite(length)) return fan(polygon);

  // (u, v, normal) is right-handed, so the polygon winds counter-clockwise in (u, v).
  const Eigen::Vector3d n = normal / length;
  const Eigen::Vector3d u = n.unitOrthogonal();
  const Eigen::Vector3d v = n.cross(u);
  const Eigen::RowVector3d origin = V.row(polygon[0]);
  std::vector<Point2> points(polygon.size());
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const Eigen::RowVector3d p = V.row(polygon[i]) - origin;
    points[i] = {p.dot(u.transpose()), p.dot(v.transpose())};
  }
  return EarClipper(std::move(points), polygon).run();
}

}  // namespace aniso
