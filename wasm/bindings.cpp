// The embind block of the WASM module: aniso::Session for the browser.
//
// Thin on purpose. Requests arrive as the JSON text of the public objects
// (op, region, direction, options) and are parsed by the core's one schema
// (core/include/anisoform/op.h), with its defaults and its checks; results
// leave as the core's JSON (to_json in op.h), parsed into JS objects here, or
// as typed arrays. js/anisoform-wasm.mjs only converts arguments and maps
// errors. Every call runs inside guarded() (guarded.h).
//
// Arrays out: positions, triangles and selection are views on the WASM heap
// (typed_memory_view, no copy). Any later call may grow the memory and detach
// them, so the JS layer fetches them afresh every time. Everything else
// (flatten results and pattern files included) is returned as a JS-owned copy.
#include <malloc.h>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <emscripten/bind.h>
#include <emscripten/heap.h>
#include <emscripten/val.h>

#include "anisoform/document.h"
#include "anisoform/error.h"
#include "anisoform/op.h"
#include "anisoform/session.h"
#include "guarded.h"
#include "js_values.h"

using emscripten::val;

namespace aniso::wasm {
namespace {

// The JS layer always sends valid JSON; a caller of the raw module may not
// (refused as the core refuses a document's or an op file's text).
Json parse_request(const std::string& text, const char* what) { return json_from_text(text, what); }

val to_js(const Json& json) {
  return val::global("JSON").call<val>("parse", json.dump());
}

val positions_copy(const Positions& V) {
  std::vector<float> xyz(static_cast<std::size_t>(V.size()));
  for (std::size_t i = 0; i < xyz.size(); ++i) xyz[i] = static_cast<float>(V.data()[i]);
  return copy_to_js(xyz.data(), xyz.size());
}

val flatten_result_to_js(const SessionFlattenResult& r) {
  val out = val::object();
  out.set("uv", copy_to_js(r.uv.data(), r.uv.size()));
  out.set("triangles", copy_to_js(r.triangles.data(), r.triangles.size()));
  out.set("compressionError", copy_to_js(r.compression_error.data(), r.compression_error.size()));
  out.set("crossError", copy_to_js(r.cross_error.data(), r.cross_error.size()));
  out.set("vertexError", copy_to_js(r.vertex_error.data(), r.vertex_error.size()));
  Json grainlines = Json::array();
  for (const Eigen::Vector2d& g : r.grainlines) grainlines.push_back({g.x(), g.y()});
  out.set("grainlines", to_js(grainlines));
  val outlines = val::array();
  for (const std::vector<std::uint32_t>& loop : r.outlines) {
    outlines.call<void>("push", copy_to_js(loop.data(), loop.size()));
  }
  out.set("outlines", outlines);
  out.set("outlinePieces", copy_to_js(r.outline_pieces.data(), r.outline_pieces.size()));
  out.set("metrics", to_js(to_json(r.metrics)));
  out.set("factorizations", r.factorizations);
  return out;
}

val bytes_copy(const std::string& bytes) {
  return copy_to_js(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
}

// ---- Session methods as JS sees them -------------------------------------

val load_mesh(Session& s, const val& bytes, const std::string& name) {
  return guarded([&] {
    const std::vector<std::uint8_t> data = byte_vector(bytes);
    return to_js(to_json(s.load_mesh(data.data(), data.size(), name)));
  });
}

val set_mesh(Session& s, const val& positions, const val& triangles, const std::string& options) {
  return guarded([&] {
    const MeshOptions parsed = mesh_options_from_json(parse_request(options, "setMesh options"));
    return to_js(to_json(s.set_mesh(double_vector(positions),
                                    checked_indices<std::uint32_t>(triangles, "setMesh: triangles"),
                                    parsed.weld)));
  });
}

val input_vertex_map(Session& s) {
  return guarded([&] {
    const std::vector<std::uint32_t>& map = s.input_vertex_map();
    return copy_to_js(map.data(), map.size());
  });
}

// What the loaded file carried besides positions and triangles, in the forms
// a GLB export takes (the core writes OBJ and PLY with them itself): texture
// coordinates per triangle corner (u, v for corners 0, 1, 2 of each
// triangle), colours in [0, 1] per vertex (mesh_io.h vertex_colors) and the
// OBJ's material runs ({name, first}: the first triangle of each); null or
// empty for what the file had not.
val surface_attributes(Session& s) {
  return guarded([&] {
    const int n = static_cast<int>(s.positions().rows());
    const SurfaceAttributes& attributes = s.attributes();
    val out = val::object();
    out.set("cornerUv", val::null());
    const CornerTexture& texture = attributes.texture;
    if (!texture.empty()) {
      std::vector<float> corners(static_cast<std::size_t>(texture.faces.rows()) * 6);
      for (Eigen::Index t = 0; t < texture.faces.rows(); ++t) {
        for (int k = 0; k < 3; ++k) {
          for (int c = 0; c < 2; ++c) corners[6 * t + 2 * k + c] = static_cast<float>(texture.uv(texture.faces(t, k), c));
        }
      }
      out.set("cornerUv", copy_to_js(corners.data(), corners.size()));
    }
    out.set("colors", val::null());
    const Eigen::MatrixX3d colors = vertex_colors(attributes, n);
    if (colors.rows() > 0) {
      std::vector<float> rgb(static_cast<std::size_t>(colors.size()));
      for (Eigen::Index i = 0; i < colors.rows(); ++i) {
        for (int k = 0; k < 3; ++k) rgb[3 * i + k] = static_cast<float>(colors(i, k));
      }
      out.set("colors", copy_to_js(rgb.data(), rgb.size()));
    }
    val runs = val::array();
    for (const auto& [first, name] : attributes.materials.runs) {
      val run = val::object();
      run.set("name", name);
      run.set("first", first);
      runs.call<void>("push", run);
    }
    out.set("materials", runs);
    return out;
  });
}

val info(Session& s) {
  return guarded([&] { return to_js(to_json(s.info())); });
}

val positions_view(Session& s) {
  return guarded([&] {
    s.positions();  // throws when there is no mesh
    const std::vector<float>& xyz = s.positions_f32();
    return val(emscripten::typed_memory_view(xyz.size(), xyz.data()));
  });
}

val triangles_view(Session& s) {
  return guarded([&] {
    s.info();
    const std::vector<std::uint32_t>& indices = s.triangles_u32();
    return val(emscripten::typed_memory_view(indices.size(), indices.data()));
  });
}

val selection_view(Session& s) {
  return guarded([&] {
    s.info();
    const std::vector<float>& weights = s.selection_f32();
    return val(emscripten::typed_memory_view(weights.size(), weights.data()));
  });
}

val select(Session& s, const std::string& region, const std::string& options) {
  return guarded([&] {
    const Region parsed_region = region_from_json(parse_request(region, "region"));
    const SelectOptions parsed = select_options_from_json(parse_request(options, "select options"));
    return s.select(parsed_region, parsed.falloff, parsed.mode);
  });
}

val set_selection(Session& s, const val& weights) {
  return guarded([&] { return s.set_selection(float_vector(weights)); });
}

val deform(Session& s, const std::string& op) {
  return guarded([&] { return to_js(to_json(s.deform(deform_op_from_json(parse_request(op, "op"))))); });
}

val commit(Session& s) {
  return guarded([&] { s.commit(); });
}

val cancel(Session& s) {
  return guarded([&] { s.cancel(); });
}

val prepare_step(Session& s) {
  return guarded([&] { return s.prepare_step(); });
}

val set_positions(Session& s, const val& positions) {
  return guarded([&] { s.set_positions(double_vector(positions)); });
}

val direction_field(Session& s, const std::string& direction) {
  return guarded([&] {
    return positions_copy(s.direction_field(direction_from_json(parse_request(direction, "direction"), "direction")));
  });
}

val distortion(Session& s, const std::string& kind, const std::string& reference) {
  return guarded([&] {
    const Eigen::VectorXf values =
        s.distortion(distortion_kind_from_name(kind), distortion_reference_from_name(reference)).cast<float>();
    return copy_to_js(values.data(), static_cast<std::size_t>(values.size()));
  });
}

val export_mesh(Session& s, const std::string& format) {
  return guarded([&] { return bytes_copy(s.export_mesh(mesh_format_from_name(format))); });
}

val flatten(Session& s, const std::string& options) {
  return guarded([&] {
    return flatten_result_to_js(s.flatten(flatten_options_from_json(parse_request(options, "flatten options"))));
  });
}

val export_pattern(Session& s, const std::string& format, const std::string& options) {
  return guarded([&] {
    const PatternOptions parsed = pattern_options_from_json(parse_request(options, "exportPattern options"));
    return bytes_copy(s.export_pattern(format, parsed.mm_per_unit));
  });
}

// ---- the edit document (document.h) ----------------------------------------

val replay(Session& s, const std::string& document, const std::string& options) {
  return guarded([&] {
    const ReplayRange range = replay_range_from_json(parse_request(options, "replay options"));
    return to_js(to_json(replay_document(s, document_from_text(document), range)));
  });
}

val select_document_region_js(Session& s, const std::string& document, const std::string& op_id) {
  return guarded([&] { return select_document_region(s, document_from_text(document), op_id); });
}

// The op as the document stores it: resolved on the current rest pose and
// selection, view-independent.
val resolve_op(Session& s, const std::string& op) {
  return guarded([&] { return to_js(to_json(resolve_for_document(s, deform_op_from_json(parse_request(op, "op"))))); });
}

val mesh_hash_js(Session& s) {
  return guarded([&] { return val(mesh_hash_text(s.mesh_hash())); });
}

// The positions as the doubles the session holds (positions() is float32):
// what replay parity and a bitwise cache need.
val positions_exact(Session& s) {
  return guarded([&] {
    const Positions& V = s.positions();
    return copy_to_js(V.data(), static_cast<std::size_t>(V.size()));
  });
}

val factorizations(Session& s) {
  return guarded([&] { return s.factorizations(); });
}

// {inUse: bytes malloc'd now, heap: bytes of WASM memory (it only grows),
//  limit: the most it may grow to}: what a host shows, and what the tests
// check after an out-of-memory failure (everything the call took is freed).
val memory_use() {
  val out = val::object();
  out.set("inUse", static_cast<double>(mallinfo().uordblks));
  out.set("heap", static_cast<double>(emscripten_get_heap_size()));
  out.set("limit", static_cast<double>(emscripten_get_heap_max()));
  return out;
}

// The keys the core accepts in each request object (op_schema, op.h).
val op_schema_js() {
  return guarded([] { return to_js(op_schema()); });
}

// Progress of the long calls, to a JS function (stage name, fraction), or
// none with null/undefined. The function runs inside the call: the worker's
// posts a message and returns; it must not throw.
val set_progress(Session& s, val report) {
  return guarded([&] {
    if (report.isNull() || report.isUndefined()) {
      s.set_progress(nullptr);
      return;
    }
    s.set_progress([report](ProgressStage stage, double fraction) {
      report(std::string(progress_stage_name(stage)), fraction);
    });
  });
}

// A browser session refuses meshes too big to edit within the module's
// memory ceiling, at load rather than at the first edit. Every edit
// factorizes the whole mesh's Laplacian; measured in Node, one AnARAP
// commit on the 200k koala peaked at 632 MB of heap (3.2 KB per vertex) and
// one on a 416k mesh (the armadillo subdivided twice) at 1182 MB (2.8 KB per
// vertex). The budget is 4 KB per vertex, a margin over both: the factor's
// fill-in depends on the mesh, not on its size alone. (800k vertices ran a
// minute into the first commit and then failed at the 2 GB ceiling.)
// The budget is for one factorized pose: above half the limit the session
// keeps no second one for undo, and any call that runs out of memory frees
// the kept ones and runs again (session.h). Before that, a 420k-vertex
// cylinder's second commit failed; now 470k-520k take commits, undo and a
// flattening.
constexpr double kEditBytesPerVertex = 4096.0;

Session* new_browser_session() {
  auto session = std::make_unique<Session>();
  const double max_bytes = ANISO_WASM_MAXIMUM_MEMORY_GB * 1073741824.0;
  session->set_vertex_limit(
      static_cast<int>(max_bytes / kEditBytesPerVertex),
      "that can be edited here: every edit factorizes the whole mesh, about 4 KB per vertex, and this "
      "browser module may use at most " ANISO_STRINGIFY(ANISO_WASM_MAXIMUM_MEMORY_GB)
      " GB (use the native CLI, or a simplified mesh)");
  return session.release();
}

}  // namespace
}  // namespace aniso::wasm

EMSCRIPTEN_BINDINGS(anisoform) {
  using namespace aniso::wasm;
  using aniso::Session;
  emscripten::class_<Session>("Session")
      .constructor(&new_browser_session, emscripten::allow_raw_pointers())
      .function("vertexLimit", &Session::vertex_limit)
      .function("setProgress", &set_progress)
      .function("loadMesh", &load_mesh)
      .function("setMesh", &set_mesh)
      .function("info", &info)
      .function("inputVertexMap", &input_vertex_map)
      .function("surfaceAttributes", &surface_attributes)
      .function("positions", &positions_view)
      .function("triangles", &triangles_view)
      .function("select", &select)
      .function("setSelection", &set_selection)
      .function("selection", &selection_view)
      .function("deform", &deform)
      .function("commit", &commit)
      .function("cancel", &cancel)
      .function("prepareStep", &prepare_step)
      .function("setPositions", &set_positions)
      .function("directionField", &direction_field)
      .function("distortion", &distortion)
      .function("exportMesh", &export_mesh)
      .function("flatten", &flatten)
      .function("exportPattern", &export_pattern)
      .function("factorizations", &factorizations)
      .function("replay", &replay)
      .function("selectDocumentRegion", &select_document_region_js)
      .function("resolveOp", &resolve_op)
      .function("meshHash", &mesh_hash_js)
      .function("positionsExact", &positions_exact);
  emscripten::function("memoryUse", &memory_use);
  emscripten::function("opSchema", &op_schema_js);
}
