// Two doubles in one vector register: SSE2 natively, simd128 in WASM (the
// GCC/clang vector extension; arithmetic is lane by lane, so each lane
// rounds as the scalar code would). The supernodal sweeps run on pairs of
// columns, the rotation fits on pairs of cells.
#pragma once
#include <cstring>

namespace aniso {

using Pair = double __attribute__((vector_size(16)));

// Unaligned load and store of two consecutive doubles.
inline Pair load_pair(const double* p) {
  Pair v;
  std::memcpy(&v, p, sizeof v);
  return v;
}

inline void store_pair(double* p, Pair v) { std::memcpy(p, &v, sizeof v); }

}  // namespace aniso
