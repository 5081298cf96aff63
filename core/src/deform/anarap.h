// The AnARAP solver: local/global iterations (METHOD §5) on a fixed rest mesh,
// with the isotropic ARAP of Sorkine & Alexa as the case T = I.
//
//   E(v', R) = sum_i sum_{j in N(i)} w_ij || e'_ij - R_i T_i e_ij ||^2
//
// Local step: R_i = argmax_{R in SO(3)} tr(R^T S_i), S_i = sum_j w_ij e'_ij (P_i e_ij)^T
// with P_i the polar positive part of T_i, found by iterative rotation
// extraction warm-started from the previous rotation: Newton steps on SO(3)
// (quadratic convergence, usually one or two steps), with the scaled-gradient
// step of Müller et al. 2016 ("A robust method to extract the rotational part
// of deformations") where Newton's Hessian is not definite. No SVD, no sign
// fix-up, robust for flat (rank-2) fans.
// Global step: L v' = b, b_i = sum_j (w_ij / 2)(R_i T_i + R_j T_j)(v_i - v_j),
// solved with the shared prefactored LaplacianSolver.
// Spokes-and-rims: every triangle's three edges count in each of its corners'
// cells; the same L results, with b assembled per triangle.
//
// Rotational targets (T_i = Q_i P_i with Q_i a rotation) have two schemes
// (METHOD §5):
// - the paper's: R_i is fitted to P_i only, so each step turns the fans by
//   Q_i once more; run a stated number of steps (no fixed point);
// - coupled rotations (beyond the paper): R_i is fitted to the whole T_i,
//   as ARAP would, but neighbouring R_i are tied together by
//     E_s = sum_i sum_{j in N(i)} k_ij || R_i - R_j ||_F^2,
//   k_ij = alpha (|tr C_i| / deg_i + |tr C_j| / deg_j) / 2 (the fans' size),
//   so that ARAP cannot absorb a region's rotation without paying at its
//   border: the energy has a minimum, the iterations a fixed point. The
//   local step is then a Gauss-Seidel sweep,
//     R_i = argmax tr(R^T (A_i T_i^T + 2 sum_j k_ij R_j)),
//   each update exact given the others, so the energy never increases.
#pragma once

#include <vector>

#include <Eigen/Geometry>

#include "anisoform/deform_request.h"
#include "anisoform/laplacian.h"
#include "geometry/laplacian_solver.h"
#include "anisoform/mesh.h"

namespace aniso {

class AnArapSolver {
 public:
  AnArapSolver(const Mesh& rest, const CotanWeights& weights,
                 const Eigen::SparseMatrix<double>& laplacian, ArapElements elements);

  // Per-vertex targets (#V). Keeps the current rotations (warm start).
  void set_targets(const std::vector<Eigen::Matrix3d>& T);
  // alpha > 0: coupled rotations (see above); 0: the paper's scheme.
  void set_rotation_coupling(double alpha) { coupling_ = alpha; }
  void reset_rotations();

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
  // `accelerate`: Anderson acceleration of the positions (anderson.h), each
  // proposal kept only if it lowers the energy, so the history still never
  // increases; for converging iterations only (not the paper's rotation steps).
  int run(const LaplacianSolver& solver, Positions& V, int max_iterations, double tolerance,
          std::vector<double>& history, bool final_energy = true, bool accelerate = false);

 private:
  void covariance_spokes(const Positions& V, std::vector<Eigen::Matrix3d>& A,
                         Eigen::VectorXd& edge_energy) const;
  void covariance_spokes_rims(const Positions& V, std::vector<Eigen::Matrix3d>& A,
                              Eigen::VectorXd& edge_energy) const;
  // The coupled local step's sweep; returns E_s after it.
  double coupled_rotations(const std::vector<Eigen::Matrix3d>& A);

  const Mesh& rest_;
  const CotanWeights& weights_;
  ArapElements elements_;
  int n_;
  // Spokes in CSR form: neighbours, weights, rest edge vectors e_ij = v_j - v_i.
  std::vector<int> offsets_, neighbors_;
  std::vector<double> spoke_weight_;
  Positions spoke_edge_;
  Positions weighted_edge_sum_;         // g_i = sum_j w_ij e_ij
  std::vector<Eigen::Matrix3d> rest_covariance_;  // C_i = sum w e e^T (for the energy)
  std::vector<Eigen::Matrix3d> T_, P_, B_;        // targets, their polar parts, R_i T_i
  // tr(B_i^T B_i C_i) = tr(T_i^T T_i C_i): R_i is orthonormal, so this part of
  // the energy depends on the targets only and is computed once per target set.
  Eigen::VectorXd target_energy_;
  std::vector<Eigen::Quaterniond> rotation_;
  // Scratch of the local step, kept to avoid reallocating every iteration.
  std::vector<Eigen::Matrix3d> covariance_;
  Eigen::VectorXd edge_energy_;
  bool symmetric_targets_ = true;
  double coupling_ = 0.0;                // alpha; 0: the paper's scheme
  std::vector<double> spoke_coupling_;   // k_ij / alpha per spoke
  std::vector<Eigen::Matrix3d> rotation_matrices_;  // scratch of the coupled sweep
  double energy_scale_ = 0.0;  // sum of |tr C_i|: the size of the rest fans
};

}  // namespace aniso
