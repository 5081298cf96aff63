// The benchmark build's extra bindings, linked only into anisoform-bench.mjs
// (wasm/CMakeLists.txt), never into the shipped module: the benchmarks'
// procedural cylinder and the Laplacian factor/solve floor every solver is
// measured against (bench/wasm-bench.mjs), and memory held aside for the
// tests of a nearly full heap.
#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/SparseCholesky>
#include <emscripten/bind.h>
#include <emscripten/val.h>

#include "anisoform/error.h"
#include "anisoform/laplacian.h"
#include "bench/primitives.h"
#include "anisoform/session.h"
#include "guarded.h"
#include "js_values.h"

using emscripten::val;

namespace aniso::wasm {
namespace {

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

// ---- A nearly full heap ------------------------------------------------------

// What holdMemory() took, kept until releaseHeldMemory(): the tests of what a
// session does when memory runs out, on meshes that fill a test's heap
// quickly instead of 2 GB slowly.
std::vector<std::unique_ptr<char[]>>& held_blocks() {
  static std::vector<std::unique_ptr<char[]>> blocks;
  return blocks;
}

val hold_memory(double bytes) {
  return guarded([&] {
    if (!(bytes >= 1 && bytes <= 2147483648.0)) {
      fail(ErrorCode::BadParameter, "holdMemory: bytes must be from 1 to 2^31");
    }
    // Not value-initialized: the pages need not be written to count as taken.
    std::unique_ptr<char[]> block(new char[static_cast<std::size_t>(bytes)]);
    held_blocks().push_back(std::move(block));
  });
}

void release_held_memory() { held_blocks().clear(); }

}  // namespace
}  // namespace aniso::wasm

EMSCRIPTEN_BINDINGS(anisoform_bench) {
  using namespace aniso::wasm;
  emscripten::function("cappedCylinder", &capped_cylinder_js);
  emscripten::function("holdMemory", &hold_memory);
  emscripten::function("releaseHeldMemory", &release_held_memory);
  emscripten::class_<LaplacianFloor>("LaplacianFloor")
      .constructor<>()
      .function("factor", &LaplacianFloor::factor)
      .function("solve", &LaplacianFloor::solve);
}
