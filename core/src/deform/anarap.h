// The AnARAP solver: local/global iterations (METHOD §5) on a fixed rest mesh,
// with the isotropic ARAP of Sorkine & Alexa as the case T = I.
//
//   E(v', R) = sum_i sum_{j in N(i)} w_ij || e'_ij - R_i T_ij e_ij ||^2
//
// T_ij, the target map of the spoke ij, is the mean of the maps of the
// triangle sides the spoke lies on (SideTargets, element_targets.h: each
// triangle's own frame). METHOD §5 writes one T_i per fan, built on the vertex
// normal; on a vertex of a crease (the spool's rims, where every vertex of its
// flanges and core lies) that normal averages the faces' normals, the
// projected direction tilts between them, and the flanges fold (Fig. 9: height
// x2.22 for su = 1.5, rims worse than isotropic ARAP). Where a fan's faces
// share one map, T_ij = T_i: the two agree.
//
// Local step: R_i = argmax_{R in SO(3)} tr(R^T S_i), S_i = sum_j w_ij e'_ij (P_ij e_ij)^T
// with P_ij the polar positive part of T_ij, found by iterative rotation
// extraction warm-started from the previous rotation: Newton steps on SO(3)
// (quadratic convergence; the fit stops after a step under 0.1 rad that
// raised tr(R^T S), usually the first, and the next iteration goes on from
// there: the fixed point is the same, and the energy never rises), with the scaled-gradient
// step of Müller et al. 2016 ("A robust method to extract the rotational part
// of deformations") where Newton's Hessian is not definite. No SVD, no sign
// fix-up, robust for flat (rank-2) fans.
// Global step: L v' = b, b_i = sum_j (w_ij / 2)(R_i + R_j) T_ij (v_i - v_j),
// solved with the shared prefactored LaplacianSolver.
// Spokes-and-rims: every triangle's three edges count in each of its corners'
// cells, each edge with its side's map; the same L results, with b assembled
// per triangle.
//
// Rotational targets (T = Q P with Q a rotation) have two schemes
// (METHOD §5):
// - the paper's: R_i is fitted to the P's only, so each step turns the fans by
//   Q once more; run a stated number of steps (no fixed point);
// - coupled rotations (beyond the paper): R_i is fitted to the whole T's,
//   as ARAP would, but neighbouring R_i are tied together by
//     E_s = sum_i sum_{j in N(i)} k_ij || R_i - R_j ||_F^2,
//   k_ij = alpha (|tr C_i| / deg_i + |tr C_j| / deg_j) / 2 (the fans' size),
//   so that ARAP cannot absorb a region's rotation without paying at its
//   border: the energy has a minimum, the iterations a fixed point. The
//   local step is then a Gauss-Seidel sweep,
//     R_i = argmax tr(R^T (sum_j w_ij e'_ij (T_ij e_ij)^T + 2 sum_j k_ij R_j)),
//   each update raises tr(R^T S) given the others, so the energy never increases.
#pragma once

#include <functional>
#include <vector>

#include <Eigen/Geometry>

#include "anisoform/deform_request.h"
#include "anisoform/laplacian.h"
#include "geometry/laplacian_solver.h"
#include "anisoform/mesh.h"
#include "deform/element_targets.h"

namespace aniso {

class AnArapSolver {
 public:
  AnArapSolver(const Mesh& rest, const CotanWeights& weights,
                 const Eigen::SparseMatrix<double>& laplacian, ArapElements elements);

  // Per-side targets (SideTargets in element_targets.h: triangle t's three
  // maps, for its sides 3t, 3t + 1, 3t + 2). Keeps the current rotations
  // (warm start). Without `polar_targets` their polar parts are not made
  // (for coupled rotations, which never read them: the decompositions were
  // a quarter of a shear's live preview at 200k vertices in WASM).
  void set_targets(const SideTargets& T, bool polar_targets = true);
  // Every side's map the identity (ARAP): the targets are the rest edges.
  void set_identity_targets();
  // Scale-only targets (TransformSpec::scales_only, the same amounts on every
  // side) are affine in the amounts: a side of weight w in a frame (u, v, n)
  // maps e to e + w (su - 1) u (u.e) + w (sv - 1) v (v.e) (transforms.h; the
  // normal's sn moves no edge lying in the surface, validate_request refuses
  // it), so per spoke (or side) t = e + (su - 1) U + (sv - 1) V.
  // (A triangle square to the direction, Frames::along_normal, adds its
  // whole in-plane edge to V and none to U: it is scaled by sv only.)
  // set_scale_steps keeps U and V, from each triangle's u and v (#F by 3) and
  // each side's weight (3 #F, side_weights); set_scale_targets(su, sv) then
  // sets the targets of any su, sv from the two: one pass over the spokes.
  // For frames used for one value only, set_scale_targets(u, v, weight, su,
  // sv) sets the same targets without keeping U and V: a copy of the rest
  // edges and a pass over the sides of positive weight.
  void set_scale_steps(const Frames& frames, const Eigen::VectorXd& side_weight);
  void set_scale_targets(double su, double sv);
  void set_scale_targets(const Frames& frames, const Eigen::VectorXd& side_weight, double su,
                         double sv);
  // Shear-only targets (TransformSpec::shears_only) are linear in the shear
  // h: a side maps e to e + w s h u (v.e), v turned to `orientation`
  // (shear_orientation, element_targets.h) and s its triangle's share
  // (shear_share; 0 on a triangle square to the direction,
  // Frames::along_normal), so t = e + h S per spoke (or side). As the scale
  // steps: set_shear_steps keeps S, set_shear_targets(h) sets the targets
  // from it, the other set_shear_targets directly. Only for coupled
  // rotations: the polar targets are not made.
  void set_shear_steps(const Frames& frames, const Eigen::VectorXd& side_weight, const Eigen::Vector3d& orientation);
  void set_shear_targets(double h);
  void set_shear_targets(const Frames& frames, const Eigen::VectorXd& side_weight, const Eigen::Vector3d& orientation,
                         double h);
  // Rotation-only targets (TransformSpec::rotates_only): a side of weight w
  // turns e about its triangle's `axis` row (#F by 3, unit) by w `radians`
  // (Rodrigues: e + sin (a x e) + (1 - cos) (a (a.e) - e)), directly, the
  // sine and cosine once per weight. Only for coupled rotations: the polar
  // targets are not made.
  void set_rotation_targets(const Positions& axis, const Eigen::VectorXd& side_weight, double radians);
  // Twist-only targets (TransformSpec::twists_only): each side's edge mapped
  // by the twist's Jacobian at its midpoint (twist_jacobian, transforms.h,
  // once per side), without the frame's C I C^T and a map per side kept.
  // `frames_u` (#F by 3) only sizes the visit. Only for coupled rotations:
  // the polar targets are not made.
  void set_twist_targets(const Positions& frames_u, const Eigen::VectorXd& side_weight, const TransformSpec& spec);
  // alpha > 0: coupled rotations (see above); 0: the paper's scheme.
  void set_rotation_coupling(double alpha) { coupling_ = alpha; }
  void reset_rotations();
  // A live preview's work once, its results thrown away: scale targets of
  // amount 1 from `frames` (#F by 3 u and v) on every side (the rest edges
  // again, bit for bit), the scale steps, and a local step, right-hand side
  // and solve at the rest pose (the rotations reset after). Run in the
  // background preparation, so that a drag's first preview finds its memory
  // touched and, in WASM, its code compiled by the optimizing tier
  // (Deformer::prepare_step).
  void warm_up(const LaplacianSolver& solver, const Frames& frames);

  // Fits the rotations to `V` and returns the energy E(V, R) with the new R.
  double local_step(const Positions& V);
  // Assembles b for the current rotations (#V by 3).
  void global_rhs(Positions& b) const;

  // Runs up to `max_iterations` local/global iterations from V (in/out);
  // stops when the relative energy change falls below `tolerance` (or never,
  // when tolerance < 0). Returns iterations run; history gets E after each
  // iteration's local step (E(V_k, R_k), non-increasing for symmetric T).
  // Without `final_energy`, the local step after the last solve is skipped
  // (V is the same): the last entry is then the energy before that solve.
  // `acceleration` (for converging iterations only, not the paper's rotation
  // steps): L-BFGS on E (run_lbfgs; Anderson with coupled rotations, see
  // run()) or Anderson acceleration of the positions (anderson.h); either
  // keeps a step only if it lowers the energy, so the history still never
  // increases.
  // `on_iteration(done)` is called after each iteration (progress).
  int run(const LaplacianSolver& solver, Positions& V, int max_iterations, double tolerance,
          std::vector<double>& history, bool final_energy = true,
          Acceleration acceleration = Acceleration::None,
          const std::function<void(int)>& on_iteration = nullptr);
  // Whether the last run() stopped on the tolerance test: a run that met it
  // on its last allowed iteration converged too, though it used them all.
  bool settled() const { return settled_; }

 private:
  // Whether the iterations stop after an iteration from `previous` to
  // `energy` (the relative-change test; small_steps counts the small
  // changes in a row).
  // Sets settled_ when it says stop.
  bool converged(double previous, double energy, double tolerance, bool accelerated, int& small_steps);
  // local_step(V) with each cell's fit starting from start[i] instead of
  // the current rotation (which it overwrites).
  double local_step(const Positions& V, const std::vector<Eigen::Quaterniond>& start);
  // run() with Acceleration::Lbfgs (anarap_lbfgs.cpp says how and why).
  int run_lbfgs(const LaplacianSolver& solver, Positions& V, int max_iterations, double tolerance,
                std::vector<double>& history, bool final_energy, const std::function<void(int)>& on_iteration);
  // run() with coupled rotations, Anderson accelerated: the rotations are
  // the iteration's state (the positions are L^-1 b(R)), so they are mixed.
  int run_coupled(const LaplacianSolver& solver, Positions& V, int max_iterations, double tolerance,
                  std::vector<double>& history, bool final_energy, const std::function<void(int)>& on_iteration);
  // g = L V - b at the V of the last local step, for the current rotations'
  // b (written to `b`), zero on the solver's pinned rows: E's gradient over
  // the free vertices, up to a constant factor (the global step solves g = 0).
  void energy_gradient(const std::vector<char>& pinned, Positions& b, Positions& g) const;
  // S_i = sum w e' t^T (full targets) and with the polar targets, per cell.
  // The polar covariance only `with_polar`.
  void update_target_energy();
  void covariance_spokes(const Positions& V, bool with_polar, Eigen::VectorXd& edge_energy);
  void covariance_spokes_rims(const Positions& V, bool with_polar, Eigen::VectorXd& edge_energy);
  // The coupled local step's sweep; returns the energy after it (the cells'
  // and the coupling's).
  double coupled_rotations();
  // Calls visit(row, side) for each side of positive weight and each target
  // row it adds to (its spokes, or itself with rims): `side` gives the
  // side's steps (w (u.e) u, w (v.e) v, w (v.e) u) for its share e of the
  // row's rest edge. With `along_normal` (Frames::along_normal) a side of a
  // triangle square to the direction says so (SideShare::across_only).
  template <typename Visit>
  void visit_side_shares(const Positions& u, const Positions& v, const Eigen::VectorXd& side_weight,
                         Visit&& visit, const std::vector<char>* along_normal = nullptr) const;
  // `step` zeroed in the layout of the targets; the targets set to the rest edges.
  Positions& zeroed_step(Positions& step) const;
  Positions& rest_targets();
  void scale_targets_set();  // after any set_*_targets but set_targets

  const Mesh& rest_;
  const CotanWeights& weights_;
  ArapElements elements_;
  int n_;
  bool settled_ = false;
  // Spokes in CSR form: neighbours, weights, rest edge vectors e_ij = v_j - v_i.
  std::vector<int> offsets_, neighbors_;
  std::vector<double> spoke_weight_;
  Positions spoke_edge_;
  // Spokes: the spokes each triangle side lies on (CSR over sides), 1 / the
  // number of sides per spoke (0: on none), and the target edges
  // t_ij = T_ij e_ij and P_ij e_ij, T_ij the mean of its sides' maps (the
  // P_ij e_ij made by set_targets, and read only while polar_differs_).
  std::vector<int> side_spoke_offsets_, side_spokes_;
  std::vector<double> spoke_share_;
  Positions spoke_target_, spoke_polar_;
  // Spokes and rims: each triangle side's rest edge (3t + k, opposite corner
  // k, from corner k+1 to k+2) and its targets T e and P e.
  Positions side_edge_, side_target_, side_polar_;
  Positions scale_step_[2];  // set_scale_steps: U, V in the layout of the targets
  Positions shear_step_;     // set_shear_steps: S, likewise
  // sum w |t|^2 per cell: depends on the targets only, computed once per target set.
  Eigen::VectorXd target_energy_;
  // Spokes: sum_j w_ij t_ij per cell, with target_energy_ (global_rhs's R_i part).
  Positions target_sum_;
  std::vector<Eigen::Quaterniond> rotation_;
  std::vector<Eigen::Matrix3d> rotation_matrices_;  // R_i as matrices, after each local step
  // Scratch of the local step, kept to avoid reallocating every iteration.
  std::vector<Eigen::Matrix3d> target_covariance_, polar_covariance_;
  Eigen::VectorXd edge_energy_;
  // L V at the V of the last local step, summed from the deformed edges it
  // reads anyway (energy_gradient's; a pass of its own over every spoke was
  // a thirtieth of a 200k commit in WASM).
  Positions laplacian_v_;
  bool polar_differs_ = false;  // some target has a rotational part (P != T)
  double coupling_ = 0.0;                // alpha; 0: the paper's scheme
  std::vector<double> spoke_coupling_;   // k_ij / alpha per spoke
  double energy_scale_ = 0.0;  // sum of |tr C_i|: the size of the rest fans
};

}  // namespace aniso
