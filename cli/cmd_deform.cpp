// `anisoform deform IN OUT [options]`: one anisotropic edit of a mesh, from the
// command line to the core's Session (the browser's, too) and back to a file.
// The edit comes from flags or, with --op FILE, as the public op (op.h); both
// become the same DeformOp, and the Session resolves what the mesh decides
// (the default direction and twist origin, ARAP's handles).
//
// The order of the work follows the exit-status contract: first everything
// the command line alone decides (a mistake there exits 2 before any file is
// read), then the input mesh (exit 3 when it cannot be solved on), then what
// needs both (a region or field naming a vertex that does not exist: exit 2),
// and only then the solve and the output file.
#include <cstdio>
#include <memory>
#include <optional>
#include <utility>

#include "anisoform/deform_request.h"
#include "anisoform/direction_field.h"
#include "anisoform/limits.h"
#include "anisoform/op.h"
#include "anisoform/transforms.h"
#include "cli_common.h"
#include "commands.h"

namespace aniso::cli {

namespace {

// The options exactly as typed; empty means "not given".
struct DeformArguments {
  std::string input;
  std::string output;
  std::string method;
  std::string select = "all";
  std::string falloff;
  std::string direction;
  std::string scale;
  std::string thicken;
  std::string shear;
  std::string rotate;
  std::string twist;
  std::string pin;
  std::string handle;
  std::string move;
  std::string iterations;
  std::string tolerance;
  std::string elements;
  std::string rotations;
  std::string acceleration;
  std::string rotation_coupling;
  std::string op;
  bool ascii = false;
};

// What the command line alone decides, checked before the mesh is read.
struct DeformPlan {
  DeformOp edit;  // pins and handles given as regions are filled in with the mesh
  Region selection;
  double falloff = 0.0;
  std::string direction_description;  // empty: the mesh's longest axis
  std::string field_path;             // --direction field:PATH
  std::optional<Region> pins;
  std::optional<Region> handles;
  WriteOptions write;
};

ArapElements parse_elements(const std::string& text) {
  if (text == "spokes") return ArapElements::Spokes;
  if (text == "spokes-rims") return ArapElements::SpokesAndRims;
  fail(ErrorCode::BadParameter,
       "--elements: '" + text + "' is not one of spokes, spokes-rims");
}

// An option's amounts (`read` sets its fields of a spec), checked by the
// core's rule (validate) on a spec that holds only them, so that an error
// names the option as well as the amount, then set on `spec`.
template <typename Read>
void read_transform_option(const std::string& option, const std::string& text, TransformSpec& spec, Read read) {
  if (text.empty()) return;
  TransformSpec only;
  read(only);
  naming_option(option, [&] { validate(only); });
  read(spec);
}

TransformSpec parse_transform(const DeformArguments& args) {
  TransformSpec spec;
  read_transform_option("--scale", args.scale, spec, [&](TransformSpec& s) { parse_scale(args.scale, s); });
  read_transform_option("--thicken", args.thicken, spec,
                        [&](TransformSpec& s) { s.sn = parse_number(args.thicken, "--thicken"); });
  read_transform_option("--shear", args.shear, spec,
                        [&](TransformSpec& s) { s.shear = parse_number(args.shear, "--shear"); });
  read_transform_option("--rotate", args.rotate, spec, [&](TransformSpec& s) { parse_rotation(args.rotate, s); });
  read_transform_option("--twist", args.twist, spec, [&](TransformSpec& s) { parse_twist(args.twist, s); });
  return spec;
}

// The op flags as (option, value): the ones --op replaces.
std::vector<std::pair<const char*, const std::string*>> op_flags(const DeformArguments& args) {
  return {{"--method", &args.method},       {"--direction", &args.direction}, {"--scale", &args.scale},
          {"--thicken", &args.thicken},     {"--shear", &args.shear},         {"--rotate", &args.rotate},
          {"--twist", &args.twist},         {"--pin", &args.pin},             {"--handle", &args.handle},
          {"--move", &args.move},           {"--iterations", &args.iterations},
          {"--tolerance", &args.tolerance}, {"--elements", &args.elements},
          {"--rotations", &args.rotations}, {"--rotation-coupling", &args.rotation_coupling},
          {"--acceleration", &args.acceleration}};
}

// --op FILE: the public op, parsed by the core (op.h) as the browser's is.
DeformOp edit_from_op_file(const DeformArguments& args) {
  for (const auto& [option, value] : op_flags(args)) {
    if (!value->empty()) {
      fail(ErrorCode::BadParameter, std::string(option) + " cannot be combined with --op: the op file " +
                                        args.op + " gives the whole edit");
    }
  }
  const Json op = json_from_text(read_text_file(args.op, "--op"), "--op: " + args.op);
  return naming_option("--op", [&] { return deform_op_from_json(op); });
}

// The flags as the same DeformOp an op gives.
DeformOp edit_from_flags(const DeformArguments& args, DeformPlan& plan) {
  DeformOp edit;
  DeformRequest& request = edit.request;
  if (!args.method.empty()) request.method = naming_option("--method", [&] { return parse_method(args.method); });
  request.transform = parse_transform(args);
  edit.direction_given = !args.direction.empty();
  if (edit.direction_given) {
    const DirectionFlag choice = parse_direction(args.direction);
    plan.direction_description = choice.description;
    request.direction.kind = choice.kind;
    request.direction.vector = choice.vector;
    if (choice.kind == DirectionSource::Kind::Constraints) {
      plan.field_path = choice.field_path;
      request.direction.constraints = read_direction_field(choice.field_path);
    }
  }
  if (!args.handle.empty() && request.method != Method::Arap) {
    fail(ErrorCode::BadParameter, "--handle: handles are for --method arap (the anisotropic methods need none)");
  }
  if (!args.move.empty()) {
    // Without --handle, the handles are the fully selected vertices (resolve_edit), as for an op's `move`.
    if (request.method != Method::Arap) {
      fail(ErrorCode::BadParameter, "--move: moves ARAP's handles: give --method arap");
    }
    request.handle_offset = parse_vector3(args.move, "--move");
  }
  if (!args.iterations.empty()) {
    const int iterations = parse_integer(args.iterations, "--iterations");
    check_iteration_count(iterations, "--iterations");
    // One count for both: AnARAP iterates to the tolerance (capped), except
    // that the paper's rotation scheme (--rotations steps), which has no fixed
    // point, runs exactly this many steps (DeformRequest::rotation_steps).
    request.max_iterations = iterations;
    request.rotation_steps = iterations;
  }
  if (!args.tolerance.empty()) {
    request.tolerance = parse_number(args.tolerance, "--tolerance");
    if (request.tolerance < 0.0) fail(ErrorCode::BadParameter, "--tolerance: must be >= 0, got " + args.tolerance);
  }
  if (!args.elements.empty()) request.elements = parse_elements(args.elements);
  if (!args.rotations.empty()) request.rotations = rotation_scheme_from_name(args.rotations, "--rotations");
  if (!args.acceleration.empty()) request.acceleration = acceleration_from_name(args.acceleration, "--acceleration");
  if (!args.rotation_coupling.empty()) {
    request.rotation_coupling = parse_number(args.rotation_coupling, "--rotation-coupling");
    validate_rotation_coupling(request.rotation_coupling, "--rotation-coupling");
  }
  return edit;
}

DeformPlan plan_deform(const DeformArguments& args) {
  DeformPlan plan;
  plan.edit = args.op.empty() ? edit_from_flags(args, plan) : edit_from_op_file(args);
  plan.selection = naming_option("--select", [&] { return parse_region(args.select); });
  if (!args.falloff.empty()) {
    plan.falloff = parse_number(args.falloff, "--falloff");
    if (plan.falloff < 0.0) fail(ErrorCode::BadParameter, "--falloff: must be >= 0, got " + args.falloff);
  }
  if (!args.pin.empty()) plan.pins = naming_option("--pin", [&] { return parse_region(args.pin); });
  if (!args.handle.empty()) plan.handles = naming_option("--handle", [&] { return parse_region(args.handle); });
  plan.write.binary = !args.ascii;
  return plan;
}

// Problems the solver works through (METHOD §2: clamped weights), worth telling.
void warn_about_solvable_problems(const MeshReport& report, std::vector<std::string>& warnings) {
  const auto warn_count = [&warnings](int count, const std::string& what) {
    if (count > 0) warnings.push_back(std::to_string(count) + " " + what);
  };
  warn_count(report.degenerate_triangles, "zero-area triangle(s): solved through with clamped weights");
  warn_count(report.duplicate_faces, "duplicate face(s)");
  warn_count(report.non_manifold_edges, "non-manifold edge(s)");
  warn_count(report.non_manifold_vertices, "non-manifold vertex(es)");
  if (!report.consistently_oriented) {
    warn_count(report.count_of(ProblemKind::InconsistentOrientation),
               "face(s) wound against a neighbour (inconsistent orientation)");
  }
  warn_count(report.unreferenced_vertices, "unreferenced vertex(es): left where they are");
}

std::string echo_number(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", value);
  return text;
}

// How an op's direction is echoed (flags echo their text as typed).
std::string op_direction_description(const DirectionSource& source) {
  switch (source.kind) {
    case DirectionSource::Kind::Global:
      return "global:" + echo_number(source.vector.x()) + "," + echo_number(source.vector.y()) + "," +
             echo_number(source.vector.z());
    case DirectionSource::Kind::CurvatureMin: return "curvature:min";
    case DirectionSource::Kind::CurvatureMax: return "curvature:max";
    case DirectionSource::Kind::Constraints:
      return "field (" + std::to_string(source.constraints.size()) + " constraints)";
    case DirectionSource::Kind::Screen: return "screen";
    case DirectionSource::Kind::Dense: return "dense";
  }
  return "";
}

double max_displacement(const Positions& rest, const Positions& deformed) {
  if (rest.rows() == 0) return 0.0;
  // stableNorm: the squares of a mesh in units of 1e-200 underflow to 0.
  return (deformed - rest).rowwise().stableNorm().maxCoeff();
}

int run_deform(const DeformArguments& args) {
  DeformPlan plan = plan_deform(args);
  check_output_path(args.output);

  Session session;
  const ReadReport read = load_into_session(session, args.input);
  const Mesh& mesh = session.rest();
  const SessionMeshInfo& info = session.info();
  std::vector<std::string> warnings = info.notes;
  warn_about_solvable_problems(info.report, warnings);

  // A field file's vertices against the mesh, named by the file's lines.
  if (!plan.field_path.empty()) {
    naming_option("--direction", [&] {
      validate_direction_constraints(plan.edit.request.direction.constraints, mesh.num_vertices(), plan.field_path);
    });
  }
  naming_option("--select", [&] { session.select(plan.selection, plan.falloff, SelectionMode::Replace); });
  DeformOp& edit = plan.edit;
  if (plan.pins) edit.request.pins = region_vertices(mesh, *plan.pins, "--pin");
  if (plan.handles) edit.request.handles = region_vertices(mesh, *plan.handles, "--handle");
  if (!args.scale.empty() && any_amounts(edit.request.direction.constraints)) {
    warnings.push_back(field_amounts_replace("--scale", args.scale, plan.field_path));
  }
  if (edit.request.method == Method::Arap && !edit.request.transform.is_identity()) {
    warnings.push_back("--method arap is isotropic ARAP with handles: the local transform "
                       "(--scale, --shear, --rotate, --twist, --thicken) is not used");
  }
  // The twist's and the move's ranges depend on the mesh, so the core checks
  // them at the solve; checked here first by the same rules, to name where
  // they came from.
  naming_option(args.op.empty() ? "--twist" : "--op",
                [&] { validate_twist(edit.request.transform, info.report.bbox.diagonal()); });
  naming_option(args.op.empty() ? "--move" : "--op",
                [&] { validate_move(edit.request.handle_offset, info.report.bbox.diagonal()); });
  // What the session will solve, for the counts echoed below.
  const DeformRequest resolved = resolve_edit(edit, mesh.V, info.report.bbox, session.selection());
  const std::string unchanged = unchanged_reason(resolved);
  if (!unchanged.empty()) warnings.push_back(unchanged);
  const DeformOpResult result = session.deform(edit);
  warnings.insert(warnings.end(), result.warnings.begin(), result.warnings.end());
  // As the app's status line: a cut-off solve is not the edit's converged shape.
  if (!result.converged) {
    // At the most --iterations allows, raising it is no advice.
    warnings.push_back(result.iterations >= limits::kMaxIterations
                           ? "stopped at the iteration cap (" + std::to_string(result.iterations) +
                                 ", the most --iterations allows) before the energy settled: a larger "
                                 "--tolerance (the default is " + echo_number(DeformRequest().tolerance) +
                                 ") ends the solve where the energy "
                                 "changes less"
                           : "stopped at the iteration cap (" + std::to_string(result.iterations) +
                                 ") before the energy settled: raise --iterations for a closer result");
  }
  // As the app's warning (edit-wording.js foldOverWarning).
  if (result.inverted > 0) {
    warnings.push_back(std::to_string(result.inverted) +
                       " triangle(s) folded over: reduce the amount or the falloff");
  }

  // An OBJ keeps the input OBJ's texture coordinates, a PLY the input PLY's vertex properties.
  write_mesh(args.output, Mesh{session.positions(), mesh.F}, session.write_options(plan.write.binary));
  print_warnings("deform", warnings);
  std::string direction = plan.direction_description;
  if (direction.empty()) {
    direction = edit.direction_given ? op_direction_description(edit.request.direction)
                                     : longest_axis_description(info.report.bbox);
  }
  print_json({
      {"method", method_name(edit.request.method)},
      {"input", args.input},
      {"output", args.output},
      {"vertices", mesh.num_vertices()},
      {"triangles", mesh.num_triangles()},
      {"selected", result.selected},
      {"direction", direction},
      {"pins", resolved.pins.size()},
      {"handles", resolved.handles.size()},
      {"iterations", result.iterations},
      {"converged", result.converged},
      {"energy", result.energy},
      {"energy_history", result.energy_history},
      {"directions_filled", result.directions_filled},
      {"inverted", result.inverted},
      {"factorizations", result.factorizations},
      {"precompute_ms", result.precompute_ms},
      {"solve_ms", result.solve_ms},
      {"max_displacement", max_displacement(mesh.V, session.positions())},
      {"warnings", warnings},
      {"read", to_json(read)},
  });
  return kExitSuccess;
}

constexpr const char* kDeformHelp =
    "Deform IN with one anisotropic edit and write OUT (format from its extension: .obj .off "
    ".ply .stl). Prints one JSON object: method, vertices, triangles, selected, direction, "
    "pins, handles, iterations, converged, energy, energy_history, directions_filled, "
    "inverted (triangles folded over), factorizations, precompute_ms, solve_ms, max_displacement, warnings, read.\n"
    "REGION forms (--select, --pin, --handle): all | box:X0,Y0,Z0,X1,Y1,Z1 | sphere:X,Y,Z,R | "
    "file:PATH (one vertex index per line, optionally followed by a weight in [0,1]).\n"
    "Mesh repairs: a triangle soup (no shared vertices) is welded by exact position; "
    "zero-area, duplicate, non-manifold and flipped faces are solved through; each is "
    "listed in warnings. Non-finite coordinates or an empty mesh exit 3.";

void add_deform_options(CLI::App& deform, DeformArguments& args) {
  deform.add_option("IN", args.input, "Input mesh (.obj .off .ply .stl)")->required();
  deform.add_option("OUT", args.output,
                    "Output mesh; its extension sets the format (unknown, or no such or no writable directory: exit 2; "
                    "a failed write: exit 3, an existing OUT left unchanged)")
      ->required();
  deform.add_option("--op", args.op,
                    "The edit as the public op, a JSON object (the browser API's and the edit "
                    "document's: method, direction, transform, pins, handles, move, elements, "
                    "maxIterations, rotationSteps, tolerance); replaces the edit's flags (--method "
                    "... --elements), which are refused beside it. --select and --falloff still apply")
      ->type_name("FILE.json");
  deform.add_option("--method", args.method, "anarap | andefgrad | arap | linear (default anarap)")
      ->type_name("NAME");
  deform.add_option("--select", args.select, "Region to edit (default all); see REGION forms")
      ->type_name("REGION");
  deform.add_option("--falloff", args.falloff,
                    "Soft border width around the selection, in model units, measured along "
                    "edges (default 0)")
      ->type_name("D");
  deform.add_option("--direction", args.direction,
                    "global:X,Y,Z | curvature:min | curvature:max | field:PATH (lines \"INDEX DX "
                    "DY DZ [SU [SV]]\": constraints propagated to a smooth line field; amounts in the file "
                    "replace --scale everywhere, and a warning says so when both are given). curvature:min "
                    "is the direction that bends least (along a tube), curvature:max the one that "
                    "bends most, by size, whichever way the faces are wound. Default: "
                    "global along the longest bounding-box axis")
      ->type_name("SOURCE");
  deform.add_option("--scale", args.scale,
                    "Scale SU along the direction and SV across it (default 1,1)")
      ->type_name("SU[,SV]");
  deform.add_option("--thicken", args.thicken,
                    "Scale SN along the normal (default 1; the linear method only: AnARAP and AnDefGrad refuse it)")
      ->type_name("SN");
  deform.add_option("--shear", args.shear, "Shear H of the direction over the cross direction")
      ->type_name("H");
  deform.add_option("--rotate", args.rotate,
                    "Local rotation about the normal (n), the direction (u) or the cross "
                    "direction (v)")
      ->type_name("n|u|v:DEGREES");
  deform.add_option("--twist", args.twist,
                    "Twist about the axis X,Y,Z through the selection's weighted centroid; the "
                    "angle grows from 0 at the selection's lowest point along the axis")
      ->type_name("X,Y,Z:DEGREES_PER_UNIT");
  deform.add_option("--pin", args.pin, "Vertices held at their rest positions")
      ->type_name("REGION");
  deform.add_option("--handle", args.handle,
                    "Vertices moved by --move and held (--method arap; default: the fully selected "
                    "vertices, with the unselected ones pinned unless --pin is given)")
      ->type_name("REGION");
  deform.add_option("--move", args.move, "Offset of the --handle vertices")->type_name("DX,DY,DZ");
  deform.add_option("--iterations", args.iterations,
                    "AnARAP/ARAP iteration cap, >= 1 (default " +
                        std::to_string(aniso::DeformRequest().max_iterations) +
                        "); with --rotations steps and a rotation, twist or shear, the number of steps (default " +
                        std::to_string(aniso::DeformRequest().rotation_steps) + ", as an op's rotationSteps)")
      ->type_name("N");
  deform.add_option("--tolerance", args.tolerance,
                    "Relative energy change that ends the iterations, >= 0 (default 1e-6)")
      ->type_name("T");
  deform.add_option("--elements", args.elements,
                    "AnARAP/ARAP energy elements: spokes (default) | spokes-rims")
      ->type_name("KIND");
  deform.add_option("--rotations", args.rotations,
                    "AnARAP with a rotation, twist or shear: coupled (default: neighbouring rotations "
                    "tied, converges) | steps (the paper's scheme: --iterations steps from the rest pose, default " +
                        std::to_string(aniso::DeformRequest().rotation_steps) + ")")
      ->type_name("SCHEME");
  deform.add_option("--rotation-coupling", args.rotation_coupling,
                    "coupled rotations: how strongly neighbours are tied, 0.0001 to 10000 (default 1)")
      ->type_name("ALPHA");
  deform.add_option("--acceleration", args.acceleration,
                    "AnARAP/ARAP iterations: lbfgs (default: L-BFGS preconditioned by the Laplacian, same "
                    "result in fewer iterations) | anderson (Anderson acceleration) | none (plain local/global)")
      ->type_name("KIND");
  deform.add_flag("--ascii", args.ascii, "Write PLY and STL as text instead of binary");
}

}  // namespace

void register_deform(CLI::App& app, Action& action) {
  auto args = std::make_shared<DeformArguments>();
  CLI::App* deform = app.add_subcommand("deform", kDeformHelp);
  add_deform_options(*deform, *args);
  run_when_chosen(deform, args, action, run_deform);
}

}  // namespace aniso::cli
