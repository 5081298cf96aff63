// Polygon triangulation by ear clipping in the polygon's best-fit plane.
//
// The polygon is projected onto the plane of its Newell normal, where it winds
// counter-clockwise; an ear is a convex corner whose triangle holds no other
// corner. Corners at the same position as the ear's own corners are ignored in
// that test, so a polygon whose hole is joined by a doubled bridge edge
// triangulates like the hole-free polygon it stands for. Only reflex corners
// (flat ones included: they may sit on an ear's edge) can lie inside an ear,
// so only they are tested, and only those near the ear (a k-d tree,
// reflex_corners.h). The walk around the polygon in search of ears steps
// from convex corner to convex corner: a long run of flat or reflex corners
// is not walked over again on every lap.
//
// Ear clipping can find no ear on self-intersecting or non-planar input. Then
// collinear (flat) ears are accepted, and failing that, the remaining corners
// are fanned: the result always has #corners-2 triangles, in the polygon's
// winding.
//
// Ear clipping may still take O(n^2) (n corners), e.g. when laps of the walk
// find few ears each. The work (corners visited, tree nodes visited, points
// tested against an ear) is therefore capped at kWorkPerCorner * n * log2(n):
// ordinary polygons finish well within it (a polygon of 400k corners, nearly
// all flat, takes an eighth of it), and a pathological one gets the rest of
// its corners fanned: O(n log n) whatever the input, at the price of
// overlapping triangles only on such polygons.
#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include <Eigen/Geometry>

#include "anisoform/error.h"
#include "anisoform/mesh_check.h"
#include "mesh/reflex_corners.h"

namespace aniso {

namespace {

// Work allowed per corner and per doubling of the corner count before the
// rest of a polygon is fanned (see the top of the file).
constexpr long long kWorkPerCorner = 64;

long long ear_clipping_budget(std::size_t corners) {
  const double n = static_cast<double>(corners);
  return static_cast<long long>(kWorkPerCorner * n * std::max(1.0, std::log2(n)));
}

using ear_clipping::orient;
using ear_clipping::Point2;
using ear_clipping::ReflexCorners;
using ear_clipping::same_position;
using ear_clipping::Triangle2;

// A ring of some of the corners, in the polygon's order, linked both ways.
class CornerRing {
 public:
  explicit CornerRing(int corners) : next_(corners, -1), prev_(corners, -1) {}

  bool holds(int corner) const { return next_[corner] != -1; }
  int next(int corner) const { return next_[corner]; }
  int size() const { return size_; }

  // Links `corner` in after `at`, or alone when `at` is -1 (empty ring).
  void insert_after(int corner, int at) {
    if (at == -1) at = corner;
    const int following = at == corner ? corner : next_[at];
    prev_[corner] = at;
    next_[corner] = following;
    next_[at] = corner;
    prev_[following] = corner;
    ++size_;
  }
  void insert_before(int corner, int at) { insert_after(corner, prev_[at]); }

  void remove(int corner) {
    next_[prev_[corner]] = next_[corner];
    prev_[next_[corner]] = prev_[corner];
    next_[corner] = prev_[corner] = -1;
    --size_;
  }

 private:
  std::vector<int> next_, prev_;
  int size_ = 0;
};

class EarClipper {
 public:
  EarClipper(std::vector<Point2> points, const std::vector<int>& polygon)
      : points_(std::move(points)),
        polygon_(polygon),
        reflex_(points_),
        convex_(static_cast<int>(points_.size())),
        budget_(ear_clipping_budget(polygon.size())) {
    const int n = static_cast<int>(points_.size());
    prev_.resize(n);
    next_.resize(n);
    for (int i = 0; i < n; ++i) {
      prev_[i] = (i + n - 1) % n;
      next_[i] = (i + 1) % n;
    }
    // Areas below this are "flat": relative to the polygon's extent squared.
    double extent = 0;
    for (const Point2& p : points_) extent = std::max({extent, std::abs(p.x), std::abs(p.y)});
    flat_tolerance_ = 1e-14 * extent * extent;
    int last_convex = -1;
    for (int i = 0; i < n; ++i) {
      update_reflex(i);
      if (reflex_.is_reflex(i)) continue;
      convex_.insert_after(i, last_convex);
      last_convex = i;
    }
  }

  std::vector<std::array<int, 3>> run() {
    int remaining = static_cast<int>(points_.size());
    int corner = 0;
    int misses = 0;
    bool accept_flat = false;
    while (remaining > 3 && work_ < budget_) {
      ++work_;
      if (is_ear(corner, accept_flat)) {
        corner = clip(corner);
        --remaining;
        misses = 0;
        accept_flat = false;
        continue;
      }
      // Only convex corners can be proper ears: the walk skips the others
      // (after a flat ear it may have to walk to the next convex corner).
      const bool on_ring = !accept_flat && convex_.holds(corner);
      corner = on_ring ? convex_.next(corner) : next_[corner];
      if (on_ring || accept_flat) ++misses;
      // A lap without an ear: of the convex corners, then of all corners.
      if (misses < (accept_flat ? remaining : convex_.size())) continue;
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
    // Flat corners count as reflex: they may sit on an ear's edge.
    reflex_.set_reflex(i, corner_orientation(i) <= flat_tolerance_);
  }

  bool is_ear(int b, bool accept_flat) {
    const int a = prev_[b];
    const int c = next_[b];
    const double area = corner_orientation(b);
    if (!(area > flat_tolerance_) && !(accept_flat && area >= -flat_tolerance_)) return false;
    const Triangle2 ear(points_[a], points_[b], points_[c]);
    const auto ignore = [&](int r) {
      const Point2& p = points_[r];
      return r == a || r == b || r == c || same_position(p, ear.a) || same_position(p, ear.b) ||
             same_position(p, ear.c);
    };
    return !reflex_.any_in(ear, ignore, work_);
  }

  // Cuts the ear at b off; returns the corner to test next: the next convex
  // one after b, as the walk would reach it.
  int clip(int b) {
    const int a = prev_[b];
    const int c = next_[b];
    triangles_.push_back({polygon_[a], polygon_[b], polygon_[c]});
    next_[a] = c;
    prev_[c] = a;
    next_[b] = prev_[b] = -1;
    reflex_.set_reflex(b, false);
    update_reflex(a);
    update_reflex(c);
    // a and c keep b's place in the ring: a just before it, c just after.
    const int anchor = convex_.holds(b) ? b : -1;
    update_convex(a, anchor, true);
    update_convex(c, anchor, false);
    int after = c;
    if (anchor != -1) {
      if (convex_.next(b) != b) after = convex_.next(b);
      convex_.remove(b);
    }
    return after;
  }

  // Puts corner i in or out of the ring of convex corners, next to `anchor`
  // (a ring member next to it in the polygon) or, without one (b was a flat
  // ear), before the next member along the polygon.
  void update_convex(int i, int anchor, bool before) {
    const bool convex = !reflex_.is_reflex(i);
    if (convex == convex_.holds(i)) return;
    if (!convex) {
      convex_.remove(i);
      return;
    }
    if (anchor == -1) {
      for (int j = next_[i]; j != i && anchor == -1; j = next_[j]) {
        ++work_;
        if (convex_.holds(j)) anchor = j;
      }
      before = true;
    }
    if (before && anchor != -1) {
      convex_.insert_before(i, anchor);
    } else {
      convex_.insert_after(i, anchor);  // alone in the ring when anchor is -1
    }
  }

  void fan_rest(int start) {
    for (int i = next_[start]; next_[i] != start; i = next_[i]) {
      triangles_.push_back({polygon_[start], polygon_[i], polygon_[next_[i]]});
    }
  }

  std::vector<Point2> points_;
  const std::vector<int>& polygon_;
  std::vector<int> prev_, next_;
  ReflexCorners reflex_;  // of the corners not clipped yet
  CornerRing convex_;     // the corners not clipped yet that are not reflex
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
