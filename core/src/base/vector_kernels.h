// Passes over long vectors of doubles (an iterate's coordinates, flat) for
// the L-BFGS iterations: several dot products in one pass, each summed in a
// vector register (base/simd_pair.h), a linear combination of several
// vectors in one pass, and the pair of a step in one pass. Why: a plain dot
// product adds into one sum, one addition waiting for the last (Eigen's
// reduction is such a loop in WASM, which has no Eigen SIMD path), and a
// two-loop recursion of 5 pairs, one update at a time, reads and writes the
// iterate's direction 20 times an iteration besides the pairs themselves;
// with the products of the pairs kept (base/lbfgs_memory.h), 4 passes read
// each pair twice and the direction 6 times: the direction of 5 pairs took
// 0.43 ms either way natively at 50k vertices, 5.2 -> 3.5 ms at 200k; in
// WASM (Node) 1.05 -> 0.53 and 6.4 -> 4.6 ms.
// Summation order: fixed on every platform (the comment of each kernel says
// which).
#pragma once

#include <cstddef>

#include "base/simd_pair.h"

namespace aniso {

namespace vector_kernels_detail {

// The products of up to 5 vectors with up to 2 targets in one pass, a pair
// of elements at a time (one partial sum of pairs per product), written to
// out[t * stride + j]. The unrolling pragmas keep the sums in registers
// under GCC (without them its direction took 0.85 against 0.43 ms at 50k
// vertices; clang unrolls these loops by itself).
template <int G, int T>
void dots_group(const double* const* vectors, const double* const* targets, double* out, int stride,
                std::size_t n) {
  Pair sum[T][G] = {};
  std::size_t i = 0;
  for (; i + 2 <= n; i += 2) {
    Pair target[T];
#pragma GCC unroll 2
    for (int t = 0; t < T; ++t) target[t] = load_pair(targets[t] + i);
#pragma GCC unroll 5
    for (int j = 0; j < G; ++j) {
      const Pair v = load_pair(vectors[j] + i);
#pragma GCC unroll 2
      for (int t = 0; t < T; ++t) sum[t][j] += v * target[t];
    }
  }
  for (int t = 0; t < T; ++t) {
    for (int j = 0; j < G; ++j) {
      double total = sum[t][j][0] + sum[t][j][1];
      for (std::size_t k = i; k < n; ++k) total += vectors[j][k] * targets[t][k];
      out[t * stride + j] = total;
    }
  }
}

// Vectors read in one pass: up to the L-BFGS memories' 5 pairs, so that the
// pairs' passes read the gradient, or H0's result, and write the direction
// once (in groups of 4, a memory of 5 took a second pass for the fifth).
constexpr int kGroup = 5;

template <int T>
void dots_groups(const double* const* vectors, int m, const double* const* targets, double* out, std::size_t n) {
  for (int j = 0; j < m; j += kGroup) {
    switch (m - j < kGroup ? m - j : kGroup) {
      case 1: dots_group<1, T>(vectors + j, targets, out + j, m, n); break;
      case 2: dots_group<2, T>(vectors + j, targets, out + j, m, n); break;
      case 3: dots_group<3, T>(vectors + j, targets, out + j, m, n); break;
      case 4: dots_group<4, T>(vectors + j, targets, out + j, m, n); break;
      default: dots_group<kGroup, T>(vectors + j, targets, out + j, m, n); break;
    }
  }
}

// out += the combination of up to 5 vectors, a pair of elements at a time,
// added in the order of j (first = true: out = base_coefficient base first).
template <int G>
void combine_group(double* out, double base_coefficient, const double* base, const double* const* vectors,
                   const double* coefficients, bool first, std::size_t n) {
  Pair a[G];
  for (int j = 0; j < G; ++j) a[j] = Pair{coefficients[j], coefficients[j]};
  const Pair c = {base_coefficient, base_coefficient};
  std::size_t i = 0;
  for (; i + 2 <= n; i += 2) {
    Pair x = first ? c * load_pair(base + i) : load_pair(out + i);
#pragma GCC unroll 5
    for (int j = 0; j < G; ++j) x += a[j] * load_pair(vectors[j] + i);
    store_pair(out + i, x);
  }
  for (; i < n; ++i) {
    double x = first ? base_coefficient * base[i] : out[i];
    for (int j = 0; j < G; ++j) x += coefficients[j] * vectors[j][i];
    out[i] = x;
  }
}

}  // namespace vector_kernels_detail

// out[t * m + j] = vectors[j] . targets[t] for j < m, t < num_targets (1 or
// 2), reading each vector once: groups of up to 5 vectors, each product one
// partial sum of pairs (elements i mod 2), its lanes added at the end, then
// the tail.
inline void dots_with(const double* const* vectors, int m, const double* const* targets, int num_targets,
                      double* out, std::size_t n) {
  if (num_targets == 2) {
    vector_kernels_detail::dots_groups<2>(vectors, m, targets, out, n);
  } else {
    vector_kernels_detail::dots_groups<1>(vectors, m, targets, out, n);
  }
}

// out = base_coefficient base + sum over j < m of coefficients[j] vectors[j],
// added in the order of j element by element (in passes of up to 5 vectors).
// out may be base.
inline void combine(double* out, double base_coefficient, const double* base, const double* const* vectors,
                    const double* coefficients, int m, std::size_t n) {
  using namespace vector_kernels_detail;
  if (m == 0) {
    combine_group<0>(out, base_coefficient, base, vectors, coefficients, true, n);
    return;
  }
  for (int j = 0; j < m; j += kGroup) {
    const bool first = j == 0;
    switch (m - j < kGroup ? m - j : kGroup) {
      case 1: combine_group<1>(out, base_coefficient, base, vectors + j, coefficients + j, first, n); break;
      case 2: combine_group<2>(out, base_coefficient, base, vectors + j, coefficients + j, first, n); break;
      case 3: combine_group<3>(out, base_coefficient, base, vectors + j, coefficients + j, first, n); break;
      case 4: combine_group<4>(out, base_coefficient, base, vectors + j, coefficients + j, first, n); break;
      default: combine_group<kGroup>(out, base_coefficient, base, vectors + j, coefficients + j, first, n); break;
    }
  }
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
