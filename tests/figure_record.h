// The reproduction gallery's hook into the figure scenes (scripts/figures.sh).
// With ANISO_FIGURES_DIR set, a scene writes the meshes it shows and the
// values it measures there, so that the gallery renders and quotes the very
// scenes the tests check (one definition of each scene, here in C++). Without
// it (the test command) every call returns at once.
#pragma once

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "anisoform/mesh.h"

namespace aniso::test {

// The directory the gallery collects into, "" when not recording.
inline std::string figures_dir() {
  const char* dir = std::getenv("ANISO_FIGURES_DIR");
  return dir ? std::string(dir) : std::string();
}

// One picture's mesh: `name` (e.g. "5-anarap") becomes DIR/NAME.json with the
// positions (#V by 2 or 3; a 2D pattern lies in z = 0), the triangles, the
// selection weights (empty: none shown) and a per-vertex heat value of the
// app's palette `heat_kind` ("area", "stretch": log2 ratios; "compression":
// errors), or "marker" (1 draws a line in the gallery's marker colour; empty:
// no heat map).
inline void record_figure_mesh(const std::string& name, const Eigen::MatrixXd& V, const Triangles& F,
                               const Eigen::VectorXd& selection = Eigen::VectorXd(),
                               const Eigen::VectorXd& heat = Eigen::VectorXd(),
                               const std::string& heat_kind = "") {
  const std::string dir = figures_dir();
  if (dir.empty()) return;
  // Rounded: the pictures do not need more, and the files stay small.
  auto rounded = [](double x) { return std::round(x * 1e6) / 1e6; };
  nlohmann::json out;
  nlohmann::json& positions = out["positions"] = nlohmann::json::array();
  for (Eigen::Index i = 0; i < V.rows(); ++i) {
    for (int k = 0; k < 3; ++k) positions.push_back(k < V.cols() ? rounded(V(i, k)) : 0.0);
  }
  nlohmann::json& triangles = out["triangles"] = nlohmann::json::array();
  for (Eigen::Index t = 0; t < F.rows(); ++t) {
    for (int k = 0; k < 3; ++k) triangles.push_back(F(t, k));
  }
  if (selection.size() > 0) {
    out["selection"] = std::vector<double>(selection.data(), selection.data() + selection.size());
  }
  if (heat.size() > 0) {
    nlohmann::json& values = out["heat"] = nlohmann::json::array();
    for (Eigen::Index i = 0; i < heat.size(); ++i) values.push_back(std::isfinite(heat[i]) ? rounded(heat[i]) : 0.0);
    out["heatKind"] = heat_kind;
  }
  std::ofstream(dir + "/" + name + ".json") << out.dump();
}

// A measured value the gallery quotes: a line {"key": KEY, "value": VALUE}
// appended to DIR/values.jsonl (keys like "5.anarap.top_tilt").
inline void record_figure_value(const std::string& key, double value) {
  const std::string dir = figures_dir();
  if (dir.empty()) return;
  std::ofstream(dir + "/values.jsonl", std::ios::app) << nlohmann::json{{"key", key}, {"value", value}}.dump() << "\n";
}

}  // namespace aniso::test
