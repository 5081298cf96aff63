// `anisoform deform IN OUT [options]`: one anisotropic edit of a mesh, from the
// command line to the core's Deformer and back to a file.
//
// The order of the work follows the exit-status contract: first everything
// the command line alone decides (a mistake there exits 2 before any file is
// read), then the input mesh (exit 3 when it cannot be solved on), then what
// needs both (a region or field naming a vertex that does not exist: exit 2),
// and only then the solve and the output file.
#include <memory>
#include <optional>
#include <utility>

#include "anisoform/direction_field.h"
#include "cli_common.h"
#include "commands.h"

namespace aniso::cli {

namespace {

// The options exactly as typed; empty means "not given".
struct DeformArguments {
  std::string input;
  std::string output;
  std::string method = "anarap";
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
  bool ascii = false;
};

// What the command line alone decides, checked before the mesh is read.
struct DeformPlan {
  Method method = Method::AnArap;
  TransformSpec transform;
  Region selection;
  double falloff = 0.0;
  std::optional<DirectionChoice> direction;  // none: the mesh's longest axis
  std::vector<DirectionConstraint> field_constraints;
  std::optional<Region> pins;
  std::optional<Region> handles;
  Eigen::Vector3d handle_offset = Eigen::Vector3d::Zero();
  std::optional<int> iterations;  // --iterations: the cap, and the steps of a rotation
  double tolerance = DeformRequest().tolerance;
  ArapElements elements = ArapElements::Spokes;
  WriteOptions write;
};

ArapElements parse_elements(const std::string& text) {
  if (text == "spokes") return ArapElements::Spokes;
  if (text == "spokes-rims") return ArapElements::SpokesAndRims;
  fail(ErrorCode::BadParameter,
       "--elements: '" + text + "' is not one of spokes, spokes-rims");
}

TransformSpec parse_transform(const DeformArguments& args) {
  TransformSpec spec;
  if (!args.scale.empty()) parse_scale(args.scale, spec);
  if (!args.thicken.empty()) spec.sn = parse_number(args.thicken, "--thicken");
  if (!args.shear.empty()) spec.shear = parse_number(args.shear, "--shear");
  if (!args.rotate.empty()) parse_rotation(args.rotate, spec);
  if (!args.twist.empty()) parse_twist(args.twist, spec);
  validate(spec);  // non-positive scales and the like, named by the core
  return spec;
}

DeformPlan plan_deform(const DeformArguments& args) {
  DeformPlan plan;
  plan.method = naming_option("--method", [&] { return parse_method(args.method); });
  plan.transform = parse_transform(args);
  plan.selection = naming_option("--select", [&] { return parse_region(args.select); });
  if (!args.falloff.empty()) {
    plan.falloff = parse_number(args.falloff, "--falloff");
    if (plan.falloff < 0.0) fail(ErrorCode::BadParameter, "--falloff: must be >= 0, got " + args.falloff);
  }
  if (!args.direction.empty()) {
    plan.direction = parse_direction(args.direction);
    if (plan.direction->kind == DirectionSource::Kind::Constraints) {
      const std::string& path = plan.direction->field_path;
      plan.field_constraints = naming_option("--direction", [&] {
        return parse_direction_constraints(read_text_file(path, "--direction"), path);
      });
    }
  }
  if (!args.pin.empty()) plan.pins = naming_option("--pin", [&] { return parse_region(args.pin); });
  if (!args.handle.empty()) {
    if (plan.method != Method::Arap) {
      fail(ErrorCode::BadParameter,
           "--handle: handles are for --method arap (the anisotropic methods need none)");
    }
    plan.handles = naming_option("--handle", [&] { return parse_region(args.handle); });
  }
  if (!args.move.empty()) {
    if (!plan.handles) fail(ErrorCode::BadParameter, "--move: needs --handle (the vertices to move)");
    plan.handle_offset = parse_vector3(args.move, "--move");
  }
  if (!args.iterations.empty()) {
    plan.iterations = parse_integer(args.iterations, "--iterations");
    if (*plan.iterations < 1) {
      fail(ErrorCode::BadParameter, "--iterations: must be at least 1, got " + args.iterations);
    }
  }
  if (!args.tolerance.empty()) {
    plan.tolerance = parse_number(args.tolerance, "--tolerance");
    if (plan.tolerance < 0.0) {
      fail(ErrorCode::BadParameter, "--tolerance: must be >= 0, got " + args.tolerance);
    }
  }
  if (!args.elements.empty()) plan.elements = parse_elements(args.elements);
  plan.write.binary = !args.ascii;
  return plan;
}

// The input mesh, made ready for the solver, and what was done to it.
struct PreparedMesh {
  Mesh mesh;
  ReadReport read;
  std::vector<std::string> warnings;
};

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
    int flipped = 0;
    for (const Problem& problem : report.problems) {
      if (problem.kind == ProblemKind::InconsistentOrientation) ++flipped;
    }
    warn_count(flipped, "face(s) wound against a neighbour (inconsistent orientation)");
  }
  warn_count(report.unreferenced_vertices, "unreferenced vertex(es): left where they are");
}

PreparedMesh prepare_mesh(const std::string& path) {
  ReadResult read = read_input_mesh(path);
  PreparedMesh prepared{std::move(read.mesh), std::move(read.report), {}};
  weld_if_soup(prepared.mesh, prepared.warnings);
  const MeshReport report = check_mesh(prepared.mesh);
  if (!report.solvable()) {
    fail(ErrorCode::BadMesh, path + ": cannot deform this mesh: " + report.blocking_summary());
  }
  warn_about_solvable_problems(report, prepared.warnings);
  return prepared;
}

DirectionSource direction_source(const DirectionChoice& choice,
                                 const std::vector<DirectionConstraint>& constraints) {
  DirectionSource source;
  source.kind = choice.kind;
  source.vector = choice.vector;
  source.constraints = constraints;
  return source;
}

struct BuiltRequest {
  DeformRequest request;
  std::string direction_description;
};

BuiltRequest build_request(const DeformPlan& plan, const Mesh& mesh,
                           std::vector<std::string>& warnings) {
  BuiltRequest built;
  DeformRequest& request = built.request;
  request.method = plan.method;
  request.selection = naming_option(
      "--select", [&] { return selection_weights(mesh, plan.selection, plan.falloff); });
  if (!(request.selection.array() > 0.0).any()) {
    warnings.push_back("the selection holds no vertex: the mesh is left unchanged");
  }
  const DirectionChoice direction =
      plan.direction ? *plan.direction : longest_axis_direction(mesh);
  request.direction = direction_source(direction, plan.field_constraints);
  built.direction_description = direction.description;
  request.transform = plan.transform;
  if (request.transform.twist) {
    request.transform.twist_origin = default_twist_origin(mesh.V, request.selection, request.transform.twist_axis);
  }
  if (plan.method == Method::Arap && !plan.transform.is_identity()) {
    warnings.push_back("--method arap is isotropic ARAP with handles: the local transform "
                       "(--scale, --shear, --rotate, --twist, --thicken) is not used");
  }
  if (plan.pins) request.pins = region_vertices(mesh, *plan.pins, "--pin");
  if (plan.handles) request.handles = region_vertices(mesh, *plan.handles, "--handle");
  request.handle_offset = plan.handle_offset;
  request.elements = plan.elements;
  if (plan.iterations) {
    // One count for both: AnARAP iterates to the tolerance (capped) unless T
    // has a rotational part, which has no fixed point and runs exactly this
    // many steps instead (DeformRequest::rotation_steps).
    request.max_iterations = *plan.iterations;
    request.rotation_steps = *plan.iterations;
  }
  request.tolerance = plan.tolerance;
  return built;
}

double max_displacement(const Positions& rest, const Positions& deformed) {
  if (rest.rows() == 0) return 0.0;
  return (deformed - rest).rowwise().norm().maxCoeff();
}

Json result_json(const DeformArguments& args, const PreparedMesh& prepared,
                           const BuiltRequest& built, const DeformResult& result) {
  return {
      {"method", method_name(result.method)},
      {"input", args.input},
      {"output", args.output},
      {"vertices", prepared.mesh.num_vertices()},
      {"triangles", prepared.mesh.num_triangles()},
      {"selected", result.selected},
      {"direction", built.direction_description},
      {"pins", built.request.pins.size()},
      {"handles", built.request.handles.size()},
      {"iterations", result.iterations},
      {"converged", result.converged},
      {"energy", result.energy},
      {"energy_history", result.energy_history},
      {"directions_filled", result.directions_filled},
      {"inverted", result.inverted},
      {"factorizations", result.factorizations},
      {"precompute_ms", result.precompute_ms},
      {"solve_ms", result.solve_ms},
      {"max_displacement", max_displacement(prepared.mesh.V, result.V)},
      {"warnings", prepared.warnings},
      {"read", to_json(prepared.read)},
  };
}

int run_deform(const DeformArguments& args) {
  const DeformPlan plan = plan_deform(args);
  check_output_path(args.output);

  PreparedMesh prepared = prepare_mesh(args.input);
  const BuiltRequest built = build_request(plan, prepared.mesh, prepared.warnings);

  Deformer deformer(prepared.mesh);
  const DeformResult result = deformer.deform(built.request);

  write_mesh(args.output, Mesh{result.V, prepared.mesh.F}, plan.write);
  print_json(result_json(args, prepared, built, result));
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
                    "Output mesh; its extension sets the format (unknown, or no such directory: exit 2; "
                    "a failed write: exit 3, an existing OUT left unchanged)")
      ->required();
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
                    "DY DZ [SU [SV]]\": constraints propagated to a smooth line field). Default: "
                    "global along the longest bounding-box axis")
      ->type_name("SOURCE");
  deform.add_option("--scale", args.scale,
                    "Scale SU along the direction and SV across it (default 1,1)")
      ->type_name("SU[,SV]");
  deform.add_option("--thicken", args.thicken, "Scale SN along the normal (default 1)")
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
  deform.add_option("--handle", args.handle, "Vertices moved by --move and held (--method arap)")
      ->type_name("REGION");
  deform.add_option("--move", args.move, "Offset of the --handle vertices")->type_name("DX,DY,DZ");
  deform.add_option("--iterations", args.iterations,
                    "AnARAP/ARAP iteration cap, >= 1 (default 50); with a rotation, twist or "
                    "shear (AnARAP), the number of steps (default 1)")
      ->type_name("N");
  deform.add_option("--tolerance", args.tolerance,
                    "Relative energy change that ends the iterations, >= 0 (default 1e-6)")
      ->type_name("T");
  deform.add_option("--elements", args.elements,
                    "AnARAP/ARAP energy elements: spokes (default) | spokes-rims")
      ->type_name("KIND");
  deform.add_flag("--ascii", args.ascii, "Write PLY and STL as text instead of binary");
}

}  // namespace

void register_deform(CLI::App& app, Action& action) {
  auto args = std::make_shared<DeformArguments>();
  CLI::App* deform = app.add_subcommand("deform", kDeformHelp);
  add_deform_options(*deform, *args);
  deform->callback([args, deform, &action] {
    action = [args, deform] {
      return run_reporting_errors("deform", [&] {
        refuse_empty_values(*deform);
        return run_deform(*args);
      });
    };
  });
}

}  // namespace aniso::cli
