// What stays put (METHOD §7): gauge pins for components without user pins,
// and the rigid / translational re-alignment of the result to the unaffected
// part of the mesh.
#pragma once

#include <vector>

#include "anisoform/mesh.h"

namespace aniso {

struct Gauge {
  std::vector<int> pins;             // user pins plus one gauge pin per free component
  std::vector<int> component;        // component label per vertex
  std::vector<char> realign;         // per component: 1 = no user pin, re-align after solving
  int components = 0;
};

// Chooses the gauge pin of each component without a user pin: its lowest
// vertex index, whatever the selection, so that a new selection never changes
// the pin set and never refactors.
Gauge make_gauge(const Mesh& mesh, const std::vector<int>& user_pins);

// The same from the mesh's vertex_components labels (topology.h), which do not
// change with the pins: a Deformer finds them once per rest pose.
Gauge make_gauge(std::vector<int> component, int components, const std::vector<int>& user_pins);

enum class Alignment { Rigid, Translation };

// Moves each re-aligned component of V so that its unaffected vertices
// (weight 0) best match their rest positions (Kabsch fit or translation); a
// component with no unaffected vertex keeps its centroid (and, for Rigid, its
// best-fit orientation to the rest).
void realign(const Mesh& rest, const Gauge& gauge, const Eigen::VectorXd& weights,
             Alignment alignment, Positions& V);

}  // namespace aniso
