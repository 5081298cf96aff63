// `anisoform flatten IN OUT [options]`: a garment pattern from an open patch,
// with the wanted compression built in (or the industry baseline), written as
// OBJ with texture coordinates, SVG or DXF.
//
// The order of the work follows the exit-status contract, as for deform: the
// command line alone first (exit 2), then the input mesh (exit 3: unreadable,
// unsolvable, or closed, since a closed surface has no boundary to flatten
// to), then what needs both (a field naming a vertex outside the patch: exit
// 2), and only then the solve and the output file.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <numeric>
#include <optional>

#include "anisoform/direction_field.h"
#include "anisoform/limits.h"
#include "anisoform/flatten.h"
#include "anisoform/op.h"
#include "anisoform/pattern_export.h"
#include "cli_common.h"
#include "commands.h"

namespace aniso::cli {

namespace {

// The options exactly as typed; empty means "not given".
struct FlattenArguments {
  std::string input;
  std::string output;
  std::string select = "all";
  std::string compress;
  std::string direction;
  std::string baseline;
  std::string mm_per_unit;
  std::string iterations;
  std::string tolerance;
  bool no_refine = false;
};

enum class PatternFormat { Obj, Svg, Dxf };

// What the command line alone decides, checked before the mesh is read.
struct FlattenPlan {
  PatternFormat format = PatternFormat::Obj;
  Region selection;
  SessionFlatten request;            // the Session's request; its options are built by the core
  std::string direction_description; // empty: the mesh's longest axis
  std::string field_path;            // --direction field:PATH
  double mm_per_unit = 1.0;
};

std::string lowercase_extension(const std::string& path) {
  std::string extension = std::filesystem::path(path).extension().string();
  for (char& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return extension;
}

// OUT's format by extension, and a directory to write it in.
PatternFormat check_pattern_output(const std::string& path) {
  const std::string extension = lowercase_extension(path);
  PatternFormat format;
  if (extension == ".obj") {
    format = PatternFormat::Obj;
  } else if (extension == ".svg") {
    format = PatternFormat::Svg;
  } else if (extension == ".dxf") {
    format = PatternFormat::Dxf;
  } else {
    fail(ErrorCode::BadParameter, "OUT: '" + path +
                                      "' has no pattern extension: use .obj (3D with vt), .svg or .dxf");
  }
  check_output_location(path);
  return format;
}

FlattenPlan plan_flatten(const FlattenArguments& args) {
  FlattenPlan plan;
  plan.format = check_pattern_output(args.output);
  plan.selection = naming_option("--select", [&] { return parse_region(args.select); });
  if (!args.compress.empty()) {
    const std::vector<double> amounts = parse_number_list(args.compress, "--compress", 0, {"SU", "SV"});
    if (amounts.empty() || amounts.size() > 2) {
      fail(ErrorCode::BadParameter, "--compress: expected SU or SU,SV, got '" + args.compress + "'");
    }
    plan.request.su = amounts[0];
    if (amounts.size() > 1) plan.request.sv = amounts[1];
    // Their range is the core's rule (validate_scale, limits.h), which
    // flatten() applies too; here the error also names the option.
    naming_option("--compress", [&] {
      validate_scale(plan.request.su, "su");
      validate_scale(plan.request.sv, "sv");
    });
  }
  plan.request.direction_given = !args.direction.empty();
  if (plan.request.direction_given) {
    const DirectionFlag direction = parse_direction(args.direction);
    plan.direction_description = direction.description;
    FlattenDirections& directions = plan.request.directions;
    if (direction.kind == DirectionSource::Kind::Constraints) {
      directions.kind = FlattenDirections::Kind::Constraints;
      plan.field_path = direction.field_path;
      directions.constraints = read_direction_field(direction.field_path);
    } else if (direction.kind == DirectionSource::Kind::Global) {
      directions.global = direction.vector;
    } else {
      fail(ErrorCode::BadParameter,
           "--direction: flatten takes global:X,Y,Z or field:PATH, got '" + args.direction + "'");
    }
  }
  if (!args.baseline.empty()) {
    if (args.baseline != "uniform") {
      fail(ErrorCode::BadParameter, "--baseline: the one baseline is 'uniform', got '" + args.baseline + "'");
    }
    plan.request.method = FlattenMethod::UniformBaseline;
  }
  if (!args.mm_per_unit.empty()) {
    plan.mm_per_unit = parse_number(args.mm_per_unit, "--mm-per-unit");
    // Before the solve, whatever the output (an .obj pattern reports it too):
    // 1e308 was taken for .obj, and refused for .svg and .dxf only after
    // the flattening, without naming the option.
    naming_option("--mm-per-unit", [&] { validate_mm_per_unit(plan.mm_per_unit); });
  }
  if (!args.iterations.empty()) {
    plan.request.max_iterations = parse_integer(args.iterations, "--iterations");
    check_iteration_count(plan.request.max_iterations, "--iterations");
  }
  if (!args.tolerance.empty()) {
    plan.request.tolerance = parse_number(args.tolerance, "--tolerance");
    if (plan.request.tolerance < 0.0) {
      fail(ErrorCode::BadParameter, "--tolerance: must be >= 0, got " + args.tolerance);
    }
  }
  plan.request.refine = !args.no_refine;
  return plan;
}

// Selected vertices as a mask (empty: everything).
std::vector<char> selection_mask(const Mesh& mesh, const Region& region) {
  if (region.kind == Region::Kind::All) return {};
  const Eigen::VectorXd weights = naming_option("--select", [&] { return region_weights(mesh, region); });
  std::vector<char> mask(mesh.num_vertices(), 0);
  for (int i = 0; i < mesh.num_vertices(); ++i) mask[i] = weights[i] > 0.0;
  return mask;
}

// The patch as an OBJ with its pattern as vt, its vertices in the input's
// order (the patch numbers them as its faces meet them): a whole mesh comes
// out numbered as it went in, so the JSON's vertex indices (suggested_cuts)
// name the same vertices in both files; a selection keeps the input's order.
std::string patch_obj_in_input_order(const FlattenPatch& patch, const Eigen::MatrixX2d& uv) {
  const int n = static_cast<int>(patch.input_vertex.size());
  std::vector<int> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int a, int b) { return patch.input_vertex[a] < patch.input_vertex[b]; });
  std::vector<int> rank(n);
  Mesh mesh;
  mesh.V.resize(n, 3);
  Eigen::MatrixX2d sorted_uv(n, 2);
  for (int k = 0; k < n; ++k) {
    rank[order[k]] = k;
    mesh.V.row(k) = patch.mesh.V.row(order[k]);
    sorted_uv.row(k) = uv.row(order[k]);
  }
  mesh.F = patch.mesh.F.unaryExpr([&](int v) { return rank[v]; });
  return write_obj_with_uv(mesh, sorted_uv);
}

// The guessed unit in words, with the size it came from and the option that
// sets it: "the mesh's unit was guessed as cm (10 mm per unit) from its
// largest side, 450 units; give --mm-per-unit if it is in another unit (1
// for mm, 10 for cm, 1000 for m, 25.4 for inches)".
std::string unit_guess_warning(const ModelUnitGuess& guess) {
  char size[32];
  std::snprintf(size, sizeof size, "%g", guess.largest_side);
  char scale[32];
  std::snprintf(scale, sizeof scale, "%g", guess.mm_per_unit);
  return "the mesh's unit was guessed as " + guess.name + " (" + scale + " mm per unit) from its largest side, " +
         size + " units; give --mm-per-unit if it is in another unit (1 for mm, 10 for cm, 1000 for m, 25.4 for "
         "inches)";
}

// A wanted amount: one number, or [min, max] when a field's amounts vary.
nlohmann::json amount_json(double low, double high) {
  return low == high ? nlohmann::json(low) : nlohmann::json::array({low, high});
}

nlohmann::json result_json(const FlattenArguments& args, const FlattenPlan& plan,
                           const std::string& direction, const std::vector<std::string>& warnings,
                           const FlattenResult& result) {
  const FlattenMetrics& m = result.metrics;
  const WantedAmounts wanted = wanted_amounts(plan.request);
  nlohmann::json grainlines = nlohmann::json::array();
  for (const Eigen::Vector2d& g : result.grainline) grainlines.push_back({g.x(), g.y()});
  nlohmann::json suggested_cuts = nlohmann::json::array();
  for (const FlattenRegion& r : m.suggested_cuts) {
    suggested_cuts.push_back({{"vertices", r.vertices},
                              {"vertex", r.vertex},
                              {"centroid", {r.centroid.x(), r.centroid.y(), r.centroid.z()}},
                              {"error_mean", r.error_mean},
                              {"triangles", r.triangles}});
  }
  return {
      {"method", m.method},
      {"input", args.input},
      {"output", args.output},
      {"triangles", m.triangles},
      {"vertices", m.vertices},
      {"components", m.components},
      {"boundary_loops", m.boundary_loops},
      {"flipped", m.flipped},
      {"outline_crossings", m.outline_crossings},
      {"su", amount_json(wanted.su_min, wanted.su_max)},
      {"sv", amount_json(wanted.sv_min, wanted.sv_max)},
      {"amounts", wanted.from_field ? "field" : "compress"},
      {"direction", direction},
      {"compression_error_mean", m.compression_error_mean},
      {"compression_error_max", m.compression_error_max},
      {"cross_error_mean", m.cross_error_mean},
      {"cross_error_max", m.cross_error_max},
      {"area_distortion_mean", m.area_distortion_mean},
      {"shear_degrees_mean", m.shear_degrees_mean},
      {"shear_degrees_max", m.shear_degrees_max},
      {"near_normal_directions", m.near_normal_directions},
      {"iterations", m.iterations},
      {"converged", m.converged},
      {"energy", m.energy},
      {"initialization", m.initialization},
      {"directions_filled", m.filled_directions},
      {"grainline", grainlines},
      {"mm_per_unit", plan.mm_per_unit},
      {"seconds", m.seconds},
      {"suggested_cuts", suggested_cuts},
      {"warnings", warnings},
  };
}

int run_flatten(const FlattenArguments& args) {
  FlattenPlan plan = plan_flatten(args);
  Session session;
  load_into_session(session, args.input);
  // Without --mm-per-unit, the unit the core guesses from the mesh's size, as
  // the app's pattern export takes it (info().unitGuess; guess_model_unit).
  std::string unit_guess;
  std::vector<std::string> warnings = session.info().notes;
  if (args.mm_per_unit.empty()) {
    const ModelUnitGuess guess = guess_model_unit(session.info().report.bbox);
    plan.mm_per_unit = guess.mm_per_unit;
    unit_guess = guess.name;
    // A guess decides the pattern's size in mm: said, as the app shows it
    // beside its export (a 450 mm panel was taken as cm and written 10x too
    // large, a 520 mm one as mm, with no word of it).
    if (plan.format != PatternFormat::Obj) warnings.push_back(unit_guess_warning(guess));
  }
  const Mesh& mesh = session.rest();
  if (session.info().report.unreferenced_vertices > 0) {
    warnings.push_back(std::to_string(session.info().report.unreferenced_vertices) +
                       " unreferenced vertex(es): not part of the pattern");
  }
  if (!args.compress.empty() && any_amounts(plan.request.directions.constraints)) {
    warnings.push_back(field_amounts_replace("--compress", args.compress, plan.field_path));
  }
  // A field file's vertices against the mesh, named by the file's lines.
  if (!plan.field_path.empty()) {
    naming_option("--direction", [&] {
      validate_direction_constraints(plan.request.directions.constraints, mesh.num_vertices(), plan.field_path);
    });
  }
  const std::vector<char> mask = selection_mask(mesh, plan.selection);

  // The one-shot flatten (its patch is written out), with the Session's request rules.
  const SessionFlatten request = resolve_flatten(plan.request, mesh.V, mesh.F);
  const std::string direction =
      plan.direction_description.empty() ? longest_axis_description(shape_bounding_box(mesh)) : plan.direction_description;
  const FlattenOutput flattened = flatten(mesh, mask, flatten_options(request));

  PatternExportOptions pattern_options;
  pattern_options.mm_per_unit = plan.mm_per_unit;
  pattern_options.note = pattern_note(plan.request, direction);
  switch (plan.format) {
    case PatternFormat::Obj:
      write_file_atomically(args.output, patch_obj_in_input_order(flattened.patch, flattened.result.uv));
      break;
    case PatternFormat::Svg:
      write_file_atomically(args.output,
                 write_pattern_svg(make_pattern(flattened.patch, flattened.result), pattern_options));
      break;
    case PatternFormat::Dxf:
      write_file_atomically(args.output,
                 write_pattern_dxf(make_pattern(flattened.patch, flattened.result), pattern_options));
      break;
  }
  const std::string problem = flatten_problem(flattened.result.metrics);
  if (!problem.empty()) warnings.push_back(problem);
  for (const std::string& warning : flatten_warnings(flattened.result.metrics)) warnings.push_back(warning);
  if (plan.format != PatternFormat::Obj) {
    std::string small = pattern_size_warning(make_pattern(flattened.patch, flattened.result), pattern_options);
    if (!small.empty()) {
      small += unit_guess.empty() ? " (--mm-per-unit)" : " (guessed from the mesh's size as " + unit_guess +
                                                              "; give --mm-per-unit)";
      warnings.push_back(small);
    }
  }
  print_warnings("flatten", warnings);
  nlohmann::json result = result_json(args, plan, direction, warnings, flattened.result);
  if (!unit_guess.empty()) result["unit_guess"] = unit_guess;  // mm_per_unit is the guess's
  result["side"] = kPatternSide;
  print_json(result);
  return kExitSuccess;
}

constexpr const char* kFlattenHelp =
    "Flatten an open patch of IN into a garment pattern with the wanted compression built in "
    "(free-boundary anisotropic ARAP, LSCM start) and write OUT: .obj (3D positions, vt = pattern "
    "coordinates in model units, faces v/vt; the patch only, its vertices in the input's order: a whole mesh keeps "
    "its numbering), .svg or .dxf (outlines in mm, "
    "grainline, scale note). Prints one JSON object: method, triangles, vertices, components, "
    "boundary_loops, flipped, outline_crossings (the pattern's outline crossing itself: it overlaps itself), su, sv (the wanted amounts: --compress's, or those of the field file, "
    "which replace them: [min, max] when they vary), amounts (compress | field), direction, "
    "compression_error_mean, compression_error_max "
    "(|achieved along / su - 1| per triangle: area-weighted mean, max), cross_error_mean, "
    "cross_error_max (the same across, with sv), area_distortion_mean, shear_degrees_mean, shear_degrees_max "
    "(how far the images of the direction and its cross direction are off square, degrees: area-weighted "
    "mean, max), near_normal_directions (triangles whose direction is within 10 degrees of their normal), "
    "iterations, converged, "
    "energy, initialization, directions_filled, grainline, mm_per_unit, unit_guess (when guessed), seconds, suggested_cuts "
    "(the regions that miss su or sv by more than 25 %, where a dart or a cut is needed, each at most a tenth of the "
    "patch's area: a larger one is its worst part; each: vertices, "
    "vertex (nearest the centroid), centroid, error_mean of max(|along/su - 1|, |across/sv - 1|), "
    "triangles; the largest connected part first), side (which side of the fabric the pattern shows), warnings.\n"
    "The pattern is the piece seen from the side its faces' normals point to (every face counter-clockwise in "
    "the pattern; the SVG and DXF say so): the same patch wound the other way gives the mirror image. Faces wound "
    "against the rest of their piece are turned over to agree with it, with a warning naming them; a "
    "non-orientable patch (a Moebius strip) exits 3.\n"
    "The patch is the faces whose vertices are all in --select; every component must have a "
    "boundary: a closed mesh or patch exits 3. Several boundary loops and several pieces are "
    "fine (pieces are laid out side by side).";

void add_flatten_options(CLI::App& command, FlattenArguments& args) {
  command.add_option("IN", args.input, "Input mesh (.obj .off .ply .stl)")->required();
  command.add_option("OUT", args.output, "Pattern: .obj, .svg or .dxf (other: exit 2; a failed write: exit 3, an "
                     "existing OUT left unchanged)")->required();
  command.add_option("--select", args.select,
                     "Region to flatten (default all): all | box:X0,Y0,Z0,X1,Y1,Z1 | "
                     "sphere:X,Y,Z,R | file:PATH")
      ->type_name("REGION");
  command.add_option("--compress", args.compress,
                     "Wanted stretch SU along the direction and SV across it (default 1,1; "
                     "0.8 = 20 % shrinkage)")
      ->type_name("SU[,SV]");
  command.add_option("--direction", args.direction,
                     "global:X,Y,Z | field:PATH (lines \"INDEX DX DY DZ [SU [SV]]\": propagated "
                     "over the patch; amounts in the file replace --compress everywhere, and a warning says so when both "
                     "are given). Default: global "
                     "along the longest bounding-box axis")
      ->type_name("SOURCE");
  command.add_option("--baseline", args.baseline,
                     "uniform: the industry baseline (flatten without compression, then scale "
                     "each piece along its mean flattened direction)")
      ->type_name("uniform");
  command.add_option("--mm-per-unit", args.mm_per_unit,
                     "Millimetres per model unit for SVG/DXF, 0.001 to 1000000 (default: guessed from the mesh's "
                     "largest side, as the app does: under 5 m (1000), under 500 cm (10), else mm (1); "
                     "the output's unit_guess says which, and for SVG/DXF a warning)")
      ->type_name("K");
  command.add_option("--iterations", args.iterations,
                     "Iteration cap of the ARAP iterations and the stretch refinement together, >= 1 (default " +
                         std::to_string(aniso::ArapFlattenSettings().max_iterations) + ")")
      ->type_name("N");
  command.add_option("--tolerance", args.tolerance,
                     "Relative energy change that ends the iterations, >= 0 (default 1e-8); the stretch "
                     "refinement also ends where 10 steps together gained less than 3e-4 of its energy")
      ->type_name("T");
  command.add_flag("--no-refine", args.no_refine,
                   "Keep the paper's ARAP result: no stretch refinement of the errors afterwards "
                   "(README, Flattening refinement)");
}

}  // namespace

void register_flatten(CLI::App& app, Action& action) {
  auto args = std::make_shared<FlattenArguments>();
  CLI::App* command = app.add_subcommand("flatten", kFlattenHelp);
  add_flatten_options(*command, *args);
  run_when_chosen(command, args, action, run_flatten);
}

}  // namespace aniso::cli
