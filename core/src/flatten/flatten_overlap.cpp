// Where a pattern overlaps itself without a folded triangle: its outline
// crosses itself. A map of a disk that folds no triangle is one-to-one when
// its boundary is a simple curve, so the crossings of the boundary loops'
// segments (two segments sharing no vertex, crossing properly) are the
// overlaps' witnesses; a pattern with any cannot be cut from cloth as laid.
// Segments are bucketed in a uniform grid of about their length, so a
// pattern of b boundary edges costs about O(b), not O(b^2).
#include <algorithm>
#include <cmath>
#include <unordered_map>
#include <vector>

#include "flatten/flatten_pipeline.h"

namespace aniso {
namespace {

struct Segment {
  int a, b;  // patch vertices
};

double orientation(const Eigen::Vector2d& p, const Eigen::Vector2d& q, const Eigen::Vector2d& r) {
  return (q - p).x() * (r - p).y() - (q - p).y() * (r - p).x();
}

bool cross_properly(const Eigen::MatrixX2d& uv, const Segment& s, const Segment& t) {
  if (s.a == t.a || s.a == t.b || s.b == t.a || s.b == t.b) return false;
  const Eigen::Vector2d p = uv.row(s.a), q = uv.row(s.b), r = uv.row(t.a), w = uv.row(t.b);
  const double o1 = orientation(p, q, r), o2 = orientation(p, q, w);
  const double o3 = orientation(r, w, p), o4 = orientation(r, w, q);
  return ((o1 > 0 && o2 < 0) || (o1 < 0 && o2 > 0)) && ((o3 > 0 && o4 < 0) || (o3 < 0 && o4 > 0));
}

}  // namespace

int count_outline_crossings(const FlattenPatch& patch, const Eigen::MatrixX2d& uv) {
  std::vector<Segment> segments;
  double length = 0.0;
  for (const std::vector<int>& loop : patch.boundary_loops) {
    for (std::size_t k = 0; k < loop.size(); ++k) {
      const Segment s{loop[k], loop[(k + 1) % loop.size()]};
      if (s.a == s.b) continue;
      segments.push_back(s);
      length += (uv.row(s.a) - uv.row(s.b)).norm();
    }
  }
  if (segments.size() < 4 || !uv.allFinite()) return 0;
  const double cell = std::max(2.0 * length / static_cast<double>(segments.size()), 1e-300);
  const Eigen::Vector2d origin = uv.colwise().minCoeff().transpose();
  // Cell keys from the cell's integer coordinates; a segment sits in every cell its box meets.
  const auto key = [](long long i, long long j) { return (i << 32) ^ (j & 0xffffffffLL); };
  std::unordered_map<long long, std::vector<int>> grid;
  const auto cells_of = [&](const Segment& s, auto&& visit) {
    const Eigen::Vector2d p = (uv.row(s.a).transpose() - origin) / cell, q = (uv.row(s.b).transpose() - origin) / cell;
    const long long i0 = static_cast<long long>(std::floor(std::min(p.x(), q.x())));
    const long long i1 = static_cast<long long>(std::floor(std::max(p.x(), q.x())));
    const long long j0 = static_cast<long long>(std::floor(std::min(p.y(), q.y())));
    const long long j1 = static_cast<long long>(std::floor(std::max(p.y(), q.y())));
    for (long long i = i0; i <= i1; ++i) {
      for (long long j = j0; j <= j1; ++j) visit(key(i, j));
    }
  };
  int crossings = 0;
  std::vector<int> seen(segments.size(), -1);  // the last segment each was tested against
  for (int s = 0; s < static_cast<int>(segments.size()); ++s) {
    cells_of(segments[s], [&](long long k) {
      std::vector<int>& bucket = grid[k];
      for (const int t : bucket) {
        if (seen[t] == s) continue;
        seen[t] = s;
        if (cross_properly(uv, segments[s], segments[t])) ++crossings;
      }
      bucket.push_back(s);
    });
  }
  return crossings;
}

}  // namespace aniso
