// Passes over long vectors of doubles (an iterate's coordinates, flat) for
// the L-BFGS iterations: dot products with several partial sums in vector
// registers (base/simd_pair.h), and an update fused with the next dot
// product. Why: a plain loop adds into one sum, one addition waiting for the
// last (Eigen's reduction is such a loop in WASM, which has no Eigen SIMD
// path), and a two-loop recursion of 5 pairs reads the 200k-vertex iterate
// 20 times an iteration; fused, 12.
// Summation order: four partial sums of pairs (elements i mod 8), added
// pairwise at the end, then the tail; fixed on every platform.
#pragma once

#include <cstddef>

#include "base/simd_pair.h"

namespace aniso {

namespace vector_kernels_detail {

inline double total(Pair a, Pair b, Pair c, Pair d) {
  const Pair sum = (a + b) + (c + d);
  return sum[0] + sum[1];
}

}  // namespace vector_kernels_detail

// a . b over n doubles.
inline double dot(const double* a, const double* b, std::size_t n) {
  Pair s0 = {0, 0}, s1 = s0, s2 = s0, s3 = s0;
  std::size_t i = 0;
  for (; i + 8 <= n; i += 8) {
    s0 += load_pair(a + i) * load_pair(b + i);
    s1 += load_pair(a + i + 2) * load_pair(b + i + 2);
    s2 += load_pair(a + i + 4) * load_pair(b + i + 4);
    s3 += load_pair(a + i + 6) * load_pair(b + i + 6);
  }
  double sum = vector_kernels_detail::total(s0, s1, s2, s3);
  for (; i < n; ++i) sum += a[i] * b[i];
  return sum;
}

// x += alpha y over n doubles, and returns z . x (the updated x); with z
// null, only the update (and 0).
inline double axpy_dot(double* x, double alpha, const double* y, const double* z, std::size_t n) {
  const Pair a = {alpha, alpha};
  std::size_t i = 0;
  if (z == nullptr) {
    for (; i + 2 <= n; i += 2) store_pair(x + i, load_pair(x + i) + a * load_pair(y + i));
    for (; i < n; ++i) x[i] += alpha * y[i];
    return 0.0;
  }
  Pair s0 = {0, 0}, s1 = s0, s2 = s0, s3 = s0;
  for (; i + 8 <= n; i += 8) {
    const Pair x0 = load_pair(x + i) + a * load_pair(y + i);
    const Pair x1 = load_pair(x + i + 2) + a * load_pair(y + i + 2);
    const Pair x2 = load_pair(x + i + 4) + a * load_pair(y + i + 4);
    const Pair x3 = load_pair(x + i + 6) + a * load_pair(y + i + 6);
    store_pair(x + i, x0);
    store_pair(x + i + 2, x1);
    store_pair(x + i + 4, x2);
    store_pair(x + i + 6, x3);
    s0 += load_pair(z + i) * x0;
    s1 += load_pair(z + i + 2) * x1;
    s2 += load_pair(z + i + 4) * x2;
    s3 += load_pair(z + i + 6) * x3;
  }
  double sum = vector_kernels_detail::total(s0, s1, s2, s3);
  for (; i < n; ++i) {
    x[i] += alpha * y[i];
    sum += z[i] * x[i];
  }
  return sum;
}

// The pair of an L-BFGS step in one pass: s = x1 - x0 and y = g1 - g0 (each
// rounded as written), and the products s.y, s.(b1 - b0), s.s and y.y, each
// with two partial sums of pairs (elements i mod 4), added at the end, then
// the tail. Why: as separate passes (two differences, four dot products)
// they read the 50k-cylinder iterate's vectors 16 times.
struct StepProducts {
  double sy = 0.0, s_db = 0.0, ss = 0.0, yy = 0.0;
};

inline StepProducts step_pair(const double* x1, const double* x0, const double* g1, const double* g0,
                              const double* b1, const double* b0, double* s, double* y, std::size_t n) {
  Pair sy[2] = {}, s_db[2] = {}, ss[2] = {}, yy[2] = {};
  std::size_t i = 0;
  for (; i + 4 <= n; i += 4) {
    for (int h = 0; h < 2; ++h) {
      const std::size_t j = i + 2 * h;
      const Pair sj = load_pair(x1 + j) - load_pair(x0 + j), yj = load_pair(g1 + j) - load_pair(g0 + j);
      store_pair(s + j, sj);
      store_pair(y + j, yj);
      sy[h] += sj * yj;
      s_db[h] += sj * (load_pair(b1 + j) - load_pair(b0 + j));
      ss[h] += sj * sj;
      yy[h] += yj * yj;
    }
  }
  const auto total = [](const Pair (&p)[2]) {
    const Pair sum = p[0] + p[1];
    return sum[0] + sum[1];
  };
  StepProducts out{total(sy), total(s_db), total(ss), total(yy)};
  for (; i < n; ++i) {
    s[i] = x1[i] - x0[i];
    y[i] = g1[i] - g0[i];
    out.sy += s[i] * y[i];
    out.s_db += s[i] * (b1[i] - b0[i]);
    out.ss += s[i] * s[i];
    out.yy += y[i] * y[i];
  }
  return out;
}

}  // namespace aniso
