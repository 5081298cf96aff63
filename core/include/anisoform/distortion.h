// Per-vertex distortion of a deformed mesh against its rest pose, for the
// browser's heat map: how much each part of the surface grew or stretched;
// and the count of triangles a deformation folded over.
#pragma once

#include <memory>
#include <vector>

#include "anisoform/mesh.h"

namespace aniso {

struct VertexAdjacency;  // mesh/topology.h

enum class DistortionKind {
  // Area of the vertex's one-ring deformed / rest: 1 unchanged, 2 doubled.
  AreaRatio,
  // The principal stretch of each triangle's deformation map (a singular
  // value) that deviates most from 1 by ratio, area-weighted over the
  // one-ring: 2 = some line element doubled, 0.5 = one halved (a squeeze along
  // one direction shows, although no line element got longer), 1 = unchanged.
  // The heat map shows its log2, so 2 and 0.5 look equally strong.
  Stretch,
};

// #V values for `rest` (V and F) deformed to `deformed` (#V by 3, same
// triangles). Zero-area rest triangles carry no weight; a vertex with none
// left gets 1. Throws Error(BadParameter) if the vertex counts differ.
Eigen::VectorXd vertex_distortion(const Mesh& rest, const Positions& deformed,
                                  DistortionKind kind);

// Triangles folded over by a deformation: the deformed normal is more than
// 90 deg from the rest normal carried along by the local rigid rotation (the
// mean of the corners' best-fit one-ring rotations). Without taking that
// rotation out, a part merely turned far (a 180 deg twist, a rotated arm)
// would count as folded everywhere. Zero-area rest triangles are skipped.
// Throws Error(BadParameter) if the vertex counts differ.
int count_inverted(const Mesh& rest, const Positions& deformed);

// count_inverted for many deformations of one rest mesh: its normals and which
// of its triangles have area are found once (a live preview asks every frame),
// and its vertex adjacency the first time a triangle turned past 90 deg (at
// 200k vertices, building it took a sixth of a one-iteration edit in WASM).
class InversionCounter {
 public:
  explicit InversionCounter(const Mesh& rest);
  // `rest` must be the mesh this counter was made for.
  int count(const Mesh& rest, const Positions& deformed) const;
  // Builds the vertex adjacency now (the background preparation: a drag's
  // preview that first turns a triangle past 90 deg then does not wait 64 ms
  // for it at 200k vertices in WASM).
  void build_adjacency(const Mesh& rest) const;

 private:
  Positions rest_normals_;
  std::vector<char> has_area_;  // per rest triangle
  mutable std::shared_ptr<const VertexAdjacency> adjacency_;  // built on first need
};

}  // namespace aniso
