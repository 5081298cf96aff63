// region_from_json and selection_mode_from_json (op.h).
#include "anisoform/op.h"
#include "json_fields.h"
#include "op_keys.h"

namespace aniso {


Region region_from_json(const Json& region) {
  using namespace json_fields;
  object(region, "region");
  std::string kinds;
  int count = 0;
  std::string kind;
  for (const std::string& candidate : op_keys::kRegionKinds) {
    if (!has(region, candidate.c_str())) continue;
    kinds += (kinds.empty() ? "" : ", ") + candidate;
    kind = candidate;
    ++count;
  }
  if (count != 1) refuse("region", "must have exactly one of all, sphere, box, vertices; got " + (kinds.empty() ? std::string("none") : kinds));
  reject_unknown_keys(region, kind == "vertices" ? op_keys::kVertices : Keys{kind}, "region");
  Region out;
  // Ranges (a negative radius, min above max, weights outside [0, 1], indices
  // beyond the mesh) are region_weights' to refuse.
  if (kind == "all") {
    if (region["all"] != Json(true)) refuse("region.all", "must be true");
    out.kind = Region::Kind::All;
  } else if (kind == "sphere") {
    const Json& sphere = object(region["sphere"], "region.sphere");
    reject_unknown_keys(sphere, op_keys::kSphere, "region.sphere");
    out.kind = Region::Kind::Sphere;
    out.center = vector3(member(sphere, "center", "region.sphere.center"), "region.sphere.center");
    out.radius = finite_number(member(sphere, "radius", "region.sphere.radius"), "region.sphere.radius");
  } else if (kind == "box") {
    const Json& box = object(region["box"], "region.box");
    reject_unknown_keys(box, op_keys::kBox, "region.box");
    out.kind = Region::Kind::Box;
    out.min = vector3(member(box, "min", "region.box.min"), "region.box.min");
    out.max = vector3(member(box, "max", "region.box.max"), "region.box.max");
  } else {
    out.kind = Region::Kind::Vertices;
    out.vertices = indices(region["vertices"], "region.vertices");
    if (has(region, "weights")) out.weights = finite_numbers(region["weights"], out.vertices.size(), "region.weights");
  }
  return out;
}

SelectionMode selection_mode_from_json(const Json& mode) {
  using namespace json_fields;
  const std::string name = one_of(mode, {"replace", "add", "subtract"}, "select: options.mode");
  if (name == "add") return SelectionMode::Add;
  if (name == "subtract") return SelectionMode::Subtract;
  return SelectionMode::Replace;
}

}  // namespace aniso
