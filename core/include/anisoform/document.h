// The edit document: a base mesh, named regions and an ordered list of ops,
// as versioned JSON (docs/document.schema.json). It is the one place replay
// is defined: the CLI (`anisoform replay`), Node and the browser all hand
// their document to replay_document.
//
//   {format: 'anisoform-document', version: 1,
//    mesh: {name, vertices, triangles, hash: 'fnv1a64:<16 hex digits>'},
//    regions: [{name, steps: [{region: <op.h region>, falloff?, mode?}]}],
//    ops: [{id, label, enabled, region: <a region's name>, op: <op.h op>}]}
//
// A region is a rule, evaluated on the rest pose the op starts from: its
// steps run in order from an empty selection, as Session::select (the first
// step's mode is usually 'replace'). Explicit sparse weights are a single
// step with a {vertices, weights} region.
//
// Ops are stored resolved and view-independent (resolve_for_document): a
// screen drag as the global direction it produced, the direction and the
// iteration counts as used. What follows from the op's region on its input
// pose (the twist origin, ARAP's handles and pins, unless the edit gave them)
// is worked out there by replay, so that a changed region or an earlier op
// changed or turned off gives what a new edit of that region would. Replay runs every
// enabled op in order: the region's selection, a full solve (never a preview,
// never warm-started, so the result does not depend on what the page
// previewed before) and a commit.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "anisoform/op.h"
#include "anisoform/session.h"

namespace aniso {

inline constexpr const char* kDocumentFormat = "anisoform-document";
inline constexpr int kDocumentVersion = 1;

// FNV-1a 64 over the mesh as the session holds it after loading (welded):
// vertex and triangle counts (uint64, little-endian), every position as its
// IEEE-754 double bytes (little-endian), every index as uint32 little-endian.
// The same number natively and in WASM.
std::uint64_t mesh_hash(const Positions& V, const Triangles& F);
// "fnv1a64:" and 16 lower-case hex digits: JSON numbers cannot hold 64 bits.
std::string mesh_hash_text(std::uint64_t hash);
// Whether `text` has mesh_hash_text's form, 'fnv1a64:<16 hex digits>' (lower case).
bool is_mesh_hash_text(const std::string& text);

struct DocumentSelectStep {
  Region region;
  double falloff = 0.0;
  SelectionMode mode = SelectionMode::Replace;
};

struct DocumentRegion {
  std::string name;
  std::vector<DocumentSelectStep> steps;
};

struct DocumentOp {
  std::string id;
  std::string label;
  bool enabled = true;
  std::string region;  // a DocumentRegion's name
  DeformOp edit;
};

struct EditDocument {
  std::string mesh_name;
  int vertices = 0;
  int triangles = 0;
  std::string mesh_hash;  // as mesh_hash_text
  std::vector<DocumentRegion> regions;
  std::vector<DocumentOp> ops;
};

// The document's form: format, version, every key, every region and op
// (through the op module's parsers and the core's range validators). Error
// (BadParameter) naming the field path: "document.ops[2] (id 'neck').op.
// transform.scale[0] must be a finite number ...", "document.version: 2 is
// not supported (this build reads version 1)".
EditDocument document_from_json(const Json& document);
// The same from text: truncated or non-JSON text is Error(BadParameter)
// "the document is not valid JSON: ...".
EditDocument document_from_text(const std::string& text);

// Everything that needs the mesh, before any solve: the hash ("document mesh
// hash ... does not match the loaded mesh ..."), the counts, every op's
// region name, region vertex indices, twist range and direction source.
void check_document(const EditDocument& document, const Session& session);

// The request an edit means now, made view-independent for the document:
// resolve_edit on the session's rest pose and selection, a screen drag turned
// into the global vector it produced, preview and warm start off, everything
// "given" but what the region decides (see above). What the page stores when
// it commits an op.
DeformOp resolve_for_document(const Session& session, const DeformOp& edit);

// Which ops replay runs: [from, to) of the document's list. from == 0 starts
// from the mesh as loaded; from > 0 starts from the session's rest pose (the
// caller has put op `from`'s input there, e.g. from its cache).
// preview: each op runs as a live preview does (at most kPreviewIterations,
// still cold): a quick look at the document while a slider on an earlier op
// moves; never what a commit stores.
struct ReplayRange {
  std::size_t from = 0;
  std::size_t to = static_cast<std::size_t>(-1);
  bool preview = false;
};

// {from?, to?, preview?} (the hosts' replay options): integers >= 0, a boolean.
ReplayRange replay_range_from_json(const Json& options);

struct ReplaySummary {
  int replayed = 0;  // enabled ops solved
  int skipped = 0;   // disabled ops
  DeformOpResult last;  // the last solve's (what a page reports after committing one op)
  // Ops that left the mesh unchanged, and why (unchanged_reason, op.h):
  // "document.ops[2] (id 'b'): its region 'r' holds no vertex: ...".
  std::vector<std::string> warnings;
};

// Checks the document (check_document), then replays the range on a scratch
// session and moves the result in (set_positions); the selection is cleared.
// On any error the session is left as it was.
ReplaySummary replay_document(Session& session, const EditDocument& document, const ReplayRange& range = {});

// Sets the session's selection to the region of op `op_id`, evaluated on the
// current rest pose (what a live re-parameterisation deforms with).
int select_document_region(Session& session, const EditDocument& document, const std::string& op_id);

// The allowed keys of the document's objects, as op_schema lists them:
// "document", "document.mesh", "document.region", "document.step",
// "document.op", "replay" (ReplayRange).
Json document_schema();

// {replayed, skipped, last: to_json(DeformOpResult) or null when nothing was solved}
Json to_json(const ReplaySummary& summary);

}  // namespace aniso
