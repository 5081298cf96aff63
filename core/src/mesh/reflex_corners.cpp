#include "mesh/reflex_corners.h"

namespace aniso::ear_clipping {

namespace {

// Few enough corners that testing them all beats descending further.
constexpr int kLeafSize = 8;

// Whether some point of the box lies on the inner side of the edge from -> to
// (or on it). orient() rounds monotonically in its third point, so the box
// corner farthest inside bounds, as computed, every point of the box.
bool box_reaches_inside_of(double min_x, double min_y, double max_x, double max_y, const Point2& from,
                           const Point2& to) {
  const Point2 farthest = {to.y - from.y >= 0 ? min_x : max_x, to.x - from.x >= 0 ? max_y : min_y};
  return orient(from, to, farthest) >= 0;
}

}  // namespace

ReflexCorners::ReflexCorners(const std::vector<Point2>& points)
    : points_(points), reflex_(points.size(), 0), leaf_of_(points.size()), order_(points.size()) {
  for (std::size_t i = 0; i < order_.size(); ++i) order_[i] = static_cast<int>(i);
  if (!order_.empty()) build(0, 0, static_cast<int>(order_.size()));
}

void ReflexCorners::set_reflex(int corner, bool reflex) {
  if (static_cast<bool>(reflex_[corner]) == reflex) return;
  reflex_[corner] = reflex;
  for (int node = leaf_of_[corner];; node = (node - 1) / 2) {
    nodes_[node].reflex += reflex ? 1 : -1;
    if (node == 0) break;
  }
}

// Each node splits its corners at the median of its box's longer side.
void ReflexCorners::build(int index, int begin, int end) {
  if (index >= static_cast<int>(nodes_.size())) nodes_.resize(index + 1);
  Node node;
  node.begin = begin;
  node.end = end;
  node.min_x = node.max_x = points_[order_[begin]].x;
  node.min_y = node.max_y = points_[order_[begin]].y;
  for (int k = begin; k < end; ++k) {
    const Point2& p = points_[order_[k]];
    node.min_x = std::min(node.min_x, p.x);
    node.max_x = std::max(node.max_x, p.x);
    node.min_y = std::min(node.min_y, p.y);
    node.max_y = std::max(node.max_y, p.y);
  }
  node.leaf = end - begin <= kLeafSize;
  nodes_[index] = node;
  if (node.leaf) {
    for (int k = begin; k < end; ++k) leaf_of_[order_[k]] = index;
    return;
  }
  const bool by_x = node.max_x - node.min_x >= node.max_y - node.min_y;
  const int middle = begin + (end - begin) / 2;
  std::nth_element(order_.begin() + begin, order_.begin() + middle, order_.begin() + end, [&](int i, int j) {
    return by_x ? points_[i].x < points_[j].x : points_[i].y < points_[j].y;
  });
  build(2 * index + 1, begin, middle);
  build(2 * index + 2, middle, end);
}

// False when no point of the node's box can be in the triangle (as
// Triangle2::holds decides): the boxes are apart, or the node's box lies
// wholly outside one of the triangle's edges.
bool ReflexCorners::may_reach(const Node& node, const Triangle2& t) {
  if (node.max_x < t.min_x || node.min_x > t.max_x || node.max_y < t.min_y || node.min_y > t.max_y) return false;
  const auto reaches = [&](const Point2& from, const Point2& to) {
    return box_reaches_inside_of(node.min_x, node.min_y, node.max_x, node.max_y, from, to);
  };
  return reaches(t.a, t.b) && reaches(t.b, t.c) && reaches(t.c, t.a);
}

}  // namespace aniso::ear_clipping
