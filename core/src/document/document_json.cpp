// document_from_json / document_from_text / document_schema (document.h):
// the document's own keys here; every region and op inside it goes through
// the op module's parsers (op.h), so the document adds no second schema.
#include <set>

#include "../request/json_fields.h"
#include "anisoform/document.h"

namespace aniso {
namespace {

using json_fields::Keys;

const Keys kDocumentKeys{"format", "version", "mesh", "regions", "ops"};
const Keys kDocumentMeshKeys{"name", "vertices", "triangles", "hash"};
const Keys kDocumentRegionKeys{"name", "steps"};
const Keys kDocumentStepKeys{"region", "falloff", "mode"};
const Keys kDocumentOpKeys{"id", "label", "enabled", "region", "op"};
const Keys kReplayOptionKeys{"from", "to", "preview"};

std::string text_field(const Json& value, const std::string& field) {
  if (!value.is_string()) json_fields::refuse(field, "must be a string, got " + json_fields::describe(value));
  return value.get<std::string>();
}

std::string non_empty_text(const Json& value, const std::string& field) {
  std::string text = text_field(value, field);
  if (text.empty()) json_fields::refuse(field, "must not be empty");
  return text;
}

// Runs a parser of the op module, whose messages start with its own root
// ("op.transform...", "region.sphere..."), and puts where the object sits in
// the document in front: "document.ops[1] (id 'neck').op.transform...".
template <typename Parse>
auto inside_document(const std::string& where, Parse&& parse) -> decltype(parse()) {
  try {
    return parse();
  } catch (const Error& error) {
    if (error.code() != ErrorCode::BadParameter) throw;
    throw Error(error.code(), where + "." + error.what());
  }
}

DocumentRegion region_rule_from_json(const Json& value, const std::string& where) {
  using namespace json_fields;
  object(value, where);
  reject_unknown_keys(value, kDocumentRegionKeys, where);
  DocumentRegion region;
  region.name = non_empty_text(member(value, "name", where + ".name"), where + ".name");
  const std::string named = where + " (name '" + region.name + "')";
  const Json& steps = member(value, "steps", named + ".steps");
  if (!steps.is_array() || steps.empty()) refuse(named + ".steps", "must be a non-empty array of select steps");
  for (std::size_t k = 0; k < steps.size(); ++k) {
    const std::string at = named + ".steps[" + std::to_string(k) + "]";
    const Json& step = object(steps[k], at);
    reject_unknown_keys(step, kDocumentStepKeys, at);
    DocumentSelectStep parsed;
    parsed.region = inside_document(at, [&] { return region_from_json(member(step, "region", at + ".region")); });
    if (has(step, "falloff")) {
      parsed.falloff = finite_number(step["falloff"], at + ".falloff");
      if (parsed.falloff < 0.0) refuse(at + ".falloff", "must be >= 0, got " + describe(step["falloff"]));
    }
    if (has(step, "mode")) parsed.mode = inside_document(at, [&] { return selection_mode_from_json(step["mode"]); });
    region.steps.push_back(std::move(parsed));
  }
  return region;
}

DocumentOp op_entry_from_json(const Json& value, const std::string& where) {
  using namespace json_fields;
  object(value, where);
  reject_unknown_keys(value, kDocumentOpKeys, where);
  DocumentOp op;
  op.id = non_empty_text(member(value, "id", where + ".id"), where + ".id");
  const std::string named = where + " (id '" + op.id + "')";
  if (has(value, "label")) op.label = text_field(value["label"], named + ".label");
  if (has(value, "enabled")) op.enabled = flag(value["enabled"], named + ".enabled");
  op.region = non_empty_text(member(value, "region", named + ".region"), named + ".region");
  const Json& edit = member(value, "op", named + ".op");
  // A document holds resolved ops (resolve_for_document): a screen drag is
  // stored as the global vector it gave, never as the drag (which needs the
  // camera of the moment). Said so, rather than "direction.camera is missing".
  if (edit.is_object() && has(edit, "direction") && edit["direction"].is_object() &&
      has(edit["direction"], "type") && edit["direction"]["type"] == "screen") {
    refuse(named + ".op.direction",
           "is a screen drag, which a document does not store: store the global vector it gives, "
           "{\"type\": \"global\", \"vector\": [x, y, z]} (as Session.resolveOp writes it)");
  }
  op.edit = inside_document(named, [&] { return deform_op_from_json(edit); });
  return op;
}

}  // namespace

EditDocument document_from_json(const Json& document) {
  using namespace json_fields;
  object(document, "document");
  const Json& format = member(document, "format", "document.format");
  if (format != Json(kDocumentFormat)) {
    refuse("document.format", "must be '" + std::string(kDocumentFormat) + "', got " + describe(format));
  }
  const Json& version = member(document, "version", "document.version");
  if (!version.is_number_integer() || version.get<long long>() != kDocumentVersion) {
    refuse("document.version", "is " + describe(version) + ", which this build does not read (it reads version " +
                                   std::to_string(kDocumentVersion) + ")");
  }
  reject_unknown_keys(document, kDocumentKeys, "document");

  EditDocument out;
  const Json& mesh = object(member(document, "mesh", "document.mesh"), "document.mesh");
  reject_unknown_keys(mesh, kDocumentMeshKeys, "document.mesh");
  out.mesh_name = text_field(member(mesh, "name", "document.mesh.name"), "document.mesh.name");
  out.vertices = integer_at_least(member(mesh, "vertices", "document.mesh.vertices"), 0, "document.mesh.vertices");
  out.triangles =
      integer_at_least(member(mesh, "triangles", "document.mesh.triangles"), 0, "document.mesh.triangles");
  out.mesh_hash = text_field(member(mesh, "hash", "document.mesh.hash"), "document.mesh.hash");
  // Its form, mesh_hash_text's: a malformed hash is the document's fault, not another mesh.
  if (!is_mesh_hash_text(out.mesh_hash)) {
    refuse("document.mesh.hash", "must be 'fnv1a64:<16 hex digits>' (as mesh_hash_text writes it), got " +
                                     describe(mesh["hash"]));
  }

  std::set<std::string> region_names;
  const Json& regions = member(document, "regions", "document.regions");
  if (!regions.is_array()) refuse("document.regions", "must be an array, got " + describe(regions));
  for (std::size_t i = 0; i < regions.size(); ++i) {
    const std::string where = "document.regions[" + std::to_string(i) + "]";
    DocumentRegion region = region_rule_from_json(regions[i], where);
    if (!region_names.insert(region.name).second) refuse(where + ".name", "'" + region.name + "' is used twice");
    out.regions.push_back(std::move(region));
  }

  std::set<std::string> op_ids;
  const Json& ops = member(document, "ops", "document.ops");
  if (!ops.is_array()) refuse("document.ops", "must be an array, got " + describe(ops));
  for (std::size_t i = 0; i < ops.size(); ++i) {
    const std::string where = "document.ops[" + std::to_string(i) + "]";
    DocumentOp op = op_entry_from_json(ops[i], where);
    if (!op_ids.insert(op.id).second) refuse(where + ".id", "'" + op.id + "' is used twice");
    if (!region_names.count(op.region)) {
      refuse(where + " (id '" + op.id + "').region",
             "names region '" + op.region + "', which the document's regions do not hold");
    }
    out.ops.push_back(std::move(op));
  }
  return out;
}

EditDocument document_from_text(const std::string& text) {
  return document_from_json(json_from_text(text, "the document"));
}

Json document_schema() {
  return {
      {"document", kDocumentKeys},       {"document.mesh", kDocumentMeshKeys},
      {"document.region", kDocumentRegionKeys}, {"document.step", kDocumentStepKeys},
      {"document.op", kDocumentOpKeys},      {"replay", kReplayOptionKeys},
  };
}

ReplayRange replay_range_from_json(const Json& options) {
  using namespace json_fields;
  object(options, "replay options");
  reject_unknown_keys(options, kReplayOptionKeys, "replay options");
  ReplayRange range;
  if (has(options, "from")) range.from = static_cast<std::size_t>(integer_at_least(options["from"], 0, "replay options.from"));
  if (has(options, "to")) range.to = static_cast<std::size_t>(integer_at_least(options["to"], 0, "replay options.to"));
  if (has(options, "preview")) range.preview = flag(options["preview"], "replay options.preview");
  return range;
}

Json to_json(const ReplaySummary& summary) {
  return {{"replayed", summary.replayed},
          {"skipped", summary.skipped},
          {"warnings", summary.warnings},
          {"last", summary.replayed > 0 ? to_json(summary.last) : Json(nullptr)}};
}

}  // namespace aniso
