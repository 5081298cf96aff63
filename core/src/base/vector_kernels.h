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

// sum_i a[i] b_i over n doubles, b's pairs and values given by pair_at(i)
// and value_at(i): four partial sums of pairs, added pairwise, then the tail.
template <class PairAt, class ValueAt>
double sum_of_products(const double* a, std::size_t n, PairAt pair_at, ValueAt value_at) {
  Pair s0 = {0, 0}, s1 = s0, s2 = s0, s3 = s0;
  std::size_t i = 0;
  for (; i + 8 <= n; i += 8) {
    s0 += load_pair(a + i) * pair_at(i);
    s1 += load_pair(a + i + 2) * pair_at(i + 2);
    s2 += load_pair(a + i + 4) * pair_at(i + 4);
    s3 += load_pair(a + i + 6) * pair_at(i + 6);
  }
  double sum = total(s0, s1, s2, s3);
  for (; i < n; ++i) sum += a[i] * value_at(i);
  return sum;
}

}  // namespace vector_kernels_detail

// a . b over n doubles.
inline double dot(const double* a, const double* b, std::size_t n) {
  return vector_kernels_detail::sum_of_products(
      a, n, [b](std::size_t i) { return load_pair(b + i); }, [b](std::size_t i) { return b[i]; });
}

// a . (b - c) over n doubles (b - c rounded first, as written).
inline double dot_difference(const double* a, const double* b, const double* c, std::size_t n) {
  return vector_kernels_detail::sum_of_products(
      a, n, [b, c](std::size_t i) { return load_pair(b + i) - load_pair(c + i); },
      [b, c](std::size_t i) { return b[i] - c[i]; });
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

}  // namespace aniso
