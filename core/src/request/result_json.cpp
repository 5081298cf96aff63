// The results as JSON with the keys the JS API returns (op.h), and the op's
// schema as the parsers read it.
#include "anisoform/document.h"
#include "anisoform/op.h"
#include "op_keys.h"

namespace aniso {
namespace {

Json vector3_json(const Eigen::Vector3d& v) { return Json::array({v.x(), v.y(), v.z()}); }

}  // namespace

Json to_json(const SessionMeshInfo& info) {
  const MeshReport& r = info.report;
  Json problems = Json::array();
  for (const Problem& p : r.problems) {
    problems.push_back({{"kind", problem_kind_name(p.kind)}, {"element", p.element}, {"message", p.message}});
  }
  Json counts = Json::object();
  for (int k = 0; k < kProblemKinds; ++k) {
    if (r.problem_counts[k] > 0) counts[problem_kind_name(static_cast<ProblemKind>(k))] = r.problem_counts[k];
  }
  const ModelUnitGuess unit = guess_model_unit(r.bbox);
  return {
      {"vertices", r.vertices},
      {"triangles", r.triangles},
      {"components", r.components},
      {"boundaryLoops", r.boundary_loops},
      {"edgeManifold", r.edge_manifold},
      {"vertexManifold", r.vertex_manifold},
      {"consistentlyOriented", r.consistently_oriented},
      {"degenerateTriangles", r.degenerate_triangles},
      {"duplicateFaces", r.duplicate_faces},
      {"unreferencedVertices", r.unreferenced_vertices},
      {"bbox", {{"min", vector3_json(r.bbox.min)}, {"max", vector3_json(r.bbox.max)}}},
      {"unitGuess", {{"name", unit.name}, {"mmPerUnit", unit.mm_per_unit}}},
      {"problems", problems},
      {"problemCounts", counts},
      {"notes", info.notes},
  };
}

Json to_json(const DeformOpResult& r) {
  return {
      {"selected", r.selected},
      {"iterations", r.iterations},
      {"energy", r.energy},
      {"energyHistory", r.energy_history},
      {"converged", r.converged},
      {"directionsFilled", r.directions_filled},
      {"inverted", r.inverted},
      {"factorizations", r.factorizations},
      {"precomputeMs", r.precompute_ms},
      {"solveMs", r.solve_ms},
      {"ms", r.total_ms},
      {"warnings", r.warnings},
  };
}

namespace {

// The regions that need a dart or a cut (FlattenRegion, flatten.h).
Json suggested_cuts_json(const std::vector<FlattenRegion>& regions) {
  Json out = Json::array();
  for (const FlattenRegion& r : regions) {
    out.push_back({{"vertices", r.vertices},
                   {"vertex", r.vertex},
                   {"centroid", {r.centroid.x(), r.centroid.y(), r.centroid.z()}},
                   {"errorMean", r.error_mean},
                   {"triangles", r.triangles}});
  }
  return out;
}

}  // namespace

Json to_json(const FlattenMetrics& m) {
  return {
      {"triangles", m.triangles},
      {"vertices", m.vertices},
      {"components", m.components},
      {"boundaryLoops", m.boundary_loops},
      {"flipped", m.flipped},
      {"outlineCrossings", m.outline_crossings},
      {"compressionErrorMean", m.compression_error_mean},
      {"compressionErrorMax", m.compression_error_max},
      {"crossErrorMean", m.cross_error_mean},
      {"crossErrorMax", m.cross_error_max},
      {"areaDistortionMean", m.area_distortion_mean},
      {"shearDegreesMean", m.shear_degrees_mean},
      {"shearDegreesMax", m.shear_degrees_max},
      {"nearNormalDirections", m.near_normal_directions},
      {"iterations", m.iterations},
      {"energy", m.energy},
      {"converged", m.converged},
      {"seconds", m.seconds},
      {"filledDirections", m.filled_directions},
      {"initialization", m.initialization},
      {"method", m.method},
      {"problem", flatten_problem(m)},
      {"warnings", flatten_warnings(m)},
      {"suggestedCuts", suggested_cuts_json(m.suggested_cuts)},
  };
}

Json op_schema() {
  using namespace op_keys;
  Json schema = {
      {"op", kOp},
      {"op.transform", kTransform},
      {"op.transform.rotate", kRotate},
      {"op.transform.twist", kTwist},
      {"direction.type", kDirectionTypes},
      {"direction.global", kGlobal},
      {"direction.curvature", kCurvature},
      {"direction.screen", kScreen},
      {"direction.screen.camera", kCamera},
      {"direction.constraints", kConstraints},
      {"direction.constraint", kConstraint},
      {"direction.dense", kDense},
      {"region", kRegionKinds},
      {"region.sphere", kSphere},
      {"region.box", kBox},
      {"region.vertices", kVertices},
      {"flatten", kFlatten},
      {"select", kSelect},
      {"setMesh", kMeshOptions},
      {"exportPattern", kPatternOptions},
  };
  schema.update(document_schema());
  return schema;
}

}  // namespace aniso
