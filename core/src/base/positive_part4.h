// The positive part of symmetric 4x4 matrices (the eigenvalues below 0 set
// to 0), two matrices at a time, one per lane of a pair of doubles
// (base/simd_pair.h), by cyclic Jacobi rotations. Why: the flattening
// refinement projects each triangle's 4x4 Hessian this way, and about 70 %
// of them are indefinite (the 30k-vertex koala head: 4.2 million
// decompositions, a third of the flatten); Eigen's eigen-solver takes them
// one at a time, and in WASM one double at a time.
#pragma once

#include <algorithm>

#include <Eigen/Core>

#include "base/simd_pair.h"

namespace aniso {

namespace positive_part_detail {

// Sweeps at most: Jacobi converges quadratically, and a 4x4 matrix is
// diagonal to round-off after 4 to 6.
constexpr int kMaxSweeps = 12;

using Bits = long long __attribute__((vector_size(16)));
constexpr long long kSignBit = static_cast<long long>(0x8000000000000000ULL);

inline Pair abs_pair(Pair v) { return reinterpret_cast<Pair>(reinterpret_cast<Bits>(v) & ~Bits{kSignBit, kSignBit}); }

// |v| with the sign of `sign`. A theta of -0 (A_qq = A_pp, A_pq < 0) so
// gives t = -1 where sgn would give +1: either rotation zeroes A_pq.
inline Pair with_sign_of(Pair v, Pair sign) {
  const Bits bit = reinterpret_cast<Bits>(sign) & Bits{kSignBit, kSignBit};
  return reinterpret_cast<Pair>((reinterpret_cast<Bits>(v) & ~Bits{kSignBit, kSignBit}) | bit);
}

// v, with 0 in the lanes where `test` is 0.
inline Pair zero_where_zero(Pair v, Pair test) {
  const Bits zero = test == Pair{0.0, 0.0};
  return reinterpret_cast<Pair>(reinterpret_cast<Bits>(v) & ~zero);
}

}  // namespace positive_part_detail

// a and b: symmetric; each replaced by its positive part V max(L, 0) V^T
// (left as it is where no eigenvalue is negative). a and b may be the same
// matrix.
inline void positive_parts(Eigen::Matrix4d& a, Eigen::Matrix4d& b) {
  using namespace positive_part_detail;
  Pair A[4][4], V[4][4];
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) {
      A[i][j] = Pair{a(i, j), b(i, j)};
      V[i][j] = Pair{i == j ? 1.0 : 0.0, i == j ? 1.0 : 0.0};
    }
  }
  // Ends where every off-diagonal entry is below 1e-17 of the matrix's
  // norm in both lanes (its square below 1e-34 of the norm's square).
  Pair norm2 = {0.0, 0.0};
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) norm2 += A[i][j] * A[i][j];
  }
  const Pair floor = norm2 * Pair{1e-34, 1e-34};
  for (int sweep = 0; sweep < kMaxSweeps; ++sweep) {
    Pair off = {0.0, 0.0};
    for (int p = 0; p < 3; ++p) {
      for (int q = p + 1; q < 4; ++q) off += A[p][q] * A[p][q];
    }
    if (!(off[0] > floor[0]) && !(off[1] > floor[1])) break;
    for (int p = 0; p < 3; ++p) {
      for (int q = p + 1; q < 4; ++q) {
        const Pair apq = A[p][q];
        // The rotation that zeroes A[p][q] (Numerical Recipes, 11.1):
        // t = sgn(theta) / (|theta| + sqrt(theta^2 + 1)), theta =
        // (A_qq - A_pp) / (2 A_pq); t = 0 where A_pq is 0 already (theta
        // infinite or NaN). A theta too large to square gives t = 0 too.
        const Pair theta = (A[q][q] - A[p][p]) / (Pair{2.0, 2.0} * apq);
        const Pair magnitude = abs_pair(theta);
        Pair t = Pair{1.0, 1.0} / (magnitude + sqrt_pair(theta * theta + Pair{1.0, 1.0}));
        t = with_sign_of(t, theta);
        t = zero_where_zero(t, apq);
        const Pair c = Pair{1.0, 1.0} / sqrt_pair(t * t + Pair{1.0, 1.0});
        const Pair s = t * c;
        for (int r = 0; r < 4; ++r) {
          if (r == p || r == q) continue;
          const Pair arp = A[r][p], arq = A[r][q];
          A[r][p] = A[p][r] = c * arp - s * arq;
          A[r][q] = A[q][r] = s * arp + c * arq;
        }
        A[p][p] -= t * apq;
        A[q][q] += t * apq;
        A[p][q] = A[q][p] = Pair{0.0, 0.0};
        for (int r = 0; r < 4; ++r) {
          const Pair vrp = V[r][p], vrq = V[r][q];
          V[r][p] = c * vrp - s * vrq;
          V[r][q] = s * vrp + c * vrq;
        }
      }
    }
  }
  Pair kept[4];
  bool negative[2] = {false, false};
  for (int k = 0; k < 4; ++k) {
    for (int lane = 0; lane < 2; ++lane) {
      negative[lane] = negative[lane] || A[k][k][lane] < 0.0;
      kept[k][lane] = std::max(A[k][k][lane], 0.0);
    }
  }
  if (!negative[0] && !negative[1]) return;
  Pair P[4][4];
  for (int i = 0; i < 4; ++i) {
    for (int j = i; j < 4; ++j) {
      Pair sum = {0.0, 0.0};
      for (int k = 0; k < 4; ++k) sum += V[i][k] * kept[k] * V[j][k];
      P[i][j] = P[j][i] = sum;
    }
  }
  // b first: where a and b are the same matrix, a's lane is the one kept.
  if (negative[1]) {
    for (int i = 0; i < 4; ++i) {
      for (int j = 0; j < 4; ++j) b(i, j) = P[i][j][1];
    }
  }
  if (negative[0]) {
    for (int i = 0; i < 4; ++i) {
      for (int j = 0; j < 4; ++j) a(i, j) = P[i][j][0];
    }
  }
}

}  // namespace aniso
