// The state of one interactive modelling session (the browser app through the
// WASM module, or any other host that edits one mesh over time): the mesh as
// loaded, the rest pose edits start from, the current positions, the selection
// weights, and the Deformer that owns the rest pose's factorizations.
//
// An edit deforms FROM the rest pose, so a live drag can call deform() many
// times (warm-started) and cancel() or commit() at the end. commit() and
// set_positions() make a new rest pose, which needs a new Deformer: its
// factorizations are redone lazily on the next edit. Every method either
// succeeds or throws an aniso::Error and leaves the session as it was.
//
// Memory: the session keeps the previous rest pose's Deformer too, so that
// undo and re-parameterising the last op need no new factorization. On a
// large mesh two factorized poses may not fit (in the browser's 2 GB, from
// about 400k vertices): above half the vertex limit a commit keeps only the
// previous pose's mesh, a load frees the old mesh's factorizations before
// it builds anything, and an edit or a flattening that runs out of memory
// frees the kept factorizations and runs once more, slower but within what
// one pose needs. Only if that fails too does it throw std::bad_alloc, with
// the session as it was.
//
// Positions, triangles and weights are also kept as float32 / uint32 copies,
// laid out as the GPU wants them, so that a host can hand out views of them
// without a copy (the WASM module's typed_memory_view).
//
// flatten() turns the current positions (or the selected part) into a garment
// pattern (session_flatten.h); its Flattener, which holds the factorization,
// is kept and reused until the positions or the patch change.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "anisoform/deformer.h"
#include "anisoform/distortion.h"
#include "anisoform/mesh.h"
#include "anisoform/progress.h"
#include "anisoform/mesh_check.h"
#include "anisoform/mesh_io.h"
#include "anisoform/selection.h"
#include "anisoform/session_flatten.h"

namespace aniso {

class TargetContext;
struct SessionFlattenState;
struct VertexAdjacency;

// What the session knows about its mesh as loaded.
struct SessionMeshInfo {
  MeshReport report;               // check_mesh of the mesh the session holds
  std::vector<std::string> notes;  // what the reader and the session repaired, in plain words
};

// How a new region combines with the current selection (fuzzy-set rules, so
// soft weights combine smoothly): Add = max(old, new), Subtract =
// min(old, 1 - new).
enum class SelectionMode { Replace, Add, Subtract };

// The public op (op.h) in C++: one edit as a host asks for it, before the
// session fills in what depends on the mesh (resolve_edit) and hands its
// DeformRequest to the solver. `request.selection` is ignored: the
// session's selection is used.
struct DeformOp {
  DeformRequest request;
  // A twist turns about `request.transform.twist_origin` when this is set;
  // otherwise about default_twist_origin (as the CLI does): the axis line
  // through the selection's weighted centroid, angle 0 at its lowest point.
  bool twist_origin_given = false;
  // false: along the longest axis of the mesh as loaded (resolve_edit, op.h);
  // deform_op_from_json sets it false when the op has no direction. (Arap
  // without handles takes its handles from the selection: resolve_edit too.)
  bool direction_given = true;
  // Live preview: at most kPreviewIterations iterations, warm-started from the
  // previous preview. The paper's rotation scheme (RotationScheme::Steps) is
  // not capped: it runs request.rotation_steps steps from the rest pose.
  bool preview = false;
};

constexpr int kPreviewIterations = 4;

struct DeformOpResult {
  int selected = 0;
  int iterations = 0;
  double energy = 0.0;
  std::vector<double> energy_history;  // after each iteration (AnARAP / ARAP)
  bool converged = true;
  int directions_filled = 0;
  int inverted = 0;        // triangles folded over (count_inverted)
  int factorizations = 0;  // total in the session so far
  double precompute_ms = 0.0;
  double solve_ms = 0.0;
  double total_ms = 0.0;  // the whole call, as the host waits for it
  std::vector<std::string> warnings;  // DeformResult::warnings
};

// What distortion() measures against.
enum class DistortionReference {
  Rest,    // the rest pose: the edit in progress
  Loaded,  // the mesh as loaded: every edit since
};

class Session {
 public:
  Session();
  ~Session();
  Session(const Session&) = delete;
  Session& operator=(const Session&) = delete;

  // Replaces the mesh by one read from file bytes; the format comes from the
  // extension of `name`. A triangle soup is welded (and noted); a mesh that
  // cannot be solved on is refused with Error(BadMesh). The selection is
  // cleared (all weights 0).
  const SessionMeshInfo& load_mesh(const std::uint8_t* data, std::size_t size,
                                   const std::string& name);
  // Same from flat arrays (xyz per vertex, 3 indices per triangle); `weld`
  // merges vertices at equal positions (an unindexed three.js geometry).
  const SessionMeshInfo& set_mesh(const std::vector<double>& positions,
                                  const std::vector<std::uint32_t>& triangles, bool weld);
  // After set_mesh: vertex i of its arrays is vertex input_vertex_map()[i] of
  // the mesh loaded (welding merges vertices; without it, the identity).
  // Empty after load_mesh and adopt_mesh. A host that keeps the input's own
  // data (a glTF scene's UVs, materials and nodes) writes the edited
  // positions back through it.
  const std::vector<std::uint32_t>& input_vertex_map() const { return input_vertex_map_; }

  // Same from a mesh already read (the CLI reads files itself, for its own
  // error texts): the one preparation every host's mesh goes through. `notes`
  // are kept in info().notes, after which the session adds its own.
  // `attributes`: what the file carries besides positions and triangles
  // (mesh_io.h: an OBJ's texture coordinates and materials, a PLY's vertex
  // properties), which an export in its format writes again; kept while the
  // faces and vertices stay as read. `numbering_note`
  // (element_numbering_note, mesh_io.h) follows a refusal that names
  // vertices or faces, unless a weld numbered the vertices anew.
  const SessionMeshInfo& adopt_mesh(Mesh mesh, std::vector<std::string> notes, SurfaceAttributes attributes = {},
                                    const std::string& numbering_note = {});
  // Those of the mesh loaded (empty: none).
  const SurfaceAttributes& attributes() const { return attributes_; }
  // How a mesh file written from this session keeps them (PLY: binary or not).
  WriteOptions write_options(bool binary = true) const;

  // The most vertices a mesh may have in this host (0, the default: no
  // limit), and why, for the refusal: "more than the N <why>". The WASM
  // module sets it from its memory ceiling: every edit factorizes the whole
  // mesh's Laplacian, and a mesh too big for that would otherwise load and
  // then fail at its first edit, a minute later.
  void set_vertex_limit(int max_vertices, std::string why);
  int vertex_limit() const { return vertex_limit_; }

  // Long calls report how far they have got: loading a mesh, factorizing,
  // a deform's iterations, a flattening's (progress.h). None by default.
  void set_progress(ProgressFn progress);
  const ProgressFn& progress() const { return progress_; }

  bool has_mesh() const { return deformer_ != nullptr; }
  // These throw Error(BadParameter) "no mesh is loaded" before the first mesh.
  const SessionMeshInfo& info() const;
  const Mesh& rest() const;
  const Positions& positions() const;
  // The positions as loaded (welded), before any edit: what a document
  // replays from.
  const Positions& loaded_positions() const;
  // mesh_hash (document.h) of the mesh as loaded.
  std::uint64_t mesh_hash() const;
  const std::vector<float>& positions_f32() const { return positions_f32_; }
  const std::vector<std::uint32_t>& triangles_u32() const { return triangles_u32_; }

  // Selection weights in [0, 1]; returns the number of vertices with weight > 0.
  int select(const Region& region, double falloff, SelectionMode mode);
  int set_selection(const std::vector<float>& weights);  // #V weights in [0, 1]
  const Eigen::VectorXd& selection() const { return weights_; }
  const std::vector<float>& selection_f32() const { return weights_f32_; }

  // Deforms the rest pose; positions() then holds the result.
  DeformOpResult deform(const DeformOp& edit);
  void commit();  // the current positions become the rest pose
  void cancel();  // the current positions go back to the rest pose
  // Restores positions (undo/redo; 3 numbers per vertex); they also become
  // the rest pose, with a new Deformer.
  void set_positions(const std::vector<double>& positions);
  // The rest pose's set-up for its next edit (the factorization first), one
  // part per call (Deformer::prepare_step): what a host with one thread runs
  // in the background after a load or a commit, answering other calls (a
  // select, an edit) between the parts; the first part also builds what
  // select() needs. Changes no edit state, nor any result. Returns the share
  // of the set-up done: 1 when nothing is left.
  double prepare_step();

  // Unit tangent direction per vertex (#V by 3) of a direction source, after
  // projection and filling exactly as the AnARAP solver frames it: what glyphs
  // should show.
  Positions direction_field(const DirectionSource& source);
  // Per-vertex distortion of the current positions (distortion.h).
  Eigen::VectorXd distortion(DistortionKind kind, DistortionReference reference) const;
  // The current mesh as file bytes.
  std::string export_mesh(MeshFormat format) const;
  // Flattens the current positions: the whole mesh or the selected patch
  // (session_flatten.h). Error(BadMesh) for a closed patch, Error(BadParameter)
  // for an empty selection or bad amounts; the session is then unchanged.
  SessionFlattenResult flatten(const SessionFlatten& request);
  // The last flatten() as a pattern file, format "svg" or "dxf", scaled by
  // millimetres per model unit. Error(BadParameter) "flatten first" when the
  // mesh or positions changed since (or there was none).
  std::string export_pattern(const std::string& format, double mm_per_unit) const;
  // Factorizations done in this session, over all rest poses and flattenings.
  int factorizations() const;

  // A session on this one's mesh, at its rest pose, that shares its
  // Deformers (the rest pose's and the previous one's, with their
  // factorizations) and its adjacency: what a replay runs its ops in, so
  // that committing an op previewed here neither reads, checks and
  // factorizes the mesh again nor changes this session if an op fails.
  // Results do not depend on the sharing: a cold solve starts from the rest
  // pose and sets every target itself (replay.cpp).
  std::unique_ptr<Session> fork();
  // This session's rest pose and positions become the rest pose of `fork`
  // (a fork of it), taking over its Deformer: the pose a replay ended at,
  // without building its Laplacian again. Error(BadParameter) for a session
  // on another mesh.
  void adopt_rest_of(Session& fork);

 private:
  void require_mesh() const;
  const VertexAdjacency& adjacency();
  void report(ProgressStage stage, double fraction) const;
  std::shared_ptr<Deformer> new_deformer(Mesh mesh, std::shared_ptr<LaplacianPatterns> patterns);
  // Runs `operation`; should it run out of memory (std::bad_alloc), frees
  // what is kept only for speed (release_kept_memory) and runs it once more.
  // The operations it wraps change nothing until their work is done, so a
  // failed first run leaves nothing half done to the second.
  void retrying_out_of_memory(const std::function<void()>& operation);
  // Frees the factorizations kept for speed: the previous rest pose's (for
  // undo), the rest pose's own (the next edit makes them again) and, in a
  // fork, its origin's; and the kept orderings. The edit state (mesh,
  // positions, selection, the last pattern) is untouched. Returns whether
  // anything was freed.
  bool release_kept_memory() noexcept;
  DeformOpResult deform_once(const DeformOp& edit);
  SessionFlattenResult flatten_once(const SessionFlatten& request);
  // Reports of `deformer` go through this session's progress.
  void report_through_this(Deformer& deformer);
  void replace_rest(Positions V);
  // `deformer` (whose rest pose is V) becomes the rest pose's.
  void install_rest(std::shared_ptr<Deformer> deformer, Positions V);
  // New current positions with their float32 copy, allocated before anything
  // changes (a failed allocation leaves the session as it was); set_current
  // then only moves them in.
  struct CurrentPositions {
    Positions V;
    std::vector<float> f32;
  };
  static CurrentPositions current_positions(Positions V);
  void set_current(CurrentPositions current) noexcept;
  void set_weights(Eigen::VectorXd weights);

  std::shared_ptr<Deformer> deformer_;  // owns the rest pose (shared with forks)
  // The orderings of the mesh's Laplacian, shared by the Deformers of all its
  // poses (and with forks): a pose's factorization reuses them.
  std::shared_ptr<LaplacianPatterns> patterns_;
  // The Deformer of the rest pose before the last change, with its
  // factorizations: going back to exactly that pose (undo, re-parameterising
  // the last op of an edit document) swaps it in instead of refactoring.
  std::shared_ptr<Deformer> previous_;
  // A fork's origin's Deformers (fork()), which it may free under memory
  // pressure too: not owned, so a fork never keeps them alive.
  std::vector<std::weak_ptr<Deformer>> origin_deformers_;
  std::unique_ptr<TargetContext> targets_;  // for direction_field(), built lazily per rest pose
  std::shared_ptr<const VertexAdjacency> adjacency_;  // for select(), built lazily per mesh (not per pose)
  std::unique_ptr<SessionFlattenState> flatten_;  // always set; dropped per positions change
  int retired_factorizations_ = 0;      // done by the Deformers of earlier rest poses
  int vertex_limit_ = 0;                // set_vertex_limit
  ProgressFn progress_;
  std::string vertex_limit_why_;
  Positions loaded_;                    // positions as loaded, for DistortionReference::Loaded
  Positions current_;
  Eigen::VectorXd weights_;
  SessionMeshInfo info_;
  std::vector<float> positions_f32_;
  std::vector<std::uint32_t> triangles_u32_;
  std::vector<float> weights_f32_;
  std::vector<std::uint32_t> input_vertex_map_;  // set_mesh's, see input_vertex_map()
  SurfaceAttributes attributes_;
};

}  // namespace aniso
