// positive_parts (base/positive_part4.h): two symmetric 4x4 matrices at
// once, each with its negative eigenvalues set to 0, against Eigen's
// eigen-decomposition; positive semidefinite matrices come back as they were.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdlib>
#include <vector>

#include <Eigen/Eigenvalues>
#include <Eigen/QR>

#include "base/positive_part4.h"

using aniso::positive_parts;

namespace {

Eigen::Matrix4d reference(const Eigen::Matrix4d& H) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d> eigen(H);
  if (eigen.eigenvalues().minCoeff() >= 0.0) return H;
  return eigen.eigenvectors() * eigen.eigenvalues().cwiseMax(0.0).asDiagonal() * eigen.eigenvectors().transpose();
}

Eigen::Matrix4d symmetric(const Eigen::Vector4d& eigenvalues, unsigned seed) {
  std::srand(seed);
  const Eigen::Matrix4d Q = Eigen::HouseholderQR<Eigen::Matrix4d>(Eigen::Matrix4d::Random()).householderQ();
  const Eigen::Matrix4d M = Q * eigenvalues.asDiagonal() * Q.transpose();
  return (M + M.transpose()) / 2.0;  // symmetric to the last bit
}

}  // namespace

TEST_CASE("positive parts of 4x4 matrices, two at a time, match the eigen-decomposition's", "[flatten]") {
  const std::vector<Eigen::Vector4d> spectra = {
      {3.0, 2.0, 1.0, 0.5},     // definite: unchanged
      {3.0, 2.0, 1.0, -0.5},    // one negative
      {3.0, -2.0, 1.0, -0.5},   // two
      {-3.0, -2.0, -1.0, -0.5}, // all: zero
      {2.0, 2.0, -1.0, -1.0},   // repeated eigenvalues
      {1e6, 1.0, -1e-6, 0.0},   // far apart, one zero
  };
  unsigned seed = 1;
  for (const Eigen::Vector4d& first : spectra) {
    for (const Eigen::Vector4d& second : spectra) {
      const Eigen::Matrix4d A = symmetric(first, seed++), B = symmetric(second, seed++);
      Eigen::Matrix4d a = A, b = B;
      positive_parts(a, b);
      const double scale = std::max(first.cwiseAbs().maxCoeff(), second.cwiseAbs().maxCoeff());
      INFO("spectra " << first.transpose() << " / " << second.transpose());
      CHECK((a - reference(A)).cwiseAbs().maxCoeff() <= 1e-12 * scale);
      CHECK((b - reference(B)).cwiseAbs().maxCoeff() <= 1e-12 * scale);
      CHECK((a - a.transpose()).cwiseAbs().maxCoeff() == 0.0);
      if (first.minCoeff() >= 0.0) CHECK(a == A);  // left as it was
    }
  }
  // Already diagonal (every rotation is the identity), and one matrix in
  // both lanes.
  Eigen::Matrix4d D = Eigen::Vector4d(1.0, -2.0, 3.0, -4.0).asDiagonal();
  positive_parts(D, D);
  CHECK(D == Eigen::Matrix4d(Eigen::Vector4d(1.0, 0.0, 3.0, 0.0).asDiagonal()));
  Eigen::Matrix4d S = symmetric({2.0, -1.0, 0.5, -3.0}, 99);
  const Eigen::Matrix4d expected = reference(S);
  positive_parts(S, S);
  CHECK((S - expected).cwiseAbs().maxCoeff() <= 1e-12 * 3.0);
}
