// `anisoform replay DOC OUT [--mesh PATH]`: replays an edit document
// (document.h) on its base mesh and writes the result. The mesh is read the
// way the browser reads it (Session::load_mesh), so its hash is the one the
// page put in the document; replay itself is the core's replay_document, the
// same code the WASM module runs.
//
// Exit statuses as every command (commands.h): a malformed document or OUT is
// 2 before the mesh is read; an unreadable mesh, or one whose hash does not
// match the document's, is 3.
#include <memory>

#include "anisoform/document.h"
#include "anisoform/file_io.h"
#include "cli_common.h"
#include "commands.h"

namespace aniso::cli {

namespace {

struct ReplayArguments {
  std::string document;
  std::string output;
  std::string mesh;  // empty: the document's mesh.name beside DOC
  bool ascii = false;
};

// The file `name` (a document's mesh.name) beside `path`: its file name
// only. A name with folders ("../../x.off", "/etc/x") named any file
// anywhere for the reader to quote; the page stores file names.
std::string path_beside(const std::string& path, const std::string& name) {
  const std::size_t folder = name.find_last_of("/\\");
  const std::string file = folder == std::string::npos ? name : name.substr(folder + 1);
  if (file.empty() || file == "." || file == ".." || file.find('\0') != std::string::npos) {
    throw Error(ErrorCode::BadParameter, "DOC: document.mesh.name " + Json(name).dump() +
                                             " is no file name to look for beside DOC: give the mesh with --mesh");
  }
  const std::size_t slash = path.find_last_of('/');
  return slash == std::string::npos ? file : path.substr(0, slash + 1) + file;
}

int run_replay(const ReplayArguments& args) {
  // Read, then parsed: each names DOC once.
  const std::string text = read_text_file(args.document, "DOC");
  const EditDocument document = naming_option("DOC", [&] { return document_from_text(text); });
  check_output_path(args.output);
  const std::string mesh_path = args.mesh.empty() ? path_beside(args.document, document.mesh_name) : args.mesh;
  const std::string bytes = read_regular_file(mesh_path);

  Session session;
  session.load_mesh(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size(), mesh_path);
  const ReplaySummary summary = replay_document(session, document);

  write_mesh(args.output, Mesh{session.positions(), session.rest().F}, session.write_options(!args.ascii));
  Json result = {{"document", args.document},
                 {"mesh", mesh_path},
                 {"output", args.output},
                 {"hash", mesh_hash_text(session.mesh_hash())},
                 {"vertices", session.rest().num_vertices()},
                 {"triangles", session.rest().num_triangles()}};
  result.update(to_json(summary));
  print_json(result);
  return kExitSuccess;
}

}  // namespace

void register_replay(CLI::App& app, Action& action) {
  auto args = std::make_shared<ReplayArguments>();
  CLI::App* replay = app.add_subcommand(
      "replay",
      "Replay an edit document (docs/document.schema.json) on its base mesh and write the "
      "result. Keys: document, mesh, output, hash, vertices, triangles, replayed, skipped, warnings (ops "
      "that left the mesh unchanged, and why), last (the last replayed op's result, null when none was "
      "replayed; in the JS API's camelCase, as the browser's replay returns it: selected, iterations, energy, "
      "energyHistory, converged, directionsFilled, inverted, factorizations, precomputeMs, solveMs, ms, warnings). "
      "The mesh must be the document's (its hash is checked).");
  replay->add_option("DOC", args->document, "Edit document (.json)")->required();
  replay->add_option("OUT", args->output, "Output mesh: .obj .off .ply .stl")->required();
  replay->add_option("--mesh", args->mesh, "Base mesh (default: the document's mesh.name beside DOC)");
  replay->add_flag("--ascii", args->ascii, "Write PLY/STL as text");
  run_when_chosen(replay, args, action, run_replay);
}

}  // namespace aniso::cli
