#include "anisoform/session.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <new>
#include <utility>

#include "anisoform/document.h"
#include "deform/element_targets.h"
#include "anisoform/error.h"
#include "anisoform/op.h"
#include "geometry/frames.h"
#include "geometry/laplacian_solver.h"
#include "mesh/topology.h"
#include "session/session_flatten_state.h"

namespace aniso {
namespace {

double milliseconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

std::vector<float> to_float32(const Positions& V) {
  std::vector<float> out(static_cast<std::size_t>(V.size()));
  for (Eigen::Index i = 0; i < V.rows(); ++i)
    for (int k = 0; k < 3; ++k) out[static_cast<std::size_t>(3 * i + k)] = static_cast<float>(V(i, k));
  return out;
}

Positions positions_from_xyz(const std::vector<double>& xyz) {
  Positions V(static_cast<Eigen::Index>(xyz.size() / 3), 3);
  for (Eigen::Index i = 0; i < V.rows(); ++i)
    for (int k = 0; k < 3; ++k) V(i, k) = xyz[static_cast<std::size_t>(3 * i + k)];
  return V;
}

void require_xyz_count(std::size_t count, const std::string& what) {
  if (count % 3 != 0) {
    fail(ErrorCode::BadParameter, what + " needs 3 numbers per vertex, got " +
                                      std::to_string(count) + " numbers");
  }
}

int count_selected(const Eigen::VectorXd& weights) {
  return static_cast<int>((weights.array() > 0.0).count());
}

// Prefixes a reader's message with the file name, keeping its code.
[[noreturn]] void fail_with_name(const Error& error, const std::string& name) {
  fail(error.code(), name + ": " + error.what());
}

}  // namespace

Session::Session() : flatten_(std::make_unique<SessionFlattenState>()) {}
Session::~Session() = default;

void Session::require_mesh() const {
  if (!deformer_) fail(ErrorCode::BadParameter, "no mesh is loaded");
}

const SessionMeshInfo& Session::info() const {
  require_mesh();
  return info_;
}

const Mesh& Session::rest() const {
  require_mesh();
  return deformer_->rest();
}

const Positions& Session::positions() const {
  require_mesh();
  return current_;
}

const Positions& Session::loaded_positions() const {
  require_mesh();
  return loaded_;
}

std::uint64_t Session::mesh_hash() const {
  require_mesh();
  return aniso::mesh_hash(loaded_, deformer_->rest().F);
}

const SessionMeshInfo& Session::load_mesh(const std::uint8_t* data, std::size_t size,
                                          const std::string& name) {
  const MeshFormat format = format_from_path(name);  // its message names the file already
  report(ProgressStage::Load, 0.0);
  ReadResult read;
  try {
    read = read_mesh_from_memory(reinterpret_cast<const char*>(data), size, format);
  } catch (const Error& error) {
    fail_with_name(error, name);
  }
  // The shares of an 800k-vertex load: reading 5 %, checking 30 %, the rest
  // the Laplacian (adopt_mesh).
  report(ProgressStage::Load, 0.05);
  const int read_vertices = read.mesh.num_vertices();
  const std::string numbering = element_numbering_note(format);
  try {
    adopt_mesh(std::move(read.mesh), std::move(read.report.notes), std::move(read.attributes), numbering);
  } catch (const Error& error) {
    fail_with_name(error, name);
  }
  // The load's notice names the faces and vertices of the problems it lists:
  // it says how they are counted too (not after a weld, which numbered the
  // vertices anew; the CLI's warnings name none).
  if (!numbering.empty() && !info_.report.problems.empty() && info_.report.vertices == read_vertices) {
    info_.notes.push_back(numbering);
  }
  return info_;
}

const SessionMeshInfo& Session::set_mesh(const std::vector<double>& positions,
                                         const std::vector<std::uint32_t>& triangles, bool weld) {
  require_xyz_count(positions.size(), "setMesh: positions");
  if (triangles.size() % 3 != 0) {
    fail(ErrorCode::BadParameter, "setMesh: triangles needs 3 indices per triangle, got " +
                                      std::to_string(triangles.size()) + " indices");
  }
  Mesh mesh;
  mesh.V = positions_from_xyz(positions);
  mesh.F.resize(static_cast<Eigen::Index>(triangles.size() / 3), 3);
  for (std::size_t i = 0; i < triangles.size(); ++i) {
    // Checked here, before the indices are narrowed to int or used by welding.
    if (triangles[i] >= static_cast<std::uint32_t>(mesh.num_vertices())) {
      fail(ErrorCode::BadMesh, "triangle " + std::to_string(i / 3) + " references vertex " +
                                   std::to_string(triangles[i]) + ", but there are only " +
                                   std::to_string(mesh.num_vertices()) + " vertices");
    }
    mesh.F(static_cast<Eigen::Index>(i / 3), static_cast<Eigen::Index>(i % 3)) =
        static_cast<int>(triangles[i]);
  }
  std::vector<std::string> notes;
  std::vector<int> map;
  if (weld) {
    const int before = mesh.num_vertices();
    const int faces_before = mesh.num_triangles();
    mesh = weld_vertices(mesh, 0.0, &map);
    if (mesh.num_vertices() < before) {
      notes.push_back("welded vertices at equal positions: " + std::to_string(before) + " -> " +
                      std::to_string(mesh.num_vertices()) + " vertices");
    }
    if (mesh.num_triangles() < faces_before) {
      notes.push_back(std::to_string(faces_before - mesh.num_triangles()) +
                      " triangle(s) collapsed by welding were dropped");
    }
  }
  // adopt_mesh welds a triangle soup, exactly as here: the map follows it
  // (after a weld here, a second one merges nothing).
  if (map.empty() && is_triangle_soup(mesh)) weld_vertices(mesh, 0.0, &map);
  std::vector<std::uint32_t> input_map(map.empty() ? positions.size() / 3 : map.size());
  for (std::size_t i = 0; i < input_map.size(); ++i) {
    input_map[i] = static_cast<std::uint32_t>(map.empty() ? static_cast<int>(i) : map[i]);
  }
  const SessionMeshInfo& info = adopt_mesh(std::move(mesh), std::move(notes));
  input_vertex_map_ = std::move(input_map);
  return info;
}

void Session::set_vertex_limit(int max_vertices, std::string why) {
  if (max_vertices < 0) fail(ErrorCode::BadParameter, "the vertex limit must be 0 (none) or positive");
  vertex_limit_ = max_vertices;
  vertex_limit_why_ = std::move(why);
}

const SessionMeshInfo& Session::adopt_mesh(Mesh mesh, std::vector<std::string> notes, SurfaceAttributes attributes,
                                           const std::string& numbering_note) {
  // A soup has no shared vertices, so no edit could spread over it: weld it,
  // and say so (what `anisoform info` reports too).
  const int faces_before = mesh.num_triangles();
  const bool welded = weld_if_triangle_soup(mesh, notes);
  const std::string numbering = welded ? std::string() : numbering_note;
  if (welded) {
    // Texture rows and material runs follow the faces: a face welding
    // collapsed shifts them. The vertices are others now.
    if (mesh.num_triangles() != faces_before) {
      attributes.texture = CornerTexture();
      attributes.materials.runs.clear();
    }
    attributes.vertex_properties.clear();
    attributes.vertex_colors.resize(0, 3);
  }
  // Before the checks and the Laplacian: the refusal should come at once.
  if (vertex_limit_ > 0 && mesh.num_vertices() > vertex_limit_) {
    fail(ErrorCode::BadMesh, "the mesh has " + std::to_string(mesh.num_vertices()) + " vertices, more than the " +
                                 std::to_string(vertex_limit_) + " " + vertex_limit_why_);
  }
  SessionMeshInfo info{check_mesh(mesh), std::move(notes)};
  if (!info.report.solvable()) {
    fail(ErrorCode::BadMesh, "cannot edit this mesh: " + info.report.blocking_summary() +
                                 (numbering.empty() ? "" : "; " + numbering));
  }
  report(ProgressStage::Load, 0.35);
  // The mesh is accepted: the old one's factorizations go now rather than at
  // the end, so that they and the new mesh's need not fit side by side.
  release_kept_memory();
  auto patterns = std::make_shared<LaplacianPatterns>();
  std::shared_ptr<Deformer> deformer = new_deformer(std::move(mesh), patterns);
  // Everything the new mesh needs is allocated before the session changes, so
  // that running out of memory (std::bad_alloc) leaves it as it was, too.
  Positions loaded = deformer->rest().V;
  const Triangles& F = deformer->rest().F;
  std::vector<std::uint32_t> triangles_u32(static_cast<std::size_t>(F.size()));
  for (Eigen::Index t = 0; t < F.rows(); ++t)
    for (int k = 0; k < 3; ++k)
      triangles_u32[static_cast<std::size_t>(3 * t + k)] = static_cast<std::uint32_t>(F(t, k));
  CurrentPositions current = current_positions(loaded);
  Eigen::VectorXd weights = Eigen::VectorXd::Zero(deformer->rest().num_vertices());
  std::vector<float> weights_f32(static_cast<std::size_t>(weights.size()), 0.0f);

  // Nothing below throws or allocates: moves only.
  targets_.reset();
  adjacency_.reset();
  if (deformer_) retired_factorizations_ += deformer_->factorizations();
  if (previous_) retired_factorizations_ += previous_->factorizations();
  previous_.reset();
  deformer_ = std::move(deformer);
  patterns_ = std::move(patterns);
  info_ = std::move(info);
  loaded_ = std::move(loaded);
  triangles_u32_ = std::move(triangles_u32);
  input_vertex_map_.clear();
  attributes_ = std::move(attributes);
  set_current(std::move(current));
  weights_ = std::move(weights);
  weights_f32_ = std::move(weights_f32);
  report(ProgressStage::Load, 1.0);
  return info_;
}

void Session::set_progress(ProgressFn progress) { progress_ = std::move(progress); }

void Session::report(ProgressStage stage, double fraction) const {
  if (progress_) progress_(stage, fraction);
}

std::shared_ptr<Deformer> Session::new_deformer(Mesh mesh, std::shared_ptr<LaplacianPatterns> patterns) {
  auto deformer = std::make_shared<Deformer>(std::move(mesh), std::move(patterns));
  report_through_this(*deformer);
  return deformer;
}

void Session::report_through_this(Deformer& deformer) {
  // Through the session, so that a later set_progress reaches it too.
  deformer.set_progress([this](ProgressStage stage, double fraction) { report(stage, fraction); });
}

Session::CurrentPositions Session::current_positions(Positions V) {
  std::vector<float> f32 = to_float32(V);
  return {std::move(V), std::move(f32)};
}

void Session::set_current(CurrentPositions current) noexcept {
  // Every change of the positions passes here: a flattening of the old ones
  // can be neither reused nor exported.
  flatten_->positions_changed();
  current_ = std::move(current.V);
  positions_f32_ = std::move(current.f32);
}

void Session::set_weights(Eigen::VectorXd weights) {
  std::vector<float> f32(weights.data(), weights.data() + weights.size());
  weights_ = std::move(weights);
  weights_f32_ = std::move(f32);
}

void Session::replace_rest(Positions V) {
  const bool back_to_previous = previous_ && previous_->rest().V.rows() == V.rows() &&
                                std::memcmp(previous_->rest().V.data(), V.data(), sizeof(double) * static_cast<std::size_t>(V.size())) == 0;
  // Built before V is moved into install_rest (argument order is unspecified).
  std::shared_ptr<Deformer> deformer = back_to_previous ? previous_ : new_deformer(Mesh{V, deformer_->rest().F}, patterns_);
  install_rest(std::move(deformer), std::move(V));
}

void Session::install_rest(std::shared_ptr<Deformer> deformer, Positions V) {
  CurrentPositions current = current_positions(std::move(V));
  // Nothing below throws or allocates.
  targets_.reset();  // it refers to the old rest mesh
  if (previous_ && previous_ != deformer) retired_factorizations_ += previous_->factorizations();
  previous_ = std::move(deformer_);
  deformer_ = std::move(deformer);
  // The vertex limit allows one factorized pose (set_vertex_limit): above
  // half of it two would not fit, so the previous pose keeps its rest mesh
  // only, and undo factorizes it again. Freed now, before the new pose is
  // factorized, so that it takes the same memory back: freed only once an
  // allocation had failed (retrying_out_of_memory), the blocks were too
  // scattered, and a 470k-vertex cylinder's second commit failed even so.
  if (previous_ && vertex_limit_ > 0 && 2 * static_cast<long>(deformer_->rest().num_vertices()) > vertex_limit_) {
    previous_->release_memory();
  }
  set_current(std::move(current));
}

std::unique_ptr<Session> Session::fork() {
  require_mesh();
  auto fork = std::make_unique<Session>();
  fork->deformer_ = deformer_;
  fork->patterns_ = patterns_;
  fork->previous_ = previous_;
  fork->origin_deformers_ = origin_deformers_;
  fork->origin_deformers_.push_back(deformer_);
  if (previous_) fork->origin_deformers_.push_back(previous_);
  adjacency();
  fork->adjacency_ = adjacency_;
  fork->vertex_limit_ = vertex_limit_;
  fork->vertex_limit_why_ = vertex_limit_why_;
  fork->progress_ = progress_;
  fork->loaded_ = loaded_;
  fork->info_ = info_;
  fork->triangles_u32_ = triangles_u32_;
  fork->set_current(current_positions(deformer_->rest().V));
  fork->set_weights(Eigen::VectorXd::Zero(deformer_->rest().num_vertices()));
  return fork;
}

void Session::adopt_rest_of(Session& fork) {
  require_mesh();
  fork.require_mesh();
  if (fork.triangles_u32_ != triangles_u32_) {
    fail(ErrorCode::BadParameter, "adopt_rest_of: the session is not a fork of this one (other triangles)");
  }
  if (fork.deformer_ == deformer_) {  // it made no new rest pose
    set_current(current_positions(deformer_->rest().V));
    return;
  }
  report_through_this(*fork.deformer_);  // the fork's reports end with it
  install_rest(fork.deformer_, fork.deformer_->rest().V);
}

// Built once per mesh, not on every select (the page asks for each one).
const VertexAdjacency& Session::adjacency() {
  const Mesh& rest = deformer_->rest();
  if (!adjacency_) adjacency_ = std::make_shared<VertexAdjacency>(vertex_adjacency(rest.F, rest.num_vertices()));
  return *adjacency_;
}

int Session::select(const Region& region, double falloff, SelectionMode mode) {
  require_mesh();
  // Regions are evaluated on the rest pose, which is what is on screen between edits.
  const Eigen::VectorXd picked = selection_weights(deformer_->rest(), adjacency(), region, falloff);
  Eigen::VectorXd weights = weights_;
  switch (mode) {
    case SelectionMode::Replace: weights = picked; break;
    case SelectionMode::Add: weights = weights.cwiseMax(picked); break;
    case SelectionMode::Subtract: weights = weights.array().min(1.0 - picked.array()).matrix(); break;
  }
  set_weights(std::move(weights));
  return count_selected(weights_);
}

int Session::set_selection(const std::vector<float>& weights) {
  require_mesh();
  const int n = deformer_->rest().num_vertices();
  if (weights.size() != static_cast<std::size_t>(n)) {
    fail(ErrorCode::BadParameter, "setSelection needs one weight per vertex (" + std::to_string(n) +
                                      "), got " + std::to_string(weights.size()));
  }
  Eigen::VectorXd converted(n);
  for (int i = 0; i < n; ++i) {
    const double w = weights[static_cast<std::size_t>(i)];
    if (!(w >= 0.0 && w <= 1.0)) {
      fail(ErrorCode::BadParameter, "setSelection: the weight of vertex " + std::to_string(i) +
                                        " is " + std::to_string(w) + ", outside [0, 1]");
    }
    converted[i] = w;
  }
  set_weights(std::move(converted));
  return count_selected(weights_);
}

void Session::retrying_out_of_memory(const std::function<void()>& operation) {
  try {
    operation();
    return;
  } catch (const std::bad_alloc&) {
    if (!release_kept_memory()) throw;
  }
  operation();
}

bool Session::release_kept_memory() noexcept {
  bool released = false;
  if (previous_) released = previous_->release_memory() || released;
  if (deformer_) released = deformer_->release_memory() || released;
  for (const std::weak_ptr<Deformer>& kept : origin_deformers_) {
    if (const std::shared_ptr<Deformer> deformer = kept.lock()) released = deformer->release_memory() || released;
  }
  if (targets_) {
    targets_.reset();
    released = true;
  }
  if (patterns_ && !patterns_->by_pins.empty()) {
    patterns_->by_pins.clear();
    released = true;
  }
  return released;
}

DeformOpResult Session::deform(const DeformOp& edit) {
  DeformOpResult summary;
  retrying_out_of_memory([&] { summary = deform_once(edit); });
  return summary;
}

DeformOpResult Session::deform_once(const DeformOp& edit) {
  require_mesh();
  const auto start = std::chrono::steady_clock::now();
  DeformResult result = deformer_->deform(resolve_edit(edit, deformer_->rest().V, info_.report.bbox, weights_));

  DeformOpResult summary;
  summary.selected = result.selected;
  summary.iterations = result.iterations;
  summary.energy = result.energy;
  summary.energy_history = std::move(result.energy_history);
  summary.converged = result.converged;
  summary.directions_filled = result.directions_filled;
  summary.inverted = result.inverted;
  summary.precompute_ms = result.precompute_ms;
  summary.solve_ms = result.solve_ms;
  summary.warnings = std::move(result.warnings);
  set_current(current_positions(std::move(result.V)));
  summary.factorizations = factorizations();
  summary.total_ms = milliseconds_since(start);
  return summary;
}

void Session::commit() {
  require_mesh();
  replace_rest(current_);
}

double Session::prepare_step() {
  require_mesh();
  double share = 0.0;
  retrying_out_of_memory([&] {
    adjacency();  // the first select's, with the first part
    share = deformer_->prepare_step();
  });
  return share;
}

void Session::cancel() {
  require_mesh();
  set_current(current_positions(deformer_->rest().V));
}

void Session::set_positions(const std::vector<double>& positions) {
  require_mesh();
  const int n = deformer_->rest().num_vertices();
  if (positions.size() != 3 * static_cast<std::size_t>(n)) {
    fail(ErrorCode::BadParameter, "setPositions needs 3 numbers per vertex (" +
                                      std::to_string(3 * static_cast<std::size_t>(n)) + "), got " +
                                      std::to_string(positions.size()));
  }
  replace_rest(positions_from_xyz(positions));
}

Positions Session::direction_field(const DirectionSource& source) {
  require_mesh();
  validate_direction_source(source, deformer_->rest().num_vertices());
  if (!targets_) targets_ = std::make_unique<TargetContext>(deformer_->rest());
  Positions directions;
  Eigen::VectorXd su, sv;
  targets_->vertex_directions(source, directions, su, sv);
  return build_frames(targets_->vertex_normals(), directions,
                      [this]() -> const VertexAdjacency& { return targets_->vertex_adjacency(); })
      .u;
}

Eigen::VectorXd Session::distortion(DistortionKind kind, DistortionReference reference) const {
  require_mesh();
  const Mesh& rest = deformer_->rest();
  if (reference == DistortionReference::Rest) return vertex_distortion(rest, current_, kind);
  return vertex_distortion(Mesh{loaded_, rest.F}, current_, kind);
}

std::string Session::export_mesh(MeshFormat format) const {
  require_mesh();
  return write_mesh_to_memory(Mesh{current_, deformer_->rest().F}, format, write_options());
}

WriteOptions Session::write_options(bool binary) const {
  WriteOptions options;
  options.binary = binary;
  options.attributes = &attributes_;  // the file's texture, materials or vertex properties, as read
  return options;
}

int Session::factorizations() const {
  return retired_factorizations_ + (deformer_ ? deformer_->factorizations() : 0) +
         (previous_ ? previous_->factorizations() : 0) + flatten_->factorizations();
}

}  // namespace aniso
