// flatten_options_from_json (op.h): a flatten's options into a SessionFlatten.
#include "anisoform/op.h"
#include "anisoform/transforms.h"
#include "json_fields.h"
#include "op_keys.h"

namespace aniso {
namespace {

// A stretch of the pattern: a finite number, then the one scale rule.
double compress_amount(const Json& value, const std::string& field) {
  using namespace json_fields;
  const double amount = finite_number(value, field);
  validate_scale(amount, field);
  return amount;
}

}  // namespace

SessionFlatten flatten_options_from_json(const Json& options) {
  using namespace json_fields;
  const std::string name = "flatten: options";
  object(options, name);
  reject_unknown_keys(options, op_keys::kFlatten, name);
  SessionFlatten out;
  if (has(options, "compress")) {
    const Json& compress = options["compress"];
    if (compress.is_number()) {
      out.su = compress_amount(compress, name + ".compress");
    } else {
      if (!compress.is_array() || compress.empty() || compress.size() > 2) {
        refuse(name + ".compress", "must be su, [su] or [su, sv], got " + describe(compress));
      }
      out.su = compress_amount(compress[0], name + ".compress[0]");
      if (compress.size() == 2) out.sv = compress_amount(compress[1], name + ".compress[1]");
    }
  }
  out.direction_given = has(options, "direction");
  if (out.direction_given) {
    const std::string where = name + ".direction";
    const Json& direction = object(options["direction"], where);
    one_of(member(direction, "type", where + ".type"), {"global", "constraints"}, where + ".type");
    DirectionSource source = direction_from_json(direction, where);
    if (source.kind == DirectionSource::Kind::Global) {
      out.directions.kind = FlattenDirections::Kind::Global;
      out.directions.global = source.vector;
    } else {
      out.directions.kind = FlattenDirections::Kind::Constraints;
      out.directions.constraints = std::move(source.constraints);
    }
  }
  if (has(options, "baseline")) {
    one_of(options["baseline"], {"uniform"}, name + ".baseline");
    out.method = FlattenMethod::UniformBaseline;
  }
  if (has(options, "patch")) {
    out.use_selection = one_of(options["patch"], {"mesh", "selection"}, name + ".patch") == "selection";
  }
  if (has(options, "maxIterations")) {
    out.max_iterations = iteration_count(options["maxIterations"], name + ".maxIterations");
  }
  if (has(options, "tolerance")) {
    out.tolerance = finite_number(options["tolerance"], name + ".tolerance");
    if (out.tolerance < 0.0) refuse(name + ".tolerance", "must be >= 0, got " + describe(options["tolerance"]));
  }
  if (has(options, "refine")) out.refine = flag(options["refine"], name + ".refine");
  return out;
}

}  // namespace aniso
