// C = A B^T for column-major blocks of doubles: the supernodal factorization's
// updates (geometry/supernodal_ldlt.cpp). Why not Eigen's product: Eigen 3.4
// has no WASM SIMD path, so in the browser its matrix kernel runs one double
// at a time (gebp with 1-row panels); this one keeps a 4-by-4 block of C in
// eight pairs of doubles (base/simd_pair.h), simd128 in WASM and SSE2
// natively, and reads a column of A's 4 rows and a row of B's 4 columns per
// step. Each entry of C is the sum over k in order, on every platform.
#pragma once

#include "base/simd_pair.h"

namespace aniso {

// C (rows by cols, leading dimension ldc) = A (rows by depth, lda) times the
// transpose of B (cols by depth, ldb); C is overwritten. With `lower`, only
// where C's lower triangle (row >= column) needs it: the register blocks
// wholly above the diagonal are skipped and those entries left as they were
// (the factorization's updates are symmetric, and a quarter of their blocks
// lay there for the 30k-vertex koala head's flattening).
inline void multiply_by_transpose(const double* A, int lda, const double* B, int ldb, int rows, int cols, int depth,
                                  double* C, int ldc, bool lower = false) {
  int j = 0;
  for (; j + 4 <= cols; j += 4) {
    int i = lower ? j : 0;
    for (; i + 4 <= rows; i += 4) {
      Pair c[2][4] = {};
      const double* a = A + i;
      const double* b = B + j;
      for (int k = 0; k < depth; ++k, a += lda, b += ldb) {
        const Pair a0 = load_pair(a), a1 = load_pair(a + 2);
        for (int q = 0; q < 4; ++q) {
          const Pair bq = {b[q], b[q]};
          c[0][q] += a0 * bq;
          c[1][q] += a1 * bq;
        }
      }
      for (int q = 0; q < 4; ++q) {
        store_pair(C + i + static_cast<long>(j + q) * ldc, c[0][q]);
        store_pair(C + i + 2 + static_cast<long>(j + q) * ldc, c[1][q]);
      }
    }
    for (; i < rows; ++i) {  // the last rows, one by one
      double c[4] = {};
      const double* a = A + i;
      const double* b = B + j;
      for (int k = 0; k < depth; ++k, a += lda, b += ldb) {
        for (int q = 0; q < 4; ++q) c[q] += a[0] * b[q];
      }
      for (int q = 0; q < 4; ++q) C[i + static_cast<long>(j + q) * ldc] = c[q];
    }
  }
  for (; j < cols; ++j) {  // the last columns, one by one
    int i = lower ? j & ~1 : 0;
    // Eight rows at a time: four independent sums, not one chain of
    // additions each waiting for the last (a matrix-vector product: the
    // factorization's column updates within a panel block).
    for (; i + 8 <= rows; i += 8) {
      Pair c[4] = {};
      for (int k = 0; k < depth; ++k) {
        const double bk = B[j + static_cast<long>(k) * ldb];
        const Pair b = {bk, bk};
        const double* a = A + i + static_cast<long>(k) * lda;
        for (int h = 0; h < 4; ++h) c[h] += load_pair(a + 2 * h) * b;
      }
      for (int h = 0; h < 4; ++h) store_pair(C + i + 2 * h + static_cast<long>(j) * ldc, c[h]);
    }
    for (; i + 2 <= rows; i += 2) {
      Pair c = {0.0, 0.0};
      for (int k = 0; k < depth; ++k) {
        const double bk = B[j + static_cast<long>(k) * ldb];
        c += load_pair(A + i + static_cast<long>(k) * lda) * Pair{bk, bk};
      }
      store_pair(C + i + static_cast<long>(j) * ldc, c);
    }
    for (; i < rows; ++i) {
      double c = 0.0;
      for (int k = 0; k < depth; ++k) c += A[i + static_cast<long>(k) * lda] * B[j + static_cast<long>(k) * ldb];
      C[i + static_cast<long>(j) * ldc] = c;
    }
  }
}

}  // namespace aniso
