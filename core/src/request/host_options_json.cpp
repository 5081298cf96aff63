// The JS API's small option objects and enum names (op.h): read here so that
// their defaults and names live in the core with the rest of the schema.
#include <string>

#include "anisoform/op.h"
#include "json_fields.h"
#include "op_keys.h"

namespace aniso {

SelectOptions select_options_from_json(const Json& options) {
  using namespace json_fields;
  object(options, "select: options");
  reject_unknown_keys(options, op_keys::kSelect, "select: options");
  SelectOptions out;
  if (has(options, "falloff")) out.falloff = finite_number(options["falloff"], "select: options.falloff");
  if (has(options, "mode")) out.mode = selection_mode_from_json(options["mode"]);
  return out;
}

MeshOptions mesh_options_from_json(const Json& options) {
  using namespace json_fields;
  object(options, "setMesh: options");
  reject_unknown_keys(options, op_keys::kMeshOptions, "setMesh: options");
  MeshOptions out;
  if (has(options, "weld")) out.weld = flag(options["weld"], "setMesh: options.weld");
  return out;
}

PatternOptions pattern_options_from_json(const Json& options) {
  using namespace json_fields;
  object(options, "exportPattern: options");
  reject_unknown_keys(options, op_keys::kPatternOptions, "exportPattern: options");
  PatternOptions out;
  if (has(options, "mmPerUnit")) {
    out.mm_per_unit = finite_number(options["mmPerUnit"], "exportPattern: options.mmPerUnit");
  }
  return out;
}

DistortionKind distortion_kind_from_name(const std::string& name) {
  if (name == "area") return DistortionKind::AreaRatio;
  if (name == "stretch") return DistortionKind::Stretch;
  fail(ErrorCode::BadParameter, "distortion: kind must be one of area, stretch, got '" + name + "'");
}

DistortionReference distortion_reference_from_name(const std::string& name) {
  if (name == "rest") return DistortionReference::Rest;
  if (name == "loaded") return DistortionReference::Loaded;
  fail(ErrorCode::BadParameter, "distortion: reference must be one of rest, loaded, got '" + name + "'");
}

MeshFormat mesh_format_from_name(const std::string& name) {
  for (MeshFormat format : {MeshFormat::Obj, MeshFormat::Off, MeshFormat::Ply, MeshFormat::Stl}) {
    std::string lower = format_name(format);  // "OBJ"
    for (char& c : lower) c = static_cast<char>(c - 'A' + 'a');
    if (name == lower) return format;
  }
  fail(ErrorCode::BadParameter, "exportMesh: format must be one of obj, off, ply, stl, got '" + name + "'");
}

}  // namespace aniso
