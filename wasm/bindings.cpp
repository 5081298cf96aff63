// The embind block of the WASM module: aniso::Session for the browser, the
// procedural cylinder of the benchmarks, and a bench-only Laplacian
// factor/solve path. Thin on purpose: JS values in and
// out, nothing more. Defaults, checks of the user's input and the public API
// live in js/anisoform-wasm.mjs, which every host uses instead of these raw
// bindings.
//
// Errors: every bound call runs inside guarded(), which catches any C++
// exception and RETURNS a JS Error carrying `code` (aniso::error_code_name,
// "out-of-memory" for std::bad_alloc and std::length_error, or "internal") and the C++ message;
// the JS layer throws it as an AnisoformError. Throwing a JS exception from inside the module instead
// (TOOLCHAIN.md §1 option (a)) skips the epilogues of the frames it unwinds:
// measured, every error then leaks 32 bytes of the 5 MB shadow stack and one
// emval handle, so a long session would end in a stack overflow.
//
// Arrays out: positions, triangles and selection are views on the WASM heap
// (typed_memory_view, no copy). Any later call may grow the memory and detach
// them, so the JS layer fetches them afresh every time. Everything else
// (flatten results and pattern files included) is returned as a JS-owned copy.
#include <malloc.h>

#include <cstdint>
#include <new>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include <Eigen/SparseCholesky>
#include <emscripten/bind.h>
#include <emscripten/heap.h>
#include <emscripten/val.h>

#include "anisoform/error.h"
#include "anisoform/laplacian.h"
#include "bench/primitives.h"
#include "anisoform/session.h"
#include "js_values.h"

using emscripten::val;

namespace aniso::wasm {
namespace {

// ANISO_WASM_MAXIMUM_MEMORY_GB is the -sMAXIMUM_MEMORY of the link
// (wasm/CMakeLists.txt), so the message names the limit actually in force.
#define ANISO_STRINGIFY2(x) #x
#define ANISO_STRINGIFY(x) ANISO_STRINGIFY2(x)
constexpr const char* kOutOfMemoryMessage =
    "out of memory: this needs more than the " ANISO_STRINGIFY(ANISO_WASM_MAXIMUM_MEMORY_GB)
    " GB of memory the module may use in the browser; nothing was changed "
    "(try a smaller mesh, or the native CLI)";

val error_value(const char* code, const char* message) {
  val error = val::global("Error").new_(std::string(message));
  error.set("code", std::string(code));
  return error;
}

// The body's result as a JS value, or the Error it failed with.
template <typename Body>
val guarded(Body&& body) {
  try {
    if constexpr (std::is_void_v<decltype(body())>) {
      body();
      return val::undefined();
    } else {
      return val(body());
    }
  } catch (const Error& error) {
    return error_value(error_code_name(error.code()), error.what());
  } catch (const std::length_error&) {
    // A container longer than 32-bit WASM can address: the same limit.
    return error_value("out-of-memory", kOutOfMemoryMessage);
  } catch (const std::bad_alloc&) {
    // Unwinding has freed what the call allocated, and the Session methods
    // change nothing until their work is done (session.h), so the session
    // stays as it was. The WASM memory itself never shrinks: it stays as
    // large as it grew, to be reused by the next calls.
    return error_value("out-of-memory", kOutOfMemoryMessage);
  } catch (const std::exception& error) {
    return error_value("internal", error.what());
  } catch (...) {
    return error_value("internal", "unknown C++ exception");
  }
}

// ---- JS values out -------------------------------------------------------

template <typename T>
val copy_to_js(const T* data, std::size_t count) {
  return val(emscripten::typed_memory_view(count, data)).call<val>("slice");
}

val positions_copy(const Positions& V) {
  std::vector<float> xyz(static_cast<std::size_t>(V.size()));
  for (std::size_t i = 0; i < xyz.size(); ++i) xyz[i] = static_cast<float>(V.data()[i]);
  return copy_to_js(xyz.data(), xyz.size());
}

val vector3_to_js(const Eigen::Vector3d& v) {
  val out = val::array();
  for (int k = 0; k < 3; ++k) out.call<void>("push", v[k]);
  return out;
}

val strings_to_js(const std::vector<std::string>& strings) {
  val out = val::array();
  for (const std::string& s : strings) out.call<void>("push", s);
  return out;
}

val info_to_js(const SessionMeshInfo& info) {
  const MeshReport& r = info.report;
  val out = val::object();
  out.set("vertices", r.vertices);
  out.set("triangles", r.triangles);
  out.set("components", r.components);
  out.set("boundaryLoops", r.boundary_loops);
  out.set("edgeManifold", r.edge_manifold);
  out.set("vertexManifold", r.vertex_manifold);
  out.set("consistentlyOriented", r.consistently_oriented);
  out.set("degenerateTriangles", r.degenerate_triangles);
  out.set("duplicateFaces", r.duplicate_faces);
  out.set("unreferencedVertices", r.unreferenced_vertices);
  val box = val::object();
  box.set("min", vector3_to_js(r.bbox.min));
  box.set("max", vector3_to_js(r.bbox.max));
  out.set("bbox", box);
  val problems = val::array();
  for (const Problem& p : r.problems) {
    val problem = val::object();
    problem.set("kind", std::string(problem_kind_name(p.kind)));
    problem.set("element", p.element);
    problem.set("message", p.message);
    problems.call<void>("push", problem);
  }
  out.set("problems", problems);
  out.set("notes", strings_to_js(info.notes));
  return out;
}

val edit_result_to_js(const SessionEditResult& r) {
  val out = val::object();
  out.set("selected", r.selected);
  out.set("iterations", r.iterations);
  out.set("energy", r.energy);
  out.set("energyHistory", copy_to_js(r.energy_history.data(), r.energy_history.size()));
  out.set("converged", r.converged);
  out.set("directionsFilled", r.directions_filled);
  out.set("inverted", r.inverted);
  out.set("factorizations", r.factorizations);
  out.set("precomputeMs", r.precompute_ms);
  out.set("solveMs", r.solve_ms);
  out.set("ms", r.total_ms);
  return out;
}

val metrics_to_js(const FlattenMetrics& m) {
  val out = val::object();
  out.set("triangles", m.triangles);
  out.set("vertices", m.vertices);
  out.set("components", m.components);
  out.set("boundaryLoops", m.boundary_loops);
  out.set("flipped", m.flipped);
  out.set("compressionErrorMean", m.compression_error_mean);
  out.set("compressionErrorMax", m.compression_error_max);
  out.set("crossErrorMean", m.cross_error_mean);
  out.set("crossErrorMax", m.cross_error_max);
  out.set("areaDistortionMean", m.area_distortion_mean);
  out.set("iterations", m.iterations);
  out.set("energy", m.energy);
  out.set("converged", m.converged);
  out.set("seconds", m.seconds);
  out.set("filledDirections", m.filled_directions);
  out.set("initialization", m.initialization);
  out.set("method", m.method);
  return out;
}

val flatten_result_to_js(const SessionFlattenResult& r) {
  val out = val::object();
  out.set("uv", copy_to_js(r.uv.data(), r.uv.size()));
  out.set("triangles", copy_to_js(r.triangles.data(), r.triangles.size()));
  out.set("compressionError", copy_to_js(r.compression_error.data(), r.compression_error.size()));
  out.set("crossError", copy_to_js(r.cross_error.data(), r.cross_error.size()));
  out.set("vertexError", copy_to_js(r.vertex_error.data(), r.vertex_error.size()));
  val grainlines = val::array();
  for (const Eigen::Vector2d& g : r.grainlines) {
    val pair = val::array();
    pair.call<void>("push", g.x());
    pair.call<void>("push", g.y());
    grainlines.call<void>("push", pair);
  }
  out.set("grainlines", grainlines);
  val outlines = val::array();
  for (const std::vector<std::uint32_t>& loop : r.outlines) {
    outlines.call<void>("push", copy_to_js(loop.data(), loop.size()));
  }
  out.set("outlines", outlines);
  out.set("outlinePieces", copy_to_js(r.outline_pieces.data(), r.outline_pieces.size()));
  out.set("metrics", metrics_to_js(r.metrics));
  out.set("factorizations", r.factorizations);
  return out;
}

MeshFormat export_format(const std::string& name) {
  if (name == "obj") return MeshFormat::Obj;
  if (name == "off") return MeshFormat::Off;
  if (name == "ply") return MeshFormat::Ply;
  if (name == "stl") return MeshFormat::Stl;
  fail(ErrorCode::BadParameter, "export format must be obj, off, ply or stl, got '" + name + "'");
}

// ---- Session methods as JS sees them -------------------------------------

val load_mesh(Session& s, const val& bytes, const std::string& name) {
  return guarded([&] {
    const std::vector<std::uint8_t> data = byte_vector(bytes);
    return info_to_js(s.load_mesh(data.data(), data.size(), name));
  });
}

val set_mesh(Session& s, const val& positions, const val& triangles, bool weld) {
  return guarded([&] {
    return info_to_js(
        s.set_mesh(double_vector(positions), checked_indices<std::uint32_t>(triangles, "setMesh: triangles"), weld));
  });
}

val info(Session& s) {
  return guarded([&] { return info_to_js(s.info()); });
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

val select(Session& s, const val& region, double falloff, const std::string& mode) {
  return guarded([&] {
    return s.select(region_from_js(region), falloff, selection_mode_from_js(mode));
  });
}

val set_selection(Session& s, const val& weights) {
  return guarded([&] { return s.set_selection(float_vector(weights)); });
}

val deform(Session& s, const val& request) {
  return guarded([&] { return edit_result_to_js(s.deform(edit_from_js(request))); });
}

val commit(Session& s) {
  return guarded([&] { s.commit(); });
}

val cancel(Session& s) {
  return guarded([&] { s.cancel(); });
}

val set_positions(Session& s, const val& positions) {
  return guarded([&] { s.set_positions(double_vector(positions)); });
}

val direction_field(Session& s, const val& direction) {
  return guarded([&] { return positions_copy(s.direction_field(direction_from_js(direction))); });
}

val distortion(Session& s, const std::string& kind, const std::string& reference) {
  return guarded([&] {
    const Eigen::VectorXd values =
        s.distortion(distortion_kind_from_js(kind), distortion_reference_from_js(reference));
    const Eigen::VectorXf floats = values.cast<float>();
    return copy_to_js(floats.data(), static_cast<std::size_t>(floats.size()));
  });
}

val export_mesh(Session& s, const std::string& format) {
  return guarded([&] {
    const std::string bytes = s.export_mesh(export_format(format));
    return copy_to_js(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
  });
}

val flatten(Session& s, const val& request) {
  return guarded([&] { return flatten_result_to_js(s.flatten(flatten_from_js(request))); });
}

val export_pattern(Session& s, const std::string& format, double mm_per_unit) {
  return guarded([&] {
    const std::string text = s.export_pattern(format, mm_per_unit);
    return copy_to_js(reinterpret_cast<const std::uint8_t*>(text.data()), text.size());
  });
}

val factorizations(Session& s) {
  return guarded([&] { return s.factorizations(); });
}

// ---- Memory ----------------------------------------------------------------

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

// ---- Procedural meshes -----------------------------------------------------

// {positions: Float64Array, triangles: Uint32Array} of aniso::capped_cylinder,
// the benchmark's cylNk meshes.
val capped_cylinder_js(int approx_vertices, double radius, double height) {
  return guarded([&] {
    const Mesh mesh = capped_cylinder(approx_vertices, radius, height);
    std::vector<std::uint32_t> triangles(static_cast<std::size_t>(mesh.F.size()));
    for (std::size_t i = 0; i < triangles.size(); ++i) triangles[i] = static_cast<std::uint32_t>(mesh.F.data()[i]);
    val out = val::object();
    out.set("positions", copy_to_js(mesh.V.data(), static_cast<std::size_t>(mesh.V.size())));
    out.set("triangles", copy_to_js(triangles.data(), triangles.size()));
    return out;
  });
}

// ---- Bench only: the floor every solver is measured against --------------

// bench/impls.cpp run_eigen_ldlt, in the module: the cotangent Laplacian of
// the session's rest mesh with `pins` removed, factored by Eigen's own
// SimplicialLDLT (factor(): the precompute), and Eigen's solve of the rest
// positions' 3 columns (solve(): one iteration's worth of linear algebra).
// bench/wasm-bench.mjs times both.
class LaplacianFloor {
 public:
  val factor(Session& s, const val& pins) {
    return guarded([&] {
      const Mesh& rest = s.rest();
      const int n = rest.num_vertices();
      const Eigen::SparseMatrix<double> L = cotangent_laplacian(rest, cotangent_weights(rest));
      std::vector<int> free_of(static_cast<std::size_t>(n), 0);
      for (int p : checked_indices<int>(pins, "LaplacianFloor: pins")) {
        if (p >= n) fail(ErrorCode::BadParameter, "pin " + std::to_string(p) + " is out of range");
        free_of[static_cast<std::size_t>(p)] = -1;
      }
      int free_count = 0;
      for (int& f : free_of) f = f < 0 ? -1 : free_count++;
      std::vector<Eigen::Triplet<double>> triplets;
      triplets.reserve(static_cast<std::size_t>(L.nonZeros()));
      for (int col = 0; col < L.outerSize(); ++col) {
        if (free_of[col] < 0) continue;
        for (Eigen::SparseMatrix<double>::InnerIterator it(L, col); it; ++it) {
          if (free_of[it.row()] >= 0) triplets.emplace_back(free_of[it.row()], free_of[col], it.value());
        }
      }
      Eigen::SparseMatrix<double> free_block(free_count, free_count);
      free_block.setFromTriplets(triplets.begin(), triplets.end());
      ldlt_.compute(free_block);
      if (ldlt_.info() != Eigen::Success) fail(ErrorCode::Numerical, "Eigen SimplicialLDLT failed");
      rhs_.resize(free_count, 3);
      for (int i = 0; i < n; ++i) {
        if (free_of[i] >= 0) rhs_.row(free_of[i]) = rest.V.row(i);
      }
      factored_ = true;
    });
  }

  val solve() {
    return guarded([&] {
      if (!factored_) fail(ErrorCode::BadParameter, "LaplacianFloor: factor() first");
      solution_ = ldlt_.solve(rhs_);
    });
  }

 private:
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt_;  // AMD ordering, as the native floor
  Eigen::MatrixXd rhs_;
  Eigen::MatrixXd solution_;
  bool factored_ = false;
};

}  // namespace
}  // namespace aniso::wasm

EMSCRIPTEN_BINDINGS(anisoform) {
  using namespace aniso::wasm;
  using aniso::Session;
  emscripten::class_<Session>("Session")
      .constructor<>()
      .function("loadMesh", &load_mesh)
      .function("setMesh", &set_mesh)
      .function("info", &info)
      .function("positions", &positions_view)
      .function("triangles", &triangles_view)
      .function("select", &select)
      .function("setSelection", &set_selection)
      .function("selection", &selection_view)
      .function("deform", &deform)
      .function("commit", &commit)
      .function("cancel", &cancel)
      .function("setPositions", &set_positions)
      .function("directionField", &direction_field)
      .function("distortion", &distortion)
      .function("exportMesh", &export_mesh)
      .function("flatten", &flatten)
      .function("exportPattern", &export_pattern)
      .function("factorizations", &factorizations);
  emscripten::function("cappedCylinder", &capped_cylinder_js);
  emscripten::function("memoryUse", &memory_use);
  emscripten::class_<LaplacianFloor>("LaplacianFloor")
      .constructor<>()
      .function("factor", &LaplacianFloor::factor)
      .function("solve", &LaplacianFloor::solve);
}
