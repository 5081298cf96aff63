// `anisoform info MESH`: what a mesh file holds and what is wrong with it, as
// one JSON object. A mesh that parses is never refused here, however broken:
// info is the tool a user runs to find out why deform refused a mesh, so it
// reports problems instead of failing on them. Only a file that cannot be read
// or parsed exits 3 (and an unknown extension 2).
#include <algorithm>
#include <memory>

#include "cli_common.h"
#include "commands.h"

namespace aniso::cli {

namespace {

// Enough to see what is wrong; the counters give the full picture.
constexpr std::size_t kMaxListedProblems = 100;

Json problems_json(const std::vector<Problem>& problems) {
  Json listed = Json::array();
  const std::size_t count = std::min(problems.size(), kMaxListedProblems);
  for (std::size_t k = 0; k < count; ++k) {
    listed.push_back({{"kind", problem_kind_name(problems[k].kind)},
                      {"element", problems[k].element},
                      {"message", problems[k].message}});
  }
  return listed;
}

Json info_json(const std::string& path, const ReadResult& read, bool soup, const MeshReport& report) {
  return {
      {"file", path},
      {"format", format_name(format_from_path(path))},
      {"vertices", report.vertices},
      {"triangles", report.triangles},
      {"components", report.components},
      {"boundary_loops", report.boundary_loops},
      {"edge_manifold", report.edge_manifold},
      {"vertex_manifold", report.vertex_manifold},
      {"consistently_oriented", report.consistently_oriented},
      {"degenerate_triangles", report.degenerate_triangles},
      {"duplicate_faces", report.duplicate_faces},
      {"non_manifold_edges", report.non_manifold_edges},
      {"non_manifold_vertices", report.non_manifold_vertices},
      {"non_finite_vertices", report.non_finite_vertices},
      {"unreferenced_vertices", report.unreferenced_vertices},
      {"triangle_soup", soup},
      {"solvable", report.solvable()},
      {"bbox", to_json(report.bbox)},
      {"problem_count", report.problem_count()},
      {"problems_listed", std::min(report.problems.size(), kMaxListedProblems)},
      {"problems", problems_json(report.problems)},
      {"read", to_json(read.report)},
  };
}

int run_info(const std::string& path) {
  ReadResult read = read_input_mesh(path);
  // The mesh a session edits: a soup welded as the Session welds it (deform,
  // replay, the browser), counted among the read's welds as deform counts it.
  const int read_vertices = read.mesh.num_vertices();
  const bool soup = weld_if_triangle_soup(read.mesh, read.report.notes);
  read.report.vertices_welded += read_vertices - read.mesh.num_vertices();
  print_json(info_json(path, read, soup, check_mesh(read.mesh)));
  return kExitSuccess;
}

}  // namespace

void register_info(CLI::App& app, Action& action) {
  auto path = std::make_shared<std::string>();
  CLI::App* info = app.add_subcommand(
      "info",
      "Report a mesh's size, topology and problems as JSON. Keys: vertices, triangles, "
      "components, boundary_loops, edge_manifold, vertex_manifold, consistently_oriented, "
      "degenerate_triangles, duplicate_faces, non_manifold_edges, non_manifold_vertices, "
      "non_finite_vertices, unreferenced_vertices, triangle_soup (the file is one: reported welded, as "
      "deform and the browser edit it), solvable, bbox {min, max} (of the vertices faces use), "
      "problem_count (all), problems (the first 100 of {kind, element, message}), read (what the "
      "reader did: polygons triangulated, vertices welded, elements skipped, notes). "
      "A mesh that parses always gives exit 0; its problems are reported.");
  info->add_option("MESH", *path, "Mesh file: .obj .off .ply .stl")->required();
  run_when_chosen(info, path, action, run_info);
}

}  // namespace aniso::cli
