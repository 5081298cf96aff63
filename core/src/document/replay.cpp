// check_document, resolve_for_document, replay_document and
// select_document_region (document.h): the one definition of replay.
#include <algorithm>

#include "anisoform/document.h"
#include "anisoform/error.h"
#include "anisoform/screen_direction.h"

namespace aniso {
namespace {

std::string document_op_name(const EditDocument& document, std::size_t index) {
  return "document.ops[" + std::to_string(index) + "] (id '" + document.ops[index].id + "')";
}

// Runs `work` and puts "WHERE: " before the message of any core Error it
// throws, keeping the code: a refusal found with the mesh still names the op.
template <typename Work>
void naming_document_part(const std::string& where, Work&& work) {
  try {
    work();
  } catch (const Error& error) {
    throw Error(error.code(), where + ": " + error.what());
  }
}

const DocumentRegion& document_region_named(const EditDocument& document, const std::string& name) {
  for (const DocumentRegion& region : document.regions) {
    if (region.name == name) return region;
  }
  // document_from_json checks every op's region name; a hand-built document may not.
  fail(ErrorCode::BadParameter, "the document has no region named '" + name + "'");
}

// The rule's steps from an empty selection, on the session's rest pose.
void apply_document_region(Session& session, const DocumentRegion& region) {
  session.set_selection(std::vector<float>(static_cast<std::size_t>(session.rest().num_vertices()), 0.0f));
  for (const DocumentSelectStep& step : region.steps) session.select(step.region, step.falloff, step.mode);
}

std::vector<double> xyz_of(const Positions& V) { return std::vector<double>(V.data(), V.data() + V.size()); }

}  // namespace

void check_document(const EditDocument& document, const Session& session) {
  const Mesh& rest = session.rest();
  const std::string loaded_hash = mesh_hash_text(session.mesh_hash());
  if (document.mesh_hash != loaded_hash) {
    fail(ErrorCode::BadMesh, "document mesh hash " + document.mesh_hash + " ('" + document.mesh_name + "', " +
                                 std::to_string(document.vertices) + " vertices, " +
                                 std::to_string(document.triangles) + " triangles) does not match the loaded mesh " +
                                 loaded_hash + " (" + std::to_string(rest.num_vertices()) + " vertices, " +
                                 std::to_string(rest.num_triangles()) +
                                 " triangles): saved edits replay only on the mesh they were made on; open them "
                                 "with '" + document.mesh_name +
                                 "' as it was when they were saved (a file of that name changed since is another "
                                 "mesh)");
  }
  // The same mesh (its hash matches), but counts the document states otherwise: it was edited by hand.
  const auto check_count = [&](const char* field, int stated, int has, const char* what) {
    if (stated == has) return;
    fail(ErrorCode::BadMesh, std::string(field) + " is " + std::to_string(stated) + ", but the loaded mesh, whose hash " +
                                 loaded_hash + " is the document's, has " + std::to_string(has) + " " + what +
                                 ": the document's counts do not describe its mesh");
  };
  check_count("document.mesh.vertices", document.vertices, rest.num_vertices(), "vertices");
  check_count("document.mesh.triangles", document.triangles, rest.num_triangles(), "triangles");
  const Mesh loaded{session.loaded_positions(), rest.F};
  for (std::size_t i = 0; i < document.regions.size(); ++i) {
    const DocumentRegion& region = document.regions[i];
    for (std::size_t k = 0; k < region.steps.size(); ++k) {
      naming_document_part("document.regions[" + std::to_string(i) + "] (name '" + region.name + "').steps[" +
                               std::to_string(k) + "].region",
                           [&] { region_weights(loaded, region.steps[k].region); });
    }
  }
  const double diagonal = shape_bounding_box(loaded).diagonal();
  for (std::size_t i = 0; i < document.ops.size(); ++i) {
    const DocumentOp& op = document.ops[i];
    naming_document_part(document_op_name(document, i), [&] {
      document_region_named(document, op.region);
      validate_twist(op.edit.request.transform, diagonal);
      validate_move(op.edit.request.handle_offset, diagonal);
      validate_direction_source(op.edit.request.direction, rest.num_vertices());
    });
  }
}

DeformOp resolve_for_document(const Session& session, const DeformOp& edit) {
  DeformOp full = edit;
  full.preview = false;
  DeformOp out;
  out.request = resolve_edit(full, session.rest().V, session.info().report.bbox, session.selection());
  DeformRequest& request = out.request;
  request.selection.resize(0);  // the document's region holds them
  request.warm_start = false;
  if (request.direction.kind == DirectionSource::Kind::Screen) {
    const Eigen::Vector3d vector = screen_drag_to_world(request.direction.screen);
    if (!vector.allFinite() || vector.norm() == 0.0) {
      fail(ErrorCode::BadParameter, "op.direction: the screen drag gives no direction (it has zero length)");
    }
    request.direction = DirectionSource();
    request.direction.vector = vector;
  }
  // What follows from the op's region on its input pose is left to replay
  // to work out there (resolve_edit, as here): the twist origin and ARAP's
  // handles and pins when the edit did not give them. Stored, they stayed
  // those of the region and pose the op was made on, so a new region or an
  // earlier op turned off kept the old twist axis, and an ARAP op its old handles.
  out.twist_origin_given = edit.twist_origin_given;
  if (edit.request.method == Method::Arap && edit.request.handles.empty()) {
    request.handles.clear();
    request.pins = edit.request.pins;
  }
  out.direction_given = true;
  out.preview = false;
  return out;
}

ReplaySummary replay_document(Session& session, const EditDocument& document, const ReplayRange& range) {
  check_document(document, session);
  const std::size_t to = std::min(range.to, document.ops.size());
  if (range.from > to) {
    fail(ErrorCode::BadParameter, "replay: from " + std::to_string(range.from) + " is beyond the document's " +
                                      std::to_string(document.ops.size()) + " ops");
  }
  // A fork, so that a failing op leaves `session` as it was; it shares the
  // session's factorizations, so committing an op that was just previewed
  // (or undone to) does not factorize again. Its progress is the session's.
  const std::unique_ptr<Session> fork = session.fork();
  Session& scratch = *fork;
  const Positions& loaded = session.loaded_positions();
  if (range.from == 0 && !(session.rest().V.array() == loaded.array()).all()) scratch.set_positions(xyz_of(loaded));
  ReplaySummary summary;
  for (std::size_t i = range.from; i < to; ++i) {
    const DocumentOp& op = document.ops[i];
    if (!op.enabled) {
      ++summary.skipped;
      continue;
    }
    naming_document_part(document_op_name(document, i), [&] {
      apply_document_region(scratch, document_region_named(document, op.region));
      // Always a cold solve: the result must not depend on what was previewed
      // before (or on whether anything was); a full one unless previewing.
      DeformOp edit = op.edit;
      edit.preview = range.preview;
      edit.request.warm_start = false;
      const std::string unchanged = unchanged_reason(
          resolve_edit(edit, scratch.rest().V, scratch.info().report.bbox, scratch.selection()),
          "its region '" + op.region + "'");
      if (!unchanged.empty()) summary.warnings.push_back(document_op_name(document, i) + ": " + unchanged);
      summary.last = scratch.deform(edit);
      for (const std::string& warning : summary.last.warnings) {
        summary.warnings.push_back(document_op_name(document, i) + ": " + warning);
      }
      scratch.commit();
    });
    ++summary.replayed;
  }
  const std::vector<float> cleared(static_cast<std::size_t>(scratch.rest().num_vertices()), 0.0f);
  session.adopt_rest_of(scratch);
  session.set_selection(cleared);
  return summary;
}

int select_document_region(Session& session, const EditDocument& document, const std::string& op_id) {
  for (const DocumentOp& op : document.ops) {
    if (op.id != op_id) continue;
    const DocumentRegion& region = document_region_named(document, op.region);
    check_document(document, session);  // every step's range, before the selection changes
    apply_document_region(session, region);
    return static_cast<int>((session.selection().array() > 0.0).count());
  }
  fail(ErrorCode::BadParameter, "the document has no op with id '" + op_id + "'");
}

}  // namespace aniso
