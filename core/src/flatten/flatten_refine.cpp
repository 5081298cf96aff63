// The stretch refinement: after the local/global iterations, the pattern is
// moved to minimise the error the flattening is judged by (METHOD §8: the
// achieved stretch along and across the wanted direction against su and sv),
// not the ARAP energy, which also penalises shear and spreads the unavoidable
// error differently (on a nearly developable panel the uniform baseline beat
// it on that error).
//
// Per triangle t with 3D area A_t, Ju = J cu and Jv = J cv its images of the
// wanted direction and of the one across (J: chart -> plane):
//   E_t = A_t [ rho(|Ju|/su - 1) + rho(|Jv|/sv - 1)
//               + kAreaWeight rho(det J / (su sv) - 1) + barrier(det J / (su sv)) ],
// rho(r) = sqrt(r^2 + d^2) - d a smoothed |r|, so that the sum is the reported
// mean errors (divided by the total area) to within d; the area term keeps the
// shear the error does not see from collapsing triangles, and the barrier
// (zero above kBarrierStart of the wanted area, for every triangle and every
// start) keeps every triangle's area positive and pushes back the ones a
// start map squeezed.
//
// Minimised by projected Newton (Teran et al. 2005; as in the SLIM line of
// parameterization methods): each triangle's Hessian in (Ju, Jv) is made
// positive semidefinite by clamping its eigenvalues at 0, the sum (plus a
// small multiple of the chart Laplacian, which removes the rotation the
// energy does not see) is factored, and a backtracking line search inside
// the fold guard's step bound takes the step: the energy (of the stage)
// falls at every iteration and no triangle ever folds. Near the optimum a
// few conjugate gradient iterations on the Hessian as it is correct each
// step for the clamped curvature (truncated_newton_direction), and a full
// step that lowers the energy is tried longer. Why not a first-order method: the
// smoothed kink has a curvature of 1/d = 100 where a triangle meets its
// target and the barrier grows without bound near it, so the problem is
// badly conditioned exactly where it ends. Preconditioned L-BFGS needed 971
// iterations on the hand and about 2,500 on spothead to converge (500 was the
// cap); Newton's steps follow that curvature. And the smoothing is wider
// in the first stages (kCoarseSmoothing), which a far from developable
// patch crosses in fewer, larger steps.
#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <memory>
#include <utility>

#include <Eigen/Cholesky>
#include <Eigen/LU>

#include "base/positive_part4.h"
#include "flatten/flatten_pipeline.h"
#include "geometry/supernodal_ldlt.h"

namespace aniso {

namespace {

constexpr double kSmoothing = 1e-2;     // d in rho: the error's kink, smoothed
// The refinement first minimises the energy with rho smoothed more, each
// stage from the last one's result and to kCoarseTolerance (or the looser
// tolerance asked for), and ends with d = kSmoothing, the energy it is judged
// by, to the tolerance asked for (continuation, as for other smoothed
// absolute values). With d = 0.01 from the start, a patch far from
// developable crawls: each kink a triangle's error crosses bends the energy
// at a scale of d, and the steps meet them one by one (stanford-bunny: 1,035
// iterations, local/global ones included, to converge). A wider kink is met
// in fewer, larger steps, and the last stage starts near its own minimum.
// Iterations to converge, local/global ones included, without / with the
// stages {0.1, 0.03} to 3e-5: bunny 1,035 / 544, demosthenes 310 / 253, hand
// 122 / 159, spothead 201 / 191, torso 48 / 53; and they end at lower errors
// where there are many minima (compression error: hand 0.202 / 0.190,
// spothead 0.199 / 0.187; the bunny 0.197 / 0.198; the torso 0.0081 either
// way). The coarse stages to 1e-5: bunny 510, spothead 330, hand 157,
// demosthenes 265; to 1e-4: 543, 186, 194, 261; to 1e-6: the bunny 621.
// Stages {0.05}: bunny 644; {0.1, 0.04, 0.02}: 514.
constexpr double kCoarseSmoothing[] = {0.1, 0.03};
constexpr double kCoarseTolerance = 3e-5;
// Each stage's share of the refinement's time, for its progress bar
// (refine_stage_outlook): the coarse stages', then the final one's. Measured
// natively (CLI, --compress 0.8): the bunny 0.69 / 0.10 / 0.21, demosthenes
// 0.66 / 0.19 / 0.15, spothead 0.68 / 0.06 / 0.26, the hand 0.52 / 0.18 /
// 0.31, the hemisphere 0.37 / 0.32 / 0.31.
constexpr double kCoarseShares[] = {0.6, 0.15};
constexpr double kFinalShare = 0.25;
static_assert(std::size(kCoarseShares) == std::size(kCoarseSmoothing), "a share per coarse stage");
constexpr double kAreaWeight = 0.25;    // the area error's share of the energy
// Area ratio below which the barrier acts. The errors measure the images of
// two directions, not the angle between them: a triangle sheared nearly flat
// can meet both lengths, and on a nearly closed patch the refinement took
// that way out (with the barrier at 0.1 of the wanted area: 35 % of the
// cube_no_bottom pattern's area, 52 % of the hand's, 34 % of demosthenes'
// below a tenth of its wanted area). At 0.3 none is, the developable
// patches keep their errors (torso compression error 0.0081 either way,
// hemisphere 0.025) and the others stay far ahead of the baseline.
constexpr double kBarrierStart = 0.3;
// Below this energy every triangle meets its targets to about 1e-6 (rho is
// r^2 / 2d near 0): the map is exact, and relative changes of an energy
// falling geometrically towards 0 say nothing more.
constexpr double kExactEnergy = 1e-14;
constexpr double kArmijo = 1e-4;        // sufficient decrease of the line search
constexpr int kMaxHalvings = 40;
// Relative energy changes below the tolerance this many times in a row end
// the iterations (also when Newton's predicted decrease is below it).
constexpr int kRefineQuietSteps = 2;
// A stage also ends when its last kProgressWindow steps together lowered its
// energy by less than kProgressWindow * kSlowProgress of it, whatever the
// tolerance. On patches far from developable the last stage otherwise
// crawled on to the tolerance, each step meeting a few more kinks, for
// errors that no longer changed where they are shown: the koala's head
// (30k vertices) took 249 iterations with it and 125 now, compression /
// cross error 0.01633 / 0.00923 then, 0.01648 / 0.00927 now; the bunny 564
// -> 315 (0.1984 / 0.1185 -> 0.1991 / 0.1190), demosthenes 249 -> 185
// (0.0959 / 0.2586 -> 0.0957 / 0.2593), spothead 191 -> 168, the hand 156
// -> 138 (errors within 0.3 %); the torso, hemisphere, cube and Nefertiti
// end as before. (Measured then; the Hessians' positive parts by Jacobi
// rotations since, base/positive_part4.h, differ from Eigen's in the last
// bits and move the counts a little: bunny 318, demosthenes 182, the hand
// 151, the cube 61.) The coarse stages end by their tolerance first. A rate of
// 1e-4 in the coarse stages too saved a tenth more on the bunny, spothead
// and demosthenes for up to 1 % more error; 3e-4, up to 2 %.
constexpr int kProgressWindow = 10;
constexpr double kSlowProgress = 3e-5;
// Steps cut short by the fold guard, with no real progress, after which the
// refinement gives up (stalled).
constexpr int kBlockedSteps = 10;
// Predicted relative decrease below which the steps use rho's own curvature
// (SmoothAbs::curvature), and the step length below which they go back to
// the majorizer. Iterations to converge, local/global ones included, with
// the switch at 1e-5 / 1e-4 / 1e-3 / never: hand 283 / 224 / 206 / 328,
// spothead 299 / 250 / 339 / 387, demosthenes 386 / 479 / 500+ / 500+, the
// cube 126 / 127 / 55 / 500+. Going back to the majorizer after short
// Newton steps: hand 269, spothead 235, demosthenes 456, cube 121.
constexpr double kNewtonFrom = 1e-4;
constexpr double kNewtonStepFloor = 0.25;
// The multiple of the chart Laplacian added to the Hessian: it fixes the
// rotation of each piece (which the energy does not see) and keeps the
// system definite where every term's curvature was clamped, small enough
// not to slow Newton down (the terms' curvature is up to 1/d = 100 times
// the Laplacian's). A failed factorization raises it kRegularizationGrowth
// times, up to kMaxRegularization.
constexpr double kRegularization = 1e-4;
constexpr double kRegularizationGrowth = 100.0;
constexpr double kMaxRegularization = 1e4;
// Conjugate gradient iterations on the Hessian as it is, per Newton step
// (truncated_newton_direction), and the relative residual that ends them.
// Iterations to converge, local/global ones included, with projected Newton
// alone / with 10 of them / with them and the doubling below: hand 269 / 146
// / 122, spothead 235 / 210 / 187, the cube 121 / 61 / 49, torso 68 / 55 / 48
// (with the unit-diagonal scaling of PatternHessian::factor, which moves the
// round-off: spothead 201, the cube 45).
constexpr int kPcgIterations = 10;
constexpr double kPcgResidual = 1e-2;
// A Newton step's conjugate gradients are preconditioned with the factored
// positive part of one of the kMaxLag iterations before it, when one is
// there, instead of its own: from one Newton step to the next it changes
// little, and the factorization is over half of a large patch's refinement
// (the bunny's: 58 %). Factorizations per refinement: the bunny 249 -> 205,
// demosthenes 168 -> 123, the koala head 173 -> 139; flattening in WASM:
// demosthenes 6.3 -> 4.4 s, the koala head 17.9 -> 14.2 s. A step that
// took more than kLaggedIterations of them has the next iteration factor
// its own. Majorized steps always do: conjugate gradients on their own
// system, preconditioned by an earlier one, took over 10 iterations.
constexpr int kMaxLag = 5;
constexpr int kLaggedIterations = 6;
// A full step that lowers the energy is doubled while that lowers it more,
// up to this many times its length (within the fold guard's bound): where
// the Hessian curves down, or its positive part overestimates the
// curvature, Newton's step falls short.
constexpr double kMaxStretch = 8.0;
// Pivots of the unit-diagonal Hessian at or below this are not positive;
// the identity multiples tried when one is (PatternHessian::factor).
constexpr double kPivotFloor = 1e-14;
constexpr double kFirstShift = 1e-12;
constexpr double kShiftGrowth = 100.0;
constexpr double kMaxShift = 1e-2;

// rho(r) = sqrt(r^2 + d^2) - d, with its derivatives.
struct SmoothAbs {
  double d;

  double value(double r) const { return std::sqrt(r * r + d * d) - d; }
  double slope(double r) const { return r / std::sqrt(r * r + d * d); }
  // The curvature Newton uses for rho at r: its own, d^2 / (r^2 + d^2)^(3/2),
  // or with `majorize` rho'(r) / r = 1 / sqrt(r^2 + d^2), the curvature of the
  // quadratic in r that touches rho at r and lies above it everywhere (rho is
  // concave in r^2). Far from the target rho is nearly |r|, its own curvature
  // nearly 0, and a Newton step from it overshoots by orders of magnitude; a
  // step that lowers the majorizing quadratic lowers rho too (iteratively
  // reweighted least squares), but the iteration converges only linearly.
  double curvature(double r, bool majorize) const {
    const double root = std::sqrt(r * r + d * d);
    if (majorize) return 1.0 / root;
    return d * d / (root * root * root);
  }
};

// barrier(x) = x0/x - 1 + ln(x/x0) below x0: zero with zero slope at x0,
// infinite at 0. +inf for x <= 0 (a folded triangle is never accepted).
double barrier(double x, double x0) {
  if (x >= x0) return 0.0;
  if (!(x > 0.0)) return std::numeric_limits<double>::infinity();
  return x0 / x - 1.0 + std::log(x / x0);
}
double barrier_slope(double x, double x0) {
  if (x >= x0) return 0.0;
  return -x0 / (x * x) + 1.0 / x;
}
double barrier_curvature(double x, double x0) {
  if (x >= x0) return 0.0;
  return 2.0 * x0 / (x * x * x) - 1.0 / (x * x);
}

using Vector4 = Eigen::Matrix<double, 4, 1>;
using Matrix4 = Eigen::Matrix<double, 4, 4>;
using Matrix6 = Eigen::Matrix<double, 6, 6>;

// One triangle's term (without its weight) as a function of z = (Ju, Jv) =
// (p, q), with the wanted stretches su, sv; with `g` and `H` also its
// gradient and Hessian in z (rho's curvature majorized or not, see
// SmoothAbs::curvature). +inf for a triangle with area <= 0.
double triangle_term(const SmoothAbs& rho, const Eigen::Vector2d& p, const Eigen::Vector2d& q, double su,
                     double sv, Vector4* g, Matrix4* H, bool majorize) {
  const double p_length = p.norm(), q_length = q.norm();
  const double along = p_length / su - 1.0, across = q_length / sv - 1.0;
  const double s = su * sv;
  const double area = (p.x() * q.y() - p.y() * q.x()) / s;
  const double b = barrier(area, kBarrierStart);
  if (!std::isfinite(b)) return std::numeric_limits<double>::infinity();
  const double value = rho.value(along) + rho.value(across) + kAreaWeight * rho.value(area - 1.0) + b;
  if (!g) return value;
  // d area / dz and its (constant) Hessian.
  const Vector4 area_gradient = Vector4(q.y(), -q.x(), -p.y(), p.x()) / s;
  const double area_slope = kAreaWeight * rho.slope(area - 1.0) + barrier_slope(area, kBarrierStart);
  *g = area_slope * area_gradient;
  if (H) {
    const double area_curvature =
        kAreaWeight * rho.curvature(area - 1.0, majorize) + barrier_curvature(area, kBarrierStart);
    *H = area_curvature * area_gradient * area_gradient.transpose();
    (*H)(0, 3) += area_slope / s;
    (*H)(3, 0) += area_slope / s;
    (*H)(1, 2) -= area_slope / s;
    (*H)(2, 1) -= area_slope / s;
  }
  // rho(|x| / scale - 1) for x = p (offset 0) and x = q (offset 2).
  const auto length_term = [&](const Eigen::Vector2d& x, double length, double scale, double r, int offset) {
    if (!(length > 0.0)) return;
    const Eigen::Vector2d n = x / length;
    const double slope = rho.slope(r);
    g->segment<2>(offset) += slope / scale * n;
    if (!H) return;
    const Eigen::Matrix2d nn = n * n.transpose();
    H->block<2, 2>(offset, offset) += rho.curvature(r, majorize) / (scale * scale) * nn +
                                      slope / (scale * length) * (Eigen::Matrix2d::Identity() - nn);
  };
  length_term(p, p_length, su, along, 0);
  length_term(q, q_length, sv, across, 2);
  return value;
}

// Each H with its negative eigenvalues set to 0. Where H is positive
// definite already, a Cholesky factorization shows it at a fraction of the
// eigen-decomposition's cost (the 30k-vertex koala head's flatten: 32.8 ->
// 31.5 s, the same iterations and errors); the others are decomposed two at
// a time (base/positive_part4.h).
void make_positive(std::vector<Matrix4>& H) {
  std::vector<std::size_t> indefinite;
  for (std::size_t i = 0; i < H.size(); ++i) {
    if (Eigen::LLT<Matrix4>(H[i]).info() != Eigen::Success) indefinite.push_back(i);
  }
  for (std::size_t k = 0; k < indefinite.size(); k += 2) {
    const std::size_t other = k + 1 < indefinite.size() ? indefinite[k + 1] : indefinite[k];
    positive_parts(H[indefinite[k]], H[other]);
  }
}

// Newton's linear system: the Hessian's lower triangle over the free
// coordinates (u and v of every vertex that is not pinned, interleaved), of
// one pattern for every iteration, so that the ordering and the symbolic
// factorization are done once.
class PatternHessian {
 public:
  PatternHessian(const Triangles& F, int num_vertices, const std::vector<int>& active,
               const std::vector<int>& pinned)
      : F_(F), active_(active), coordinate_(2 * static_cast<std::size_t>(num_vertices), 0) {
    for (const int v : pinned) coordinate_[2 * v] = coordinate_[2 * v + 1] = -1;
    int free = 0;
    for (int& c : coordinate_) c = c < 0 ? -1 : free++;
    std::vector<Eigen::Triplet<double>> entries;
    for (int c = 0; c < free; ++c) entries.emplace_back(c, c, 0.0);
    for (const int t : active_) {
      for (int a = 0; a < 6; ++a) {
        for (int b = 0; b < 6; ++b) {
          const int row = coordinate(t, a), col = coordinate(t, b);
          if (row >= 0 && col >= 0 && row >= col) entries.emplace_back(row, col, 0.0);
        }
      }
    }
    H_.resize(free, free);
    H_.setFromTriplets(entries.begin(), entries.end());
    slots_.assign(active_.size() * 36, -1);
    for (std::size_t index = 0; index < active_.size(); ++index) {
      for (int a = 0; a < 6; ++a) {
        for (int b = 0; b < 6; ++b) {
          const int row = coordinate(active_[index], a), col = coordinate(active_[index], b);
          if (row >= 0 && col >= 0 && row >= col) slots_[index * 36 + a * 6 + b] = slot(row, col);
        }
      }
    }
    if (free > 0) analysis_ = std::make_unique<SupernodalAnalysis>(H_);
  }

  void clear() { std::fill(H_.valuePtr(), H_.valuePtr() + H_.nonZeros(), 0.0); }

  void add(int index, const Matrix6& block) {
    const int* slot = &slots_[static_cast<std::size_t>(index) * 36];
    double* values = H_.valuePtr();
    for (int a = 0; a < 6; ++a) {
      for (int b = 0; b < 6; ++b) {
        if (slot[a * 6 + b] >= 0) values[slot[a * 6 + b]] += block(a, b);
      }
    }
  }

  // Factors the assembled matrix scaled to a unit diagonal, S H S with S =
  // diag(H)^-1/2, plus the smallest of 0, kFirstShift, 100 kFirstShift, ...
  // kMaxShift times the identity that gives positive pivots (Marquardt's
  // relative damping); false when none does. A triangle squeezed to a
  // millionth of its wanted area has a barrier curvature of ~1e17 along one
  // direction of its corners and the rest of theirs ~1: relative to it, the
  // other directions vanish in round-off, and a pivot floor relative to the
  // largest diagonal, or any multiple of the chart Laplacian, could not pass
  // it (the upper 40 % of human_woman from its Tutte start stopped there).
  bool factor() {
    if (!analysis_) return true;
    // The diagonal is each column's first stored entry (lower triangle).
    double* diagonal_value = H_.valuePtr();
    const int* column_start = H_.outerIndexPtr();
    scale_.resize(H_.rows());
    for (int col = 0; col < H_.outerSize(); ++col) {
      double& diagonal = diagonal_value[column_start[col]];
      if (!std::isfinite(diagonal) || diagonal < 0.0) return false;
      // A coordinate no active triangle reaches (only degenerate ones
      // around it) has an empty row: it stays where it is.
      if (diagonal == 0.0) diagonal = 1.0;
      scale_[col] = 1.0 / std::sqrt(diagonal);
    }
    for (int col = 0; col < H_.outerSize(); ++col) {
      for (Eigen::SparseMatrix<double>::InnerIterator it(H_, col); it; ++it) {
        it.valueRef() *= scale_[it.row()] * scale_[col];
      }
    }
    double shift = 0.0;
    while (true) {
      analysis_->factor(H_, kPivotFloor, ldlt_);
      if (ldlt_.bad_pivot < 0) break;
      const double next = shift > 0.0 ? kShiftGrowth * shift : kFirstShift;
      if (next > kMaxShift) return false;
      for (int col = 0; col < H_.outerSize(); ++col) diagonal_value[column_start[col]] += next - shift;
      shift = next;
    }
    inv_d_ = ldlt_.d.cwiseInverse();
    return true;
  }

  // H^-1 b for a #P by 2 b, as a #P by 2 map change (0 on the pinned
  // vertices, whose rows of b are not read).
  Eigen::MatrixXd solve(const Eigen::MatrixXd& b) const {
    Eigen::MatrixXd x = Eigen::MatrixXd::Zero(b.rows(), 2);
    if (!analysis_) return x;
    Eigen::VectorXd y(H_.rows());
    for (int v = 0; v < b.rows(); ++v) {
      for (int c = 0; c < 2; ++c) {
        const int i = coordinate_[2 * v + c];
        if (i >= 0) y[ldlt_.perm[i]] = scale_[i] * b(v, c);
      }
    }
    ldlt_.L.solve(inv_d_, y.data(), 1);
    for (int v = 0; v < b.rows(); ++v) {
      for (int c = 0; c < 2; ++c) {
        const int i = coordinate_[2 * v + c];
        if (i >= 0) x(v, c) = scale_[i] * y[ldlt_.perm[i]];
      }
    }
    return x;
  }

 private:
  // The free coordinate of corner a / 2's u (a even) or v (a odd) in triangle t, or -1.
  int coordinate(int t, int a) const { return coordinate_[2 * static_cast<std::size_t>(F_(t, a / 2)) + a % 2]; }

  int slot(int row, int col) const {
    const int* begin = H_.innerIndexPtr() + H_.outerIndexPtr()[col];
    const int* end = H_.innerIndexPtr() + H_.outerIndexPtr()[col + 1];
    return static_cast<int>(std::lower_bound(begin, end, row) - H_.innerIndexPtr());
  }

  const Triangles& F_;
  const std::vector<int>& active_;
  std::vector<int> coordinate_;  // per vertex and component: its free coordinate, or -1 (pinned)
  Eigen::SparseMatrix<double> H_;
  std::vector<int> slots_;       // per active triangle, its 6 by 6 block's places in H_ (-1: not stored)
  std::unique_ptr<SupernodalAnalysis> analysis_;
  SupernodalLdlt ldlt_;
  Eigen::VectorXd scale_;  // S: H^-1 = S (S H S)^-1 S
  Eigen::VectorXd inv_d_;
};

// Per triangle: Ju = sum_k alpha_k u_k and Jv = sum_k beta_k u_k (u_k its
// corners in the plane), with the weight A_t / (total area).
struct StretchTerms {
  Eigen::MatrixX3d alpha, beta;
  Eigen::VectorXd weight, su, sv;
  std::vector<int> active;  // non-degenerate triangles
  SmoothAbs rho{kSmoothing};
  mutable std::vector<Matrix4> hessians_;  // evaluate's scratch: each triangle's Hessian in (Ju, Jv)

  StretchTerms(const TriangleCharts& charts, const FlattenTargets& targets) {
    const int m = static_cast<int>(charts.area.size());
    alpha.setZero(m, 3);
    beta.setZero(m, 3);
    weight.setZero(m);
    su = targets.su;
    sv = targets.sv;
    const double total = charts.area.sum();
    for (int t = 0; t < m; ++t) {
      if (!(charts.area[t] > 0.0)) continue;
      Eigen::Matrix2d chart_edges;
      chart_edges << charts.corners(t, 2), charts.corners(t, 4),  //
          charts.corners(t, 3), charts.corners(t, 5);
      const Eigen::Matrix2d inverse = chart_edges.inverse();
      const Eigen::Vector2d cu = targets.direction.row(t).transpose();
      const Eigen::Vector2d a = inverse * cu;
      const Eigen::Vector2d b = inverse * Eigen::Vector2d(-cu.y(), cu.x());
      alpha.row(t) << -a.x() - a.y(), a.x(), a.y();
      beta.row(t) << -b.x() - b.y(), b.x(), b.y();
      weight[t] = charts.area[t] / total;
      active.push_back(t);
    }
  }

  // Ju and Jv of triangle t.
  std::pair<Eigen::Vector2d, Eigen::Vector2d> images(const Triangles& F, const Eigen::MatrixXd& uv, int t) const {
    Eigen::Vector2d p = Eigen::Vector2d::Zero(), q = Eigen::Vector2d::Zero();
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector2d corner = uv.row(F(t, k)).transpose();
      p += alpha(t, k) * corner;
      q += beta(t, k) * corner;
    }
    return {p, q};
  }

  // G^T Hz G for G = d(Ju, Jv) / d(u_0, v_0, u_1, v_1, u_2, v_2) of triangle
  // t: corner i's u (c = 0) or v (c = 1) enters Ju_c with alpha_i and Jv_c
  // with beta_i, and nothing else.
  Matrix6 corner_block(int t, const Matrix4& Hz) const {
    Matrix6 block;
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) {
        const double aa = alpha(t, i) * alpha(t, j), ab = alpha(t, i) * beta(t, j);
        const double ba = beta(t, i) * alpha(t, j), bb = beta(t, i) * beta(t, j);
        for (int a = 0; a < 2; ++a) {
          for (int b = 0; b < 2; ++b) {
            block(2 * i + a, 2 * j + b) =
                aa * Hz(a, b) + ab * Hz(a, 2 + b) + ba * Hz(2 + a, b) + bb * Hz(2 + a, 2 + b);
          }
        }
      }
    }
    return block;
  }

  // E(uv); with `gradient`, also dE/duv (#P by 2); with `hessian`, also
  // each triangle's positive part of the Hessian plus `regularization` times
  // its chart Laplacian block, added to it; with `exact`, also each active
  // triangle's Hessian in (Ju, Jv) as it is (not made positive), weighted,
  // plus the same regularization. Both need `gradient`.
  double evaluate(const Triangles& F, const Eigen::MatrixXd& uv, Eigen::MatrixXd* gradient,
                  PatternHessian* hessian, double regularization, bool majorize,
                  std::vector<Matrix4>* exact = nullptr) const {
    if (gradient) gradient->setZero(uv.rows(), 2);
    if (exact) exact->resize(active.size());
    if (hessian) hessians_.resize(active.size());
    double sum = 0.0;
    Vector4 g;
    Matrix4 H;
    for (std::size_t index = 0; index < active.size(); ++index) {
      const int t = active[index];
      const auto [p, q] = images(F, uv, t);
      const double term = triangle_term(rho, p, q, su[t], sv[t], gradient ? &g : nullptr,
                                        hessian || exact ? &H : nullptr, majorize);
      if (!std::isfinite(term)) return std::numeric_limits<double>::infinity();
      sum += weight[t] * term;
      if (!gradient) continue;
      for (int k = 0; k < 3; ++k) {
        gradient->row(F(t, k)) +=
            weight[t] * (alpha(t, k) * g.head<2>() + beta(t, k) * g.tail<2>()).transpose();
      }
      if (exact) (*exact)[index] = weight[t] * (H + regularization * Matrix4::Identity());
      if (hessian) hessians_[index] = H;
    }
    if (!hessian) return sum;
    // The positive parts, two at a time, then the blocks in the triangles'
    // order. The chart Laplacian's block is G^T G, G = d(Ju, Jv) /
    // d(corners): |Ju|^2 + |Jv|^2 is the Dirichlet energy.
    make_positive(hessians_);
    for (std::size_t index = 0; index < active.size(); ++index) {
      const int t = active[index];
      const Matrix4 Hz = weight[t] * (hessians_[index] + regularization * Matrix4::Identity());
      hessian->add(static_cast<int>(index), corner_block(t, Hz));
    }
    return sum;
  }

  // H v for the per-triangle Hessians `exact` (from evaluate): each
  // triangle's (Ju, Jv) of v, times its Hessian, spread back to its corners
  // as the gradient is.
  Eigen::MatrixXd hessian_times(const Triangles& F, const std::vector<Matrix4>& exact,
                                const Eigen::MatrixXd& v) const {
    Eigen::MatrixXd product = Eigen::MatrixXd::Zero(v.rows(), 2);
    for (std::size_t index = 0; index < active.size(); ++index) {
      const int t = active[index];
      const auto [p, q] = images(F, v, t);
      const Vector4 h = exact[index] * (Vector4() << p, q).finished();
      for (int k = 0; k < 3; ++k) {
        product.row(F(t, k)) += (alpha(t, k) * h.head<2>() + beta(t, k) * h.tail<2>()).transpose();
      }
    }
    return product;
  }

  double energy(const Triangles& F, const Eigen::MatrixXd& uv) const {
    return evaluate(F, uv, nullptr, nullptr, 0.0, false);
  }
};

double dot(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) { return a.cwiseProduct(b).sum(); }

// The Newton direction for the Hessian as it is (H, through `exact`), by
// conjugate gradients preconditioned with the positive part P of this
// iteration's Hessian or of a recent one's (factored in `system`), from 0:
// the first iterate is the preconditioned step -P^-1 g scaled to H's
// curvature along it; each further one adds what P gets wrong (the clamped
// negative curvature, the steps since P was made), in the directions it
// gets least right. Stops at a relative residual (in P's norm) of
// kPcgResidual, after kPcgIterations, or where H curves down along the
// search direction (then the iterate so far: conjugate gradients from 0
// give descent directions until then). Where H curves down at the first
// search direction, that direction itself. `used`: the iterations taken.
Eigen::MatrixXd truncated_newton_direction(const Triangles& F, const StretchTerms& terms,
                                           const std::vector<Matrix4>& exact, const PatternHessian& system,
                                           const std::vector<int>& pinned, const Eigen::MatrixXd& gradient,
                                           int& used) {
  Eigen::MatrixXd residual = -gradient;
  for (const int v : pinned) residual.row(v).setZero();
  Eigen::MatrixXd preconditioned = system.solve(residual);
  Eigen::MatrixXd search = preconditioned;
  Eigen::MatrixXd direction = Eigen::MatrixXd::Zero(gradient.rows(), 2);
  const double start = dot(residual, preconditioned);
  double current = start;
  used = 0;
  for (int k = 0; k < kPcgIterations; ++k) {
    used = k + 1;
    Eigen::MatrixXd curved = terms.hessian_times(F, exact, search);
    for (const int v : pinned) curved.row(v).setZero();
    const double curvature = dot(search, curved);
    if (!(curvature > 0.0)) return k == 0 ? search : direction;
    const double length = current / curvature;
    direction += length * search;
    residual -= length * curved;
    preconditioned = system.solve(residual);
    const double next = dot(residual, preconditioned);
    if (!(next > kPcgResidual * kPcgResidual * start)) break;
    search = preconditioned + (next / current) * search;
    current = next;
  }
  return direction;
}

// How a stage of the refinement ended.
enum class StageEnd { Converged, Stalled, Capped, Stopped };

// Projected Newton on `terms` at its current smoothing, from uv to a
// relative energy change of `tolerance`; counts its iterations on in
// report.iterations (at most `cap` in all) and, for the final stage
// (`history`), records its energies.
class NewtonStage {
 public:
  NewtonStage(const Triangles& F, const TriangleCharts& charts, const StretchTerms& terms,
              const std::vector<int>& pinned, PatternHessian& system, const ArapFlattenSettings& settings,
              int iterations_before, const RefineProgress& progress, StretchRefineReport& report)
      : F_(F), charts_(charts), terms_(terms), pinned_(pinned), system_(system), settings_(settings),
        iterations_before_(iterations_before), progress_(progress), report_(report),
        cap_(std::max(0, settings.max_iterations - iterations_before)) {}

  // `index`: the stage's, for progress (refine_stage_outlook's order).
  StageEnd run(int index, double tolerance, std::vector<double>* history, Eigen::MatrixXd& uv) {
    factored_ = false;  // the last stage's factorization is of another smoothing
    double energy = terms_.energy(F_, uv);
    if (history) history->push_back(energy);
    bool majorize = true;
    int quiet = 0, blocked = 0;
    std::vector<double> stage_energies{energy};  // its start, then after each step
    while (report_.iterations < cap_) {
      if (energy <= kExactEnergy) return StageEnd::Converged;
      // A majorized step solves with its own factored positive part; a
      // Newton step may precondition with a recent iteration's (kMaxLag).
      const bool refactor = majorize || !factored_ || lagged_ >= kMaxLag || slow_;
      if (refactor) system_.clear();
      terms_.evaluate(F_, uv, &gradient_, refactor ? &system_ : nullptr, regularization_, majorize,
                      majorize ? nullptr : &exact_);
      if (refactor) {
        factored_ = system_.factor();
        if (!factored_) {
          if (regularization_ * kRegularizationGrowth > kMaxRegularization) return StageEnd::Stalled;
          regularization_ *= kRegularizationGrowth;
          continue;
        }
        ++report_.factorizations;
        lagged_ = 0;
      } else {
        ++lagged_;
      }
      // Majorized steps minimise the majorizing quadratic made positive; Newton
      // steps go further, towards H's own minimum.
      int used = 0;
      const Eigen::MatrixXd direction =
          majorize ? Eigen::MatrixXd(system_.solve(-gradient_))
                   : truncated_newton_direction(F_, terms_, exact_, system_, pinned_, gradient_, used);
      slow_ = !refactor && used > kLaggedIterations;
      const double slope = dot(gradient_, direction);
      // Newton's predicted decrease, -slope / 2, below the tolerance: the
      // minimum is reached (also when the gradient vanishes to round-off).
      if (!(slope < 0.0) || -0.5 * slope <= tolerance * energy) return StageEnd::Converged;
      const double bound = fold_free_step_fraction(F_, charts_, uv, uv + direction);
      double step = std::min(1.0, bound);
      Eigen::MatrixXd candidate = uv + step * direction;
      double candidate_energy = terms_.energy(F_, candidate);
      int halvings = 0;
      while (!(candidate_energy <= energy + kArmijo * step * slope) && halvings < kMaxHalvings) {
        step *= 0.5;
        candidate = uv + step * direction;
        candidate_energy = terms_.energy(F_, candidate);
        ++halvings;
      }
      // A full step that lowered the energy: longer ones, while they lower it more.
      if (halvings == 0 && bound >= 1.0) {
        const double reach =
            kMaxStretch * fold_free_step_fraction(F_, charts_, uv, uv + kMaxStretch * direction);
        for (double longer = 2.0 * step; longer <= reach; longer *= 2.0) {
          Eigen::MatrixXd further = uv + longer * direction;
          const double further_energy = terms_.energy(F_, further);
          if (!(further_energy < candidate_energy)) break;
          candidate = std::move(further);
          candidate_energy = further_energy;
          step = longer;
        }
      }
      // No step lowers the energy along a descent direction: at the minimum,
      // to round-off, when the predicted decrease is below what double
      // precision resolves in the energy (a tolerance of 0 ends here); else
      // something (a near-degenerate triangle) blocks the descent.
      if (!(candidate_energy < energy)) {
        return -0.5 * slope <= kRoundOffDecrease * energy ? StageEnd::Converged : StageEnd::Stalled;
      }
      // Majorized steps until the predicted decrease is small (near a
      // minimum, where Newton's own curvature is the right one), and back to
      // them when a Newton step falls short (halved, or stopped by the fold
      // guard, to under kNewtonStepFloor).
      if (majorize && -0.5 * slope < kNewtonFrom * energy) {
        majorize = false;
      } else if (!majorize && step < kNewtonStepFloor) {
        majorize = true;
      }
      const double previous = energy;
      uv = std::move(candidate);
      energy = candidate_energy;
      ++report_.iterations;
      if (history) history->push_back(energy);
      if (progress_ && !progress_(index, iterations_before_ + report_.iterations, energy)) return StageEnd::Stopped;
      // A step the fold guard cut short says nothing about convergence (it
      // was small because a triangle is near zero area), but many in a row
      // mean such triangles block the descent.
      const bool small_change = small_decrease(previous, energy, tolerance);
      const bool cut_short = bound < 1.0;
      quiet = small_change && !cut_short ? quiet + 1 : 0;
      blocked = small_change && cut_short ? blocked + 1 : 0;
      if (quiet >= kRefineQuietSteps) return StageEnd::Converged;
      // Steps the guard held back are a stall, not slow progress: checked first.
      if (blocked >= kBlockedSteps) return StageEnd::Stalled;
      stage_energies.push_back(energy);
      if (stage_energies.size() > kProgressWindow) {
        const double before = stage_energies[stage_energies.size() - 1 - kProgressWindow];
        if (before - energy <= kProgressWindow * kSlowProgress * energy) return StageEnd::Converged;
      }
    }
    return StageEnd::Capped;
  }

 private:
  const Triangles& F_;
  const TriangleCharts& charts_;
  const StretchTerms& terms_;
  const std::vector<int>& pinned_;
  PatternHessian& system_;
  const ArapFlattenSettings& settings_;
  const int iterations_before_;
  const RefineProgress& progress_;
  StretchRefineReport& report_;
  const int cap_;
  // Raised when a factorization fails, and kept for the later stages (it is
  // about the patch, not the smoothing).
  double regularization_ = kRegularization;
  // Whether system_ holds a factorization of this stage, made how many
  // iterations ago, and whether the last Newton step preconditioned with an
  // earlier iteration's took more than kLaggedIterations (the next iteration
  // then factors its own).
  bool factored_ = false;
  int lagged_ = 0;
  bool slow_ = false;
  Eigen::MatrixXd gradient_;
  std::vector<Matrix4> exact_;
};

}  // namespace

StretchRefineReport refine_stretch(const FlattenPatch& patch, const TriangleCharts& charts,
                                   const FlattenTargets& targets, const std::vector<int>& pinned,
                                   const ArapFlattenSettings& settings, int iterations_before,
                                   const std::vector<Eigen::MatrixX2d>& starts, Eigen::MatrixX2d& uv_out,
                                   const RefineProgress& progress) {
  const Triangles& F = patch.mesh.F;
  StretchTerms terms(charts, targets);
  StretchRefineReport report;
  double energy = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < starts.size(); ++k) {
    if (count_folded(F, charts, starts[k]) > 0) continue;
    const double start_energy = terms.energy(F, starts[k]);
    if (start_energy < energy) {
      energy = start_energy;
      report.start = static_cast<int>(k);
    }
  }
  if (report.start < 0) return report;
  Eigen::MatrixXd uv = starts[report.start];
  PatternHessian system(F, static_cast<int>(uv.rows()), terms.active, pinned);
  NewtonStage stage(F, charts, terms, pinned, system, settings, iterations_before, progress, report);
  // A coarse stage that converged or stalled hands on to the next one.
  StageEnd end = StageEnd::Converged;
  const int coarse_stages = static_cast<int>(std::size(kCoarseSmoothing));
  for (int k = 0; k < coarse_stages; ++k) {
    terms.rho.d = kCoarseSmoothing[k];
    end = stage.run(k, std::max(settings.tolerance, kCoarseTolerance), nullptr, uv);
    if (end == StageEnd::Capped || end == StageEnd::Stopped) break;
  }
  report.coarse_iterations = report.iterations;
  terms.rho.d = kSmoothing;
  if (end == StageEnd::Capped || end == StageEnd::Stopped) {
    report.energy_history.push_back(terms.energy(F, uv));
  } else {
    end = stage.run(coarse_stages, settings.tolerance, &report.energy_history, uv);
  }
  report.converged = end == StageEnd::Converged;
  report.stalled = end == StageEnd::Stalled;
  report.energy = report.energy_history.back();
  uv_out = uv;
  return report;
}

std::vector<StagedProgress::Stage> refine_stage_outlook(double tolerance) {
  // A stage ends at its tolerance or where its steps gained less than
  // kSlowProgress each on average (kProgressWindow of them together),
  // whichever comes first; its changes come and go from step to step, so
  // the bar follows their mean over that window.
  std::vector<StagedProgress::Stage> stages;
  for (const double share : kCoarseShares) {
    stages.push_back({share, std::max({tolerance, kCoarseTolerance, kSlowProgress}), kProgressWindow});
  }
  stages.push_back({kFinalShare, std::max(tolerance, kSlowProgress), kProgressWindow});
  return stages;
}

}  // namespace aniso
