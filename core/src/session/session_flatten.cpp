// Session::flatten and Session::export_pattern (session.h, session_flatten.h):
// the Flattener cached per (positions, patch mask), and the result re-indexed
// from the patch's compact numbering to the session's input vertices.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <utility>

#include "anisoform/error.h"
#include "anisoform/op.h"
#include "anisoform/pattern_export.h"
#include "anisoform/session.h"
#include "session/session_flatten_state.h"

namespace aniso {
namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

std::vector<char> patch_mask(const Eigen::VectorXd& weights, bool use_selection) {
  if (!use_selection) return {};  // the Flattener's "everything"
  std::vector<char> mask(static_cast<std::size_t>(weights.size()), 0);
  for (Eigen::Index i = 0; i < weights.size(); ++i) mask[static_cast<std::size_t>(i)] = weights[i] > 0.0;
  return mask;
}

std::string short_number(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", value);
  return text;
}

float relative_error(double achieved, double wanted) {
  const double error = std::abs(achieved / wanted - 1.0);
  return std::isfinite(error) ? static_cast<float>(error) : kNaN;
}

// Per input vertex, the flattening laid out for a host (session_flatten.h).
SessionFlattenResult reindex(const FlattenPatch& patch, const TriangleCharts& charts,
                             const FlattenResult& result, int num_input_vertices) {
  SessionFlattenResult out;
  out.metrics = result.metrics;
  const auto n = static_cast<std::size_t>(num_input_vertices);
  out.uv.assign(2 * n, kNaN);
  for (std::size_t p = 0; p < patch.input_vertex.size(); ++p) {
    const auto i = static_cast<std::size_t>(patch.input_vertex[p]);
    out.uv[2 * i] = static_cast<float>(result.uv(static_cast<Eigen::Index>(p), 0));
    out.uv[2 * i + 1] = static_cast<float>(result.uv(static_cast<Eigen::Index>(p), 1));
  }

  const Triangles& F = patch.mesh.F;
  const auto num_triangles = static_cast<std::size_t>(F.rows());
  out.triangles.resize(3 * num_triangles);
  out.compression_error.assign(num_triangles, kNaN);
  out.cross_error.assign(num_triangles, kNaN);
  std::vector<double> error_sum(n, 0.0), area_sum(n, 0.0);
  for (Eigen::Index t = 0; t < F.rows(); ++t) {
    const auto ut = static_cast<std::size_t>(t);
    for (int k = 0; k < 3; ++k) {
      out.triangles[3 * ut + k] = static_cast<std::uint32_t>(patch.input_vertex[F(t, k)]);
    }
    if (result.stretch.degenerate[ut]) continue;
    out.compression_error[ut] = relative_error(result.stretch.along[t], result.targets.su[t]);
    out.cross_error[ut] = relative_error(result.stretch.across[t], result.targets.sv[t]);
    if (std::isnan(out.compression_error[ut])) continue;
    for (int k = 0; k < 3; ++k) {
      const std::size_t i = out.triangles[3 * ut + k];
      error_sum[i] += charts.area[t] * out.compression_error[ut];
      area_sum[i] += charts.area[t];
    }
  }
  out.vertex_error.assign(n, kNaN);
  for (std::size_t i = 0; i < n; ++i) {
    if (area_sum[i] > 0.0) out.vertex_error[i] = static_cast<float>(error_sum[i] / area_sum[i]);
  }

  out.grainlines = result.grainline;
  for (const std::vector<int>& loop : patch.boundary_loops) {
    std::vector<std::uint32_t> outline;
    outline.reserve(loop.size());
    for (int p : loop) outline.push_back(static_cast<std::uint32_t>(patch.input_vertex[p]));
    out.outlines.push_back(std::move(outline));
  }
  out.outline_pieces = patch.loop_component;
  return out;
}

}  // namespace

SessionFlattenResult Session::flatten(const SessionFlatten& given) {
  SessionFlattenResult result;
  retrying_out_of_memory([&] { result = flatten_once(given); });
  return result;
}

SessionFlattenResult Session::flatten_once(const SessionFlatten& given) {
  require_mesh();
  const SessionFlatten request = resolve_flatten(given, current_, rest().F);
  SessionFlattenState& state = *flatten_;
  std::vector<char> mask = patch_mask(weights_, request.use_selection);

  // A new Flattener only when the patch changed (the positions' changes have
  // already dropped the old one). Built aside, so that a refused patch
  // (closed, empty) leaves the previous one and its result in place.
  std::unique_ptr<Flattener> built;
  if (!state.flattener || state.mask != mask) {
    built = std::make_unique<Flattener>(Mesh{current_, deformer_->rest().F}, mask);
  }
  Flattener& flattener = built ? *built : *state.flattener;

  FlattenOptions options = flatten_options(request);
  if (progress_) {
    options.progress = [this](double fraction) {
      report(ProgressStage::Flatten, fraction);
      return true;
    };
  }
  FlattenResult result = flattener.flatten(options);
  report(ProgressStage::Flatten, 1.0);
  SessionFlattenResult out =
      reindex(flattener.patch(), flattener.charts(), result, deformer_->rest().num_vertices());

  std::string note = pattern_note(request, describe_directions(request.directions));
  // Nothing below throws or allocates: moves only.
  if (built) {
    if (state.flattener) state.retired_factorizations += state.flattener->factorizations();
    state.flattener = std::move(built);
    state.mask = std::move(mask);
  }
  state.last = std::move(result);
  state.note = std::move(note);
  out.factorizations = factorizations();
  return out;
}

std::string Session::export_pattern(const std::string& format, double mm_per_unit) const {
  require_mesh();
  if (format != "svg" && format != "dxf") {
    fail(ErrorCode::BadParameter, "pattern format must be svg or dxf, got '" + format + "'");
  }
  const SessionFlattenState& state = *flatten_;
  if (!state.last || !state.flattener) {
    fail(ErrorCode::BadParameter,
         "flatten first: there is no flattening of the current positions to export");
  }
  PatternExportOptions options;
  options.mm_per_unit = mm_per_unit;
  options.note = state.note;
  const Pattern pattern = make_pattern(state.flattener->patch(), *state.last);
  return format == "svg" ? write_pattern_svg(pattern, options) : write_pattern_dxf(pattern, options);
}

std::string describe_directions(const FlattenDirections& directions) {
  if (directions.kind == FlattenDirections::Kind::Global) {
    return "global:" + short_number(directions.global.x()) + "," + short_number(directions.global.y()) + "," +
           short_number(directions.global.z());
  }
  return "field (" + std::to_string(directions.constraints.size()) + " constraints)";
}

WantedAmounts wanted_amounts(const SessionFlatten& request) {
  WantedAmounts out{request.su, request.su, request.sv, request.sv, false};
  if (request.directions.kind != FlattenDirections::Kind::Constraints) return out;
  for (const DirectionConstraint& c : request.directions.constraints) {
    if (!c.has_amounts) continue;
    if (!out.from_field) out = {c.su, c.su, c.sv, c.sv, true};
    out.su_min = std::min(out.su_min, c.su);
    out.su_max = std::max(out.su_max, c.su);
    out.sv_min = std::min(out.sv_min, c.sv);
    out.sv_max = std::max(out.sv_max, c.sv);
  }
  return out;
}

namespace {

std::string amount_range(double low, double high) {
  return low == high ? short_number(low) : short_number(low) + "-" + short_number(high);
}

}  // namespace

std::string pattern_note(const SessionFlatten& request, const std::string& direction) {
  std::string note = request.method == FlattenMethod::UniformBaseline ? "uniform baseline" : "anisotropic";
  const WantedAmounts wanted = wanted_amounts(request);
  note += ", su " + amount_range(wanted.su_min, wanted.su_max) + " sv " + amount_range(wanted.sv_min, wanted.sv_max);
  if (wanted.from_field) note += " (the field's)";
  return note + ", direction " + direction + "; grainline = mean compression direction";
}

}  // namespace aniso
