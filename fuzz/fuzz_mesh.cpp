// libFuzzer target: the whole path a user's file takes through the core.
//
// Input: one format byte (low two bits: OBJ, OFF, PLY, STL) and the file's
// bytes. What parses is checked; what is solvable and small is deformed
// (AnDefGrad, a few AnARAP iterations and a coupled shear's) and, if it has a boundary,
// flattened. aniso::Error is the expected way to refuse an input; anything
// else escaping (std::bad_alloc from an unbounded read, a std::out_of_range,
// a sanitizer report, a timeout) is a finding.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "anisoform/deformer.h"
#include "anisoform/error.h"
#include "anisoform/flatten.h"
#include "anisoform/mesh_check.h"
#include "anisoform/mesh_io.h"

namespace {

// Solving is what costs time per input; past this size the readers and the
// check have been exercised and the solve adds nothing new but seconds.
constexpr int kMaxSolvedVertices = 600;

void deform_a_little(const aniso::Mesh& mesh) {
  aniso::Deformer deformer(mesh);
  // The background preparation, its warm-up of a preview included (nine
  // parts; the bound only guards against a part that never ends).
  for (int part = 0; part < 20 && deformer.prepare_step() < 1.0; ++part) {
  }
  aniso::DeformRequest request;
  request.method = aniso::Method::AnDefGrad;
  request.direction.vector = Eigen::Vector3d(0.3, 1.0, 0.2).normalized();
  request.transform.su = 1.5;
  request.transform.sv = 0.8;
  deformer.deform(request);
  request.method = aniso::Method::AnArap;
  request.max_iterations = 2;
  deformer.deform(request);
  // Live previews of a shear and a rotation (targets without a map per
  // side), on a soft selection with unselected vertices (the shear's
  // orientation); then a committed shear: coupled rotations, Anderson on the
  // rotations (mixed unit quaternions, renormalized; a rejected proposal's
  // way back).
  request.selection.resize(mesh.num_vertices());
  for (int i = 0; i < mesh.num_vertices(); ++i) request.selection[i] = 0.5 * (i % 3);
  aniso::TransformSpec shear, rotation;
  shear.shear = 0.4;
  rotation.rotate_axis = aniso::RotateAxis::Normal;
  rotation.rotate_degrees = 30.0;
  const auto solve = [&](const aniso::TransformSpec& transform, bool preview, int iterations) {
    request.transform = transform;
    request.preview = preview;
    request.warm_start = preview;
    request.max_iterations = iterations;
    deformer.deform(request);
  };
  solve(shear, true, 1);
  solve(rotation, true, 1);
  solve(shear, false, 6);
}

void flatten_a_little(const aniso::Mesh& mesh) {
  aniso::FlattenOptions options;
  options.su = 0.9;
  options.solver.max_iterations = 5;
  aniso::flatten(mesh, {}, options);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  static const aniso::MeshFormat kFormats[] = {aniso::MeshFormat::Obj, aniso::MeshFormat::Off,
                                               aniso::MeshFormat::Ply, aniso::MeshFormat::Stl};
  const aniso::MeshFormat format = kFormats[data[0] & 3];
  try {
    aniso::ReadResult read =
        aniso::read_mesh_from_memory(reinterpret_cast<const char*>(data + 1), size - 1, format);
    const aniso::MeshReport report = aniso::check_mesh(read.mesh);
    if (!report.solvable() || read.mesh.num_vertices() > kMaxSolvedVertices) return 0;
    deform_a_little(read.mesh);
    if (report.boundary_loops > 0) flatten_a_little(read.mesh);
  } catch (const aniso::Error&) {
    // A clear refusal: the behaviour we want for bad input.
  }
  return 0;
}
