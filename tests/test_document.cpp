// The edit document (document.h): ops round-trip through JSON exactly, replay
// is deterministic (bitwise), a disabled op is skipped, every bad document is
// refused naming the op or field and leaves the session as it was, and the
// CLI's `replay` writes the positions the core computes, digit for digit.
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>

#include <catch2/catch.hpp>

#include "anisoform/document.h"
#include "anisoform/mesh_io.h"
#include "anisoform/op.h"
#include "anisoform/session.h"
#include "test_support.h"

namespace {

using namespace aniso;

void load_spool(Session& session) {
  const std::string bytes = test::slurp(test::mesh_path("closed/spool.off"));
  REQUIRE_FALSE(bytes.empty());
  session.load_mesh(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size(), "spool.off");
}

// Three ops on the spool: stretch the top along y, twist the middle, thicken
// everything (a disabled-able last op).
Json spool_document(const Session& session) {
  Json document = Json::parse(R"({
    "format": "anisoform-document", "version": 1,
    "mesh": {"name": "spool.off"},
    "regions": [
      {"name": "top", "steps": [{"region": {"box": {"min": [-1, 0.2, -1], "max": [1, 1, 1]}}, "falloff": 0.1}]},
      {"name": "middle", "steps": [{"region": {"sphere": {"center": [0, 0, 0], "radius": 0.35}}},
                                   {"region": {"sphere": {"center": [0, 0.1, 0], "radius": 0.1}}, "mode": "subtract"}]},
      {"name": "everything", "steps": [{"region": {"all": true}}]}],
    "ops": [
      {"id": "stretch", "label": "Stretch the top", "enabled": true, "region": "top",
       "op": {"direction": {"type": "global", "vector": [0, 1, 0]}, "transform": {"scale": 1.3}}},
      {"id": "twist", "label": "Twist the middle", "enabled": true, "region": "middle",
       "op": {"transform": {"twist": {"axis": [0, 1, 0], "degreesPerUnit": 40}}, "rotationSteps": 2}},
      {"id": "thicken", "label": "Thicken", "enabled": true, "region": "everything",
       "op": {"method": "andefgrad", "transform": {"scale": [1, 1.2]}}}]})");
  document["mesh"]["vertices"] = session.rest().num_vertices();
  document["mesh"]["triangles"] = session.rest().num_triangles();
  document["mesh"]["hash"] = mesh_hash_text(session.mesh_hash());
  return document;
}

Positions replayed_spool(const Json& document) {
  Session session;
  load_spool(session);
  replay_document(session, document_from_json(document));
  return session.positions();
}

bool positions_bitwise_equal(const Positions& a, const Positions& b) {
  return a.rows() == b.rows() &&
         std::memcmp(a.data(), b.data(), sizeof(double) * static_cast<std::size_t>(a.size())) == 0;
}

// The refusal a bad document gets, with the session's positions (an edit in
// progress included) checked unchanged.
std::string refusal_of_document(const Json& document, ErrorCode code) {
  Session session;
  load_spool(session);
  session.select(Region{}, 0.0, SelectionMode::Replace);
  DeformOp edit;
  edit.request.transform.su = 1.1;
  session.deform(edit);  // an uncommitted edit: current != rest
  const Positions rest = session.rest().V;
  const Positions current = session.positions();
  const Eigen::VectorXd selection = session.selection();
  const std::string message = test::error_message_of(
      [&] { replay_document(session, document_from_json(document)); }, code);
  CHECK(positions_bitwise_equal(session.rest().V, rest));
  CHECK(positions_bitwise_equal(session.positions(), current));
  CHECK(session.selection() == selection);
  return message;
}

// to_json(parse(text)) read back gives the same JSON: every value and every
// "given" flag survives.
void check_op_round_trip(const Json& op) {
  const DeformOp parsed = deform_op_from_json(op);
  const Json written = to_json(parsed);
  const DeformOp again = deform_op_from_json(written);
  CHECK(to_json(again) == written);
  CHECK(again.direction_given == parsed.direction_given);
  CHECK(again.request.handles == parsed.request.handles);
  CHECK(again.request.pins == parsed.request.pins);
  CHECK(again.twist_origin_given == parsed.twist_origin_given);
  CHECK(again.preview == parsed.preview);
  CHECK(again.request.transform.su == parsed.request.transform.su);
  CHECK(again.request.transform.twist_origin == parsed.request.transform.twist_origin);
  CHECK(again.request.direction.vector == parsed.request.direction.vector);
}

// Selects op's region by hand, step by step, as the replay does.
void select_op_region(Session& session, const EditDocument& document, const DocumentOp& op) {
  session.set_selection(std::vector<float>(static_cast<std::size_t>(session.rest().num_vertices()), 0.0f));
  for (const DocumentRegion& region : document.regions) {
    if (region.name != op.region) continue;
    for (const DocumentSelectStep& step : region.steps) session.select(step.region, step.falloff, step.mode);
  }
}

}  // namespace

TEST_CASE("document: an op round-trips through to_json", "[document]") {
  check_op_round_trip(Json::object());
  check_op_round_trip(Json::parse(R"({"method":"anarap","direction":{"type":"global","vector":[0.1,0.7,-0.3]},
      "transform":{"scale":[1.3,0.9],"thickness":1.1,"shear":0.2,"rotate":{"axis":"u","degrees":12.5},
      "twist":{"axis":[0,0,2],"degreesPerUnit":33.3,"origin":[0.1,0.2,0.3]}},
      "maxIterations":7,"rotationSteps":3,"tolerance":1e-9,"preview":true,"warmStart":false})"));
  check_op_round_trip(Json::parse(R"({"method":"arap","handles":[1,2,3],"pins":[4,5],"move":[0,0.25,0],
      "elements":"spokes-rims"})"));
  check_op_round_trip(Json::parse(R"({"direction":{"type":"curvature","which":"max","smoothing":3}})"));
  check_op_round_trip(Json::parse(R"({"direction":{"type":"constraints","constraints":[
      {"vertex":3,"direction":[1,0,0],"su":1.5,"sv":1},{"vertex":9,"direction":[0,1,0]}]}})"));
  check_op_round_trip(Json::parse(R"({"direction":{"type":"dense","directions":[1,0,0,0,1,0]}})"));
  check_op_round_trip(Json::parse(R"({"direction":{"type":"screen","from":[10,20],"to":[40,25],
      "camera":{"view":[1,0,0,0,0,1,0,0,0,0,1,0,0,0,-3,1],"projection":[1,0,0,0,0,1,0,0,0,0,-1,-1,0,0,-0.2,0],
      "viewport":[0,0,800,600],"anchor":[0,0,0]}}})"));
}

namespace {

// The spool document and its replay, computed once for the test case below:
// Catch2 runs a test case's body again for every section, and the three full
// solves of a replay are what the sections share.
struct SpoolReplay {
  Positions loaded;
  Json document;
  Positions first;
};

const SpoolReplay& spool_replay_once() {
  static const SpoolReplay replay = [] {
    Session session;
    load_spool(session);
    SpoolReplay out;
    out.loaded = session.loaded_positions();
    out.document = spool_document(session);
    out.first = replayed_spool(out.document);
    return out;
  }();
  return replay;
}

}  // namespace

TEST_CASE("document: replay is deterministic and runs every enabled op", "[document]") {
  const Json& document = spool_replay_once().document;
  const Positions& first = spool_replay_once().first;
  const EditDocument parsed = document_from_json(document);

  SECTION("a second replay gives the same bits, and the ops moved the mesh") {
    CHECK(positions_bitwise_equal(replayed_spool(document), first));
    CHECK((first - spool_replay_once().loaded).cwiseAbs().maxCoeff() > 0.05);
  }
  SECTION("the same ops by hand, through the Session (cold full solves and commits), give the same bits") {
    Session by_hand;
    load_spool(by_hand);
    for (const DocumentOp& op : parsed.ops) {
      select_op_region(by_hand, parsed, op);
      DeformOp edit = op.edit;
      edit.request.warm_start = false;
      by_hand.deform(edit);
      by_hand.commit();
    }
    CHECK(positions_bitwise_equal(by_hand.positions(), first));
  }
  SECTION("committing each op after live previews of it reuses their factorization, with the same bits") {
    // What the app does: a drag or a slider previews the op on the session
    // (warm-started, scale steps kept), then the commit replays it.
    Session live;
    load_spool(live);
    int factorized = 0;  // through the progress reports: a replay's scratch work reports there too
    live.set_progress([&factorized](ProgressStage stage, double fraction) {
      if (stage == ProgressStage::Factorize && fraction == kSetupFactorizedShare) ++factorized;  // one's end
    });
    for (std::size_t i = 0; i < parsed.ops.size(); ++i) {
      select_op_region(live, parsed, parsed.ops[i]);
      for (const double amount : {0.5, 0.8, 1.0}) {
        DeformOp edit = parsed.ops[i].edit;
        edit.preview = true;
        edit.request.transform.su = 1.0 + amount * (edit.request.transform.su - 1.0);
        edit.request.transform.twist_degrees_per_unit *= amount;
        live.deform(edit);
      }
      CHECK(factorized > 0);
      factorized = 0;
      replay_document(live, parsed, {i, i + 1});
      CHECK(factorized == 0);
    }
    CHECK(positions_bitwise_equal(live.positions(), first));
  }
  SECTION("a disabled op is skipped") {
    Json without_last = document;
    without_last["ops"].erase(2);
    Json toggled = document;
    toggled["ops"][2]["enabled"] = false;
    const Positions skipped = replayed_spool(toggled);
    CHECK(positions_bitwise_equal(skipped, replayed_spool(without_last)));
    CHECK_FALSE(positions_bitwise_equal(skipped, first));
  }
  SECTION("a range replays from the session's rest pose") {
    Session stepwise;
    load_spool(stepwise);
    const EditDocument doc = document_from_json(document);
    replay_document(stepwise, doc, {0, 1});
    replay_document(stepwise, doc, {1, 3});
    CHECK(positions_bitwise_equal(stepwise.positions(), first));
  }
  SECTION("a preview replay runs each op as a cold live preview") {
    Session previewing;
    load_spool(previewing);
    const ReplaySummary summary = replay_document(previewing, parsed, {0, parsed.ops.size(), /*preview=*/true});
    CHECK(summary.last.iterations <= kPreviewIterations);
    Session preview_by_hand;
    load_spool(preview_by_hand);
    for (const DocumentOp& op : parsed.ops) {
      select_op_region(preview_by_hand, parsed, op);
      DeformOp edit = op.edit;
      edit.preview = true;
      edit.request.warm_start = false;
      preview_by_hand.deform(edit);
      preview_by_hand.commit();
    }
    CHECK(positions_bitwise_equal(previewing.positions(), preview_by_hand.positions()));
    CHECK_FALSE(positions_bitwise_equal(previewing.positions(), first));
  }
  SECTION("the op's region is selected on the rest pose") {
    Session selecting;
    load_spool(selecting);
    const int selected = select_document_region(selecting, document_from_json(document), "thicken");
    CHECK(selected == selecting.rest().num_vertices());
  }
}

TEST_CASE("document: a resolved screen drag replays as the solve it stands for", "[document]") {
  Session session;
  load_spool(session);
  Region cap;
  cap.kind = Region::Kind::Sphere;
  cap.center = Eigen::Vector3d(0, 0.4, 0);
  cap.radius = 0.3;
  session.select(cap, 0.05, SelectionMode::Replace);
  const DeformOp edit = deform_op_from_json(Json::parse(R"({"direction":{"type":"screen","from":[400,300],
      "to":[400,200],"camera":{"view":[1,0,0,0,0,1,0,0,0,0,1,0,0,0,-3,1],
      "projection":[1.3,0,0,0,0,1.7,0,0,0,0,-1.002,-1,0,0,-0.2,0],"viewport":[0,0,800,600],"anchor":[0,0.4,0]}},
      "transform":{"scale":1.25,"twist":{"axis":[0,1,0],"degreesPerUnit":20}},"warmStart":false})"));
  const DeformOp resolved = resolve_for_document(session, edit);
  CHECK(resolved.request.direction.kind == DirectionSource::Kind::Global);
  CHECK_FALSE(resolved.twist_origin_given);  // the region's, worked out again by replay
  CHECK_FALSE(resolved.preview);
  const Json op = to_json(resolved);
  CHECK(op["direction"]["type"] == "global");
  CHECK_FALSE(op.contains("pins"));  // none given: an empty list means "not given" (op.h)

  session.deform(edit);
  const Positions solved = session.positions();

  Session replaying;
  load_spool(replaying);
  Json document = Json::parse(R"({"format": "anisoform-document", "version": 1,
      "mesh": {"name": "spool.off", "vertices": 649, "triangles": 1294},
      "regions": [{"name": "cap", "steps": [{"region": {"sphere": {"center": [0, 0.4, 0], "radius": 0.3}},
                                              "falloff": 0.05}]}],
      "ops": [{"id": "a", "label": "drag", "region": "cap"}]})");
  document["mesh"]["hash"] = mesh_hash_text(replaying.mesh_hash());
  document["ops"][0]["op"] = op;
  replay_document(replaying, document_from_json(document));
  // The twist axis is normalised once more on the way back in, so the
  // replay may differ from the live solve in the last bits only.
  CHECK((replaying.positions() - solved).cwiseAbs().maxCoeff() < 1e-12);
}

TEST_CASE("document: a bad document is refused naming the field, the session unchanged", "[document]") {
  Session session;
  load_spool(session);
  const Json good = spool_document(session);

  Json version = good;
  version["version"] = 2;
  CHECK_THAT(refusal_of_document(version, ErrorCode::BadParameter),
             Catch::Contains("document.version is 2, which this build does not read (it reads version 1)"));

  Json format = good;
  format["format"] = "glb";
  CHECK_THAT(refusal_of_document(format, ErrorCode::BadParameter), Catch::Contains("document.format"));

  Json missing_region = good;
  missing_region["ops"][1]["region"] = "handle";
  CHECK_THAT(refusal_of_document(missing_region, ErrorCode::BadParameter),
             Catch::Contains("document.ops[1] (id 'twist').region names region 'handle', which the document's "
                             "regions do not hold"));

  Json out_of_range = good;
  out_of_range["ops"][0]["op"]["transform"]["scale"] = -2;
  CHECK_THAT(refusal_of_document(out_of_range, ErrorCode::BadParameter),
             Catch::StartsWith("document.ops[0] (id 'stretch').op.transform"));

  Json twist_too_far = good;
  twist_too_far["ops"][1]["op"]["transform"]["twist"]["degreesPerUnit"] = 1e6;
  CHECK_THAT(refusal_of_document(twist_too_far, ErrorCode::BadParameter),
             Catch::StartsWith("document.ops[1] (id 'twist')"));

  Json vertex_beyond = good;
  vertex_beyond["regions"][2]["steps"][0]["region"] = Json::parse(R"({"vertices": [1, 5000]})");
  CHECK_THAT(refusal_of_document(vertex_beyond, ErrorCode::BadParameter),
             Catch::StartsWith("document.regions[2] (name 'everything').steps[0].region"));

  Json other_mesh = good;
  other_mesh["mesh"]["hash"] = "fnv1a64:0123456789abcdef";
  CHECK_THAT(refusal_of_document(other_mesh, ErrorCode::BadMesh),
             Catch::Contains("document mesh hash fnv1a64:0123456789abcdef ('spool.off', 649 vertices, 1294 "
                             "triangles) does not match the loaded mesh fnv1a64:"));
  CHECK_THAT(refusal_of_document(other_mesh, ErrorCode::BadMesh),
             Catch::EndsWith("triangles): saved edits replay only on the mesh they were made on; open them with "
                             "'spool.off' as it was when they were saved (a file of that name changed since is "
                             "another mesh)"));

  const std::string text = good.dump();
  CHECK_THAT(test::bad_parameter_message([&] { document_from_text(text.substr(0, text.size() / 2)); }),
             Catch::StartsWith("the document is not valid JSON"));
  CHECK_THAT(test::bad_parameter_message([&] { document_from_text("not json"); }),
             Catch::StartsWith("the document is not valid JSON"));
}

TEST_CASE("document: the mesh hash is the mesh as loaded", "[document]") {
  Session a;
  load_spool(a);
  Session b;
  load_spool(b);
  CHECK(a.mesh_hash() == b.mesh_hash());
  replay_document(a, document_from_json(spool_document(a)));
  CHECK(a.mesh_hash() == b.mesh_hash());  // edits do not change the base mesh
  Positions moved = b.loaded_positions();
  moved(0, 0) = std::nextafter(moved(0, 0), 1.0);
  CHECK(mesh_hash(moved, b.rest().F) != b.mesh_hash());
  CHECK(mesh_hash_text(0x1234) == "fnv1a64:0000000000001234");
}

TEST_CASE("document: the CLI replays to the core's positions", "[document][cli]") {
  Session session;
  load_spool(session);
  const Json document = spool_document(session);
  const std::string doc_path = test::temp_path("spool-doc.json");
  std::ofstream(doc_path) << document.dump();
  const std::string out = test::temp_path("spool-replayed.obj");
  const test::CliRun run =
      test::run_cli_expecting({"replay", doc_path, out, "--mesh", test::mesh_path("closed/spool.off")}, 0);
  const Json result = Json::parse(run.out);
  CHECK(result["replayed"] == 3);
  CHECK(result["skipped"] == 0);
  CHECK(result["hash"] == document["mesh"]["hash"]);
  const Positions written = read_mesh(out).mesh.V;
  CHECK(positions_bitwise_equal(written, replayed_spool(document)));
  // `last` was in the JSON but not in --help's key list: the help names it
  // and lists its keys, the JS API's camelCase ones, as the output has them.
  const std::string help = test::run_cli_expecting({"replay", "--help"}, 0).out;
  std::string words;
  std::istringstream split(help);
  for (std::string word; split >> word;) words += word + " ";
  const std::string listed = "as the browser's replay returns it: ";
  const std::size_t from = words.find(listed);
  REQUIRE(from != std::string::npos);
  const std::string keys = words.substr(from + listed.size(), words.find(')', from) - from - listed.size());
  std::string output_keys;
  for (const auto& item : result["last"].items()) output_keys += (output_keys.empty() ? "" : ", ") + item.key();
  CHECK(keys == output_keys);
  CHECK(words.find("warnings (ops that left the mesh unchanged, and why), last (the last replayed op's result") !=
        std::string::npos);

  Json other = document;
  other["mesh"]["hash"] = "fnv1a64:0000000000000000";
  std::ofstream(doc_path) << other.dump();
  const test::CliRun mismatch =
      test::run_cli_expecting({"replay", doc_path, out, "--mesh", test::mesh_path("closed/spool.off")}, 3);
  CHECK_THAT(mismatch.err, Catch::Contains("does not match the loaded mesh"));
  std::ofstream(doc_path) << "{\"format\":";
  const test::CliRun truncated =
      test::run_cli_expecting({"replay", doc_path, out, "--mesh", test::mesh_path("closed/spool.off")}, 2);
  CHECK_THAT(truncated.err, Catch::Contains("not valid JSON"));

  // Without --mesh, the file of mesh.name's file name beside DOC, wherever
  // the name points (an absolute path or ../ named any file anywhere).
  Json elsewhere = document;
  elsewhere["mesh"]["name"] = test::mesh_path("closed/spool.off");
  std::ofstream(doc_path) << elsewhere.dump();
  const std::string beside_doc = doc_path.substr(0, doc_path.find_last_of('/') + 1) + "spool.off";
  std::remove(beside_doc.c_str());  // a run before this one left it
  const test::CliRun not_beside = test::run_cli_expecting({"replay", doc_path, out}, 3);
  CHECK_THAT(not_beside.err, Catch::Contains("spool.off"));
  CHECK_THAT(not_beside.err, !Catch::Contains("meshes/closed"));
  std::ofstream(beside_doc) << test::slurp(test::mesh_path("closed/spool.off"));
  const test::CliRun beside = test::run_cli_expecting({"replay", doc_path, out}, 0);
  CHECK(positions_bitwise_equal(read_mesh(out).mesh.V, replayed_spool(document)));
  elsewhere["mesh"]["name"] = "../";
  std::ofstream(doc_path) << elsewhere.dump();
  CHECK_THAT(test::run_cli_expecting({"replay", doc_path, out}, 2).err,
             Catch::Contains("document.mesh.name \"../\" is no file name to look for beside DOC"));
  std::remove(beside_doc.c_str());
}

TEST_CASE("document: an op given a new region is what a new edit of that region gives", "[document]") {
  // The twist origin and ARAP's handles and pins follow from the region: a
  // document stores them only when the edit gave them, so an op moved to
  // another region twists about that region's axis, and an ARAP drag moves
  // its vertices (it used to keep the old region's axis, and move the old
  // region's handles while the Edits list showed the new one).
  Region one, other;
  one.kind = other.kind = Region::Kind::Sphere;
  one.center = Eigen::Vector3d(0.3, 0.4, 0);
  other.center = Eigen::Vector3d(-0.3, -0.4, 0);
  one.radius = other.radius = 0.3;
  const auto region_json = [](const Region& r) {
    return Json{{"sphere", {{"center", {r.center.x(), r.center.y(), r.center.z()}}, {"radius", r.radius}}}};
  };
  for (const char* op_text : {R"({"transform":{"twist":{"axis":[0,1,0],"degreesPerUnit":60}}})",
                              R"({"method":"arap","move":[0,0.2,0.1]})"}) {
    INFO(op_text);
    const DeformOp edit = deform_op_from_json(Json::parse(op_text));
    Session made;
    load_spool(made);
    made.select(one, 0.05, SelectionMode::Replace);
    const Json op = to_json(resolve_for_document(made, edit));
    CHECK_FALSE(op.contains("handles"));
    CHECK_FALSE(op.dump().find("origin") != std::string::npos);

    Session fresh;
    load_spool(fresh);
    fresh.select(other, 0.05, SelectionMode::Replace);
    fresh.deform(edit);
    fresh.commit();

    Session replaying;
    load_spool(replaying);
    Json document = {{"format", "anisoform-document"}, {"version", 1},
                     {"mesh", {{"name", "spool.off"},
                               {"vertices", replaying.rest().num_vertices()},
                               {"triangles", replaying.rest().num_triangles()},
                               {"hash", mesh_hash_text(replaying.mesh_hash())}}},
                     {"regions", {{{"name", "moved"}, {"steps", {{{"region", region_json(other)}, {"falloff", 0.05}}}}}}},
                     {"ops", {{{"id", "a"}, {"label", "edit"}, {"region", "moved"}, {"op", op}}}}};
    CHECK(replay_document(replaying, document_from_json(document)).warnings.empty());
    const double moved = (fresh.positions() - replaying.positions()).cwiseAbs().maxCoeff();
    CHECK(moved < 1e-9);
    CHECK((fresh.positions() - made.positions()).cwiseAbs().maxCoeff() > 1e-3);  // the edit does something there
  }
}

TEST_CASE("document: an op whose region selects nothing is replayed with a warning naming it", "[document]") {
  // It leaves the mesh unchanged: said, as the CLI's deform says it of an
  // empty --select (the edit used to vanish with no word).
  Session session;
  load_spool(session);
  Json document = spool_document(session);
  document["regions"][0]["steps"][0]["region"] = Json::parse(R"({"sphere": {"center": [10, 10, 10], "radius": 0.1}})");
  const ReplaySummary summary = replay_document(session, document_from_json(document));
  REQUIRE(summary.warnings.size() == 1);
  CHECK(summary.warnings[0] ==
        "document.ops[0] (id 'stretch'): its region 'top' holds no vertex: the mesh is left unchanged");
  CHECK(to_json(summary)["warnings"][0] == summary.warnings[0]);
  CHECK(replay_document(session, document_from_json(spool_document(session))).warnings.empty());
}

TEST_CASE("document: stated counts, a malformed hash and a screen drag are refused naming document.mesh or the op",
          "[document]") {
  // check_document said it checked the counts, but checked only the hash: a
  // document stating 3000 vertices for the spool's 649 replayed (exit 0). A
  // hash "abc" was "does not match the loaded mesh" (exit 3), and a screen
  // drag "direction.camera is missing".
  Session session;
  load_spool(session);
  const Json good = spool_document(session);
  Json vertices = good;
  vertices["mesh"]["vertices"] = 3000;
  CHECK_THAT(refusal_of_document(vertices, ErrorCode::BadMesh),
             Catch::StartsWith("document.mesh.vertices is 3000, but the loaded mesh, whose hash fnv1a64:") &&
                 Catch::EndsWith("is the document's, has 649 vertices: the document's counts do not describe its mesh"));
  Json triangles = good;
  triangles["mesh"]["triangles"] = 1;
  CHECK_THAT(refusal_of_document(triangles, ErrorCode::BadMesh),
             Catch::StartsWith("document.mesh.triangles is 1, but") && Catch::Contains("has 1294 triangles"));

  for (const char* hash : {"abc", "fnv1a64:0123456789ABCDEF", "fnv1a64:0123456789abcde", "sha1:0123456789abcdef"}) {
    Json malformed = good;
    malformed["mesh"]["hash"] = hash;
    CHECK(refusal_of_document(malformed, ErrorCode::BadParameter) ==
          "document.mesh.hash must be 'fnv1a64:<16 hex digits>' (as mesh_hash_text writes it), got '" +
              std::string(hash) + "'");
  }

  Json screen = good;
  screen["ops"][0]["op"]["direction"] = Json::parse(R"({"type": "screen", "from": [0, 0], "to": [10, 0]})");
  CHECK_THAT(refusal_of_document(screen, ErrorCode::BadParameter),
             Catch::StartsWith("document.ops[0] (id 'stretch').op.direction is a screen drag, which a document "
                               "does not store: store the global vector it gives"));

  // Through the CLI: a mismatch of the mesh is exit 3, a malformed document exit 2.
  const std::string doc_path = test::temp_path("spool-doc-counts.json");
  const std::string out = test::temp_path("spool-doc-counts.obj");
  std::ofstream(doc_path) << vertices.dump();
  CHECK_THAT(test::run_cli_expecting({"replay", doc_path, out, "--mesh", test::mesh_path("closed/spool.off")}, 3).err,
             Catch::Contains("document.mesh.vertices is 3000") && Catch::Contains("has 649 vertices"));
  Json malformed = good;
  malformed["mesh"]["hash"] = "abc";
  std::ofstream(doc_path) << malformed.dump();
  CHECK_THAT(test::run_cli_expecting({"replay", doc_path, out, "--mesh", test::mesh_path("closed/spool.off")}, 2).err,
             Catch::Contains("document.mesh.hash must be 'fnv1a64:<16 hex digits>'"));
}
