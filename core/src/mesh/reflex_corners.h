// The corners of a polygon being ear clipped, in its plane, and which of them
// are reflex, indexed so that an ear test finds those in its triangle without
// scanning them all (see triangulate.cpp, the one user).
//
// A k-d tree over all corners counts the reflex ones in each node; a search
// descends only into nodes that hold some and that the triangle may reach.
// Not a uniform grid over the triangle's bounding box: a polygon whose edges
// are cut into many collinear pieces is clipped as long thin fans, whose
// bounding boxes cover much of the polygon, while the tree's nodes are also
// cut off by the triangle's edges.
#pragma once

#include <algorithm>
#include <vector>

namespace aniso::ear_clipping {

struct Point2 {
  double x, y;
};

// Twice the signed area of (a, b, c): > 0 when counter-clockwise.
inline double orient(const Point2& a, const Point2& b, const Point2& c) {
  return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}

inline bool same_position(const Point2& a, const Point2& b) { return a.x == b.x && a.y == b.y; }

struct Triangle2 {
  Point2 a, b, c;
  double min_x, min_y, max_x, max_y;  // bounding box

  Triangle2(const Point2& a, const Point2& b, const Point2& c)
      : a(a), b(b), c(c),
        min_x(std::min({a.x, b.x, c.x})), min_y(std::min({a.y, b.y, c.y})),
        max_x(std::max({a.x, b.x, c.x})), max_y(std::max({a.y, b.y, c.y})) {}

  // Closed: a point on an edge is inside. The bounding box test only rules
  // out rounding artefacts, and lets the tree prune by the box exactly.
  bool holds(const Point2& p) const {
    return p.x >= min_x && p.x <= max_x && p.y >= min_y && p.y <= max_y &&
           orient(a, b, p) >= 0 && orient(b, c, p) >= 0 && orient(c, a, p) >= 0;
  }
};

class ReflexCorners {
 public:
  // No corner is reflex at first. `points` must outlive this.
  explicit ReflexCorners(const std::vector<Point2>& points);

  bool is_reflex(int corner) const { return reflex_[corner]; }
  void set_reflex(int corner, bool reflex);

  // Whether a reflex corner that `ignore` does not exclude lies in the
  // triangle; adds the nodes visited and the points tested to `work`.
  template <typename Ignore>
  bool any_in(const Triangle2& triangle, const Ignore& ignore, long long& work) {
    stack_.assign(1, 0);
    while (!stack_.empty()) {
      const int index = stack_.back();
      stack_.pop_back();
      const Node& node = nodes_[index];
      ++work;
      if (node.reflex == 0 || !may_reach(node, triangle)) continue;
      if (!node.leaf) {
        stack_.push_back(2 * index + 1);
        stack_.push_back(2 * index + 2);
        continue;
      }
      for (int k = node.begin; k < node.end; ++k) {
        const int corner = order_[k];
        if (!reflex_[corner]) continue;
        ++work;
        if (!ignore(corner) && triangle.holds(points_[corner])) return true;
      }
    }
    return false;
  }

 private:
  struct Node {
    double min_x = 0, min_y = 0, max_x = 0, max_y = 0;  // box of all its corners
    int begin = 0, end = 0;                             // its corners: order_[begin, end)
    int reflex = 0;                                     // how many of them are reflex
    bool leaf = true;
  };

  void build(int index, int begin, int end);
  static bool may_reach(const Node& node, const Triangle2& triangle);

  const std::vector<Point2>& points_;
  std::vector<char> reflex_;
  std::vector<int> leaf_of_;  // per corner: the leaf holding it
  std::vector<int> order_;    // corners, grouped by node
  std::vector<Node> nodes_;   // numbered as a heap: node i's children are 2i+1, 2i+2
  std::vector<int> stack_;    // reused by any_in
};

}  // namespace aniso::ear_clipping
