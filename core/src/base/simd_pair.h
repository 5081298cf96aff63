// Two doubles in one vector register: SSE2 natively, simd128 in WASM (the
// GCC/clang vector extension; arithmetic is lane by lane, so each lane
// rounds as the scalar code would). The supernodal sweeps run on pairs of
// columns, the rotation fits on pairs of cells.
#pragma once
#include <cmath>
#include <cstring>

#if defined(__wasm_simd128__)
#include <wasm_simd128.h>
#elif defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace aniso {

using Pair = double __attribute__((vector_size(16)));

// Unaligned load and store of two consecutive doubles.
inline Pair load_pair(const double* p) {
  Pair v;
  std::memcpy(&v, p, sizeof v);
  return v;
}

inline void store_pair(double* p, Pair v) { std::memcpy(p, &v, sizeof v); }

// Lane by lane square root, correctly rounded as std::sqrt is.
inline Pair sqrt_pair(Pair v) {
#if defined(__wasm_simd128__)
  return reinterpret_cast<Pair>(wasm_f64x2_sqrt(reinterpret_cast<v128_t>(v)));
#elif defined(__SSE2__)
  return reinterpret_cast<Pair>(_mm_sqrt_pd(reinterpret_cast<__m128d>(v)));
#else
  return Pair{std::sqrt(v[0]), std::sqrt(v[1])};
#endif
}

}  // namespace aniso
