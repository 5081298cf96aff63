// The defaults of an edit and a flattening that depend on the mesh (op.h):
// the one place they are decided, for the Session and so for every host.
#include <algorithm>

#include "anisoform/error.h"
#include "anisoform/op.h"
#include "anisoform/transforms.h"

namespace aniso {

Eigen::Vector3d longest_axis(const BoundingBox& box) {
  const Eigen::Vector3d extent = box.max - box.min;
  int axis = 0;
  for (int k = 1; k < 3; ++k) {
    if (extent[k] > extent[axis]) axis = k;
  }
  return Eigen::Vector3d::Unit(axis);
}

ModelUnitGuess guess_model_unit(const BoundingBox& box) {
  const double largest = (box.max - box.min).maxCoeff();
  if (!(largest >= 5.0)) return {"m", 1000.0, largest};  // an empty box (NaN) too
  if (largest < 500.0) return {"cm", 10.0, largest};
  return {"mm", 1.0, largest};
}

namespace {

// ARAP with handles in the modelling sense (Sorkine & Alexa): the fully
// selected vertices are the handle and move with the drag, the soft border
// deforms as rigidly as possible, the unselected rest is pinned.
constexpr double kHandleWeight = 0.999;

void arap_handles_from_selection(const Eigen::VectorXd& weights, DeformRequest& request) {
  // Nothing selected: no handle, so nothing moves, as with the other methods
  // (an empty selection used to make every vertex a handle: the whole mesh
  // moved while the CLI said it was left unchanged). A host that means the
  // whole mesh selects it (the web app's empty selection is "all").
  if (!(weights.array() > 0.0).any()) return;
  for (Eigen::Index i = 0; i < weights.size(); ++i) {
    if (weights[i] >= kHandleWeight) request.handles.push_back(static_cast<int>(i));
  }
}

// Without pins, what holds the mesh while the handles move is the unselected
// rest (weight 0), whether the handles came from the selection or were given:
// given handles with no pins used to leave every other vertex free, and the
// whole mesh followed the handles rigidly whatever was selected.
void arap_pins_from_selection(const Eigen::VectorXd& weights, DeformRequest& request, bool handles_given) {
  if (!request.pins.empty() || request.handles.empty()) return;
  const Eigen::Index n = weights.size();
  std::vector<char> handle(static_cast<std::size_t>(n), 0);
  for (const int h : request.handles) {
    if (h >= 0 && h < n) handle[static_cast<std::size_t>(h)] = 1;  // a bad index is the solve's to refuse
  }
  Eigen::Index free = 0;
  for (Eigen::Index i = 0; i < n; ++i) {
    if (handle[static_cast<std::size_t>(i)]) continue;
    if (weights[i] == 0.0) request.pins.push_back(static_cast<int>(i));
    else ++free;
  }
  // Given handles, a move, and the rest all selected: nothing holds the mesh,
  // and the move is a rigid translation of all of it, the handles' shape
  // change nowhere (as a whole-mesh rotation with AnARAP, refused too).
  if (handles_given && request.pins.empty() && free > 0 && !request.handle_offset.isZero(0.0)) {
    fail(ErrorCode::BadParameter,
         "ARAP holds the mesh by its pins or, with none given, by the unselected vertices: with everything but the "
         "handles selected and no pins, nothing holds it, and the move is a rigid translation of the whole mesh. "
         "Select the part that may bend (the rest holds), or give pins");
  }
}

}  // namespace

DeformRequest resolve_edit(const DeformOp& edit, const Positions& rest, const BoundingBox& loaded_box,
                           const Eigen::VectorXd& weights) {
  DeformRequest request = edit.request;
  request.selection = weights;
  if (!edit.direction_given) {
    request.direction = DirectionSource();
    request.direction.vector = longest_axis(loaded_box);
  }
  if (request.transform.twist && !edit.twist_origin_given) {
    request.transform.twist_origin = default_twist_origin(rest, weights, request.transform.twist_axis);
  }
  if (request.method == Method::Arap) {
    const bool handles_given = !request.handles.empty();
    if (!handles_given) arap_handles_from_selection(weights, request);
    arap_pins_from_selection(weights, request, handles_given);
  }
  if (edit.preview) {
    request.max_iterations = std::min(request.max_iterations, kPreviewIterations);
    request.final_energy = false;
    request.preview = true;
  }
  return request;
}

std::string unchanged_reason(const DeformRequest& resolved, const std::string& selection) {
  const Eigen::VectorXd& weights = resolved.selection;
  const bool selected = (weights.array() > 0.0).any();
  // ARAP moves its handles, given or taken from the selection (resolve_edit);
  // the other methods the selected vertices.
  if (resolved.method == Method::Arap) {
    if (!resolved.handles.empty()) return "";
    return selected ? "ARAP's handles are the vertices selected with weight 1; " + selection +
                          " has none: the mesh is left unchanged (select the part to move fully, or give handles)"
                    : selection + " holds no vertex: the mesh is left unchanged";
  }
  if (!selected) return selection + " holds no vertex: the mesh is left unchanged";
  // The surface methods move only selected vertices; with all of them held,
  // the edit has nothing to move (ARAP's handles move although pinned).
  std::vector<char> pinned(static_cast<std::size_t>(weights.size()), 0);
  for (const int p : resolved.pins) {
    if (p >= 0 && p < weights.size()) pinned[static_cast<std::size_t>(p)] = 1;  // a bad index is the solve's to refuse
  }
  for (Eigen::Index i = 0; i < weights.size(); ++i) {
    if (weights[i] > 0.0 && !pinned[static_cast<std::size_t>(i)]) return "";
  }
  return "every selected vertex is pinned: the mesh is left unchanged";
}

SessionFlatten resolve_flatten(const SessionFlatten& request, const Positions& positions, const Triangles& faces) {
  SessionFlatten out = request;
  if (!out.direction_given) {
    out.directions = FlattenDirections();
    out.directions.global = longest_axis(shape_bounding_box(positions, faces));
    out.direction_given = true;
  }
  return out;
}

}  // namespace aniso
