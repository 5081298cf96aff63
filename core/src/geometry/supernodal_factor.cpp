#include "geometry/supernodal_factor.h"

#include <algorithm>
#include <cstddef>
#include <string>
#include <utility>

#include "anisoform/error.h"
#include "base/simd_pair.h"

namespace aniso {

namespace {

// Rows of a supernode's block taken together in the sweeps: each value of
// the right-hand side loaded serves them all. The rows of a group are stored
// interleaved by pairs of columns (the block layout below), so that the sweeps read
// one contiguous stream: reading the rows side by side from their own
// places was two streams, and the sweeps over the large blocks ran at half
// the speed (200k cylinder, natively: 2.9 -> 1.2 cycles per value forward).
constexpr int kRowBlock = 2;
// Columns copied together into the row-major block: a cache line of each
// destination row per pass, each source column read in order.
constexpr int kCopyTile = 8;

// The block layout: a group of `rows` rows (w values each) holds row i's
// value in column k at
//   (k / 2) * 2 rows + 2 i + (k & 1)  for k below paired = w & ~1,
//   paired rows + i                   for an odd last column k = paired:
// pairs of columns k, k+1 of the group's rows side by side, then a last odd
// column's values, one per row (store writes it, the sweeps read it).

// The sweeps multiply and add two consecutive columns k, k+1 of a
// supernode at a time (base/simd_pair.h).

// Forward: y[R[i]] -= B_i x for a group of Rows rows B_i (the block layout);
// xt holds x by column (column c's w values at xt + c w).
template <int K, int Rows>
void subtract_rows(const double* b, int w, const double* xt, const int* R, double* y) {
  Pair acc[Rows][K] = {};
  int k = 0;
  for (; k + 2 <= w; k += 2, b += 2 * Rows) {
    Pair xk[K];
    for (int c = 0; c < K; ++c) xk[c] = load_pair(xt + c * w + k);
    for (int i = 0; i < Rows; ++i) {
      const Pair bk = load_pair(b + 2 * i);
      for (int c = 0; c < K; ++c) acc[i][c] += bk * xk[c];
    }
  }
  for (int i = 0; i < Rows; ++i) {
    double* yi = y + static_cast<std::ptrdiff_t>(R[i]) * K;
    for (int c = 0; c < K; ++c) {
      double sum = acc[i][c][0] + acc[i][c][1];
      if (k < w) sum += b[i] * xt[c * w + k];
      yi[c] -= sum;
    }
  }
}

// Backward: acc += sum_i B_i^T y[R[i]] over a group of Rows rows, acc by
// column (column c's w sums at acc + c w). The group's values are read from
// the last down, as the whole backward sweep reads the factor: one stream
// of falling addresses. Read upwards within each small block, the hardware
// prefetch lost it (200k cylinder, natively: 3 to 7.5 cycles per value on
// blocks of up to 16 columns, against 1.2 to 3 now).
template <int K, int Rows>
void gather_rows(const double* b, int w, const int* R, const double* y, double* acc) {
  double yr[Rows][K];
  Pair yp[Rows][K];
  for (int i = 0; i < Rows; ++i) {
    for (int c = 0; c < K; ++c) {
      yr[i][c] = y[static_cast<std::ptrdiff_t>(R[i]) * K + c];
      yp[i][c] = Pair{yr[i][c], yr[i][c]};
    }
  }
  const int paired = w & ~1;
  if (paired < w) {
    const double* last = b + static_cast<std::ptrdiff_t>(paired) * Rows;
    for (int c = 0; c < K; ++c) {
      double a = acc[c * w + paired];
      for (int i = Rows - 1; i >= 0; --i) a += last[i] * yr[i][c];
      acc[c * w + paired] = a;
    }
  }
  for (int k = paired - 2; k >= 0; k -= 2) {
    const double* values = b + static_cast<std::ptrdiff_t>(k) * Rows;
    Pair bk[Rows];
    for (int i = Rows - 1; i >= 0; --i) bk[i] = load_pair(values + 2 * i);
    for (int c = 0; c < K; ++c) {
      Pair a = load_pair(acc + c * w + k);
      for (int i = Rows - 1; i >= 0; --i) a += bk[i] * yp[i][c];
      store_pair(acc + c * w + k, a);
    }
  }
}

// Single precision, the same block layout: a group's pair of columns k, k+1
// is one Quad (row 0's two values, then row 1's), multiplied by x's values
// at k, k+1 twice over, so lanes 0-1 sum row 0 and lanes 2-3 row 1.
template <int K, int Rows>
void subtract_rows(const float* b, int w, const float* xt, const int* R, float* y) {
  static_assert(Rows == 1 || Rows == 2, "groups of two rows, or one row alone");
  Quad acc[K] = {};
  float sum[Rows][K];
  int k = 0;
  if constexpr (Rows == 2) {
    for (; k + 2 <= w; k += 2, b += 4) {
      const Quad bk = load_quad(b);
      for (int c = 0; c < K; ++c) acc[c] += bk * load_pair_twice(xt + c * w + k);
    }
    for (int c = 0; c < K; ++c) {
      sum[0][c] = acc[c][0] + acc[c][1];
      sum[1][c] = acc[c][2] + acc[c][3];
      if (k < w) {  // the odd last column, one value per row
        sum[0][c] += b[0] * xt[c * w + k];
        sum[1][c] += b[1] * xt[c * w + k];
      }
    }
  } else {  // a row alone is stored in order: four columns at a time
    for (; k + 4 <= w; k += 4) {
      const Quad bk = load_quad(b + k);
      for (int c = 0; c < K; ++c) acc[c] += bk * load_quad(xt + c * w + k);
    }
    for (int c = 0; c < K; ++c) {
      sum[0][c] = (acc[c][0] + acc[c][1]) + (acc[c][2] + acc[c][3]);
      for (int j = k; j < w; ++j) sum[0][c] += b[j] * xt[c * w + j];
    }
  }
  for (int i = 0; i < Rows; ++i) {
    float* yi = y + static_cast<std::ptrdiff_t>(R[i]) * K;
    for (int c = 0; c < K; ++c) yi[c] -= sum[i][c];
  }
}

// Backward in single precision: the group's products are summed lane by
// lane into `pairs` (column c's pair p at pairs + 4 (c (w / 2) + p), row 0's
// sums in lanes 0-1, row 1's in 2-3) and folded into acc once per
// supernode (fold_pairs); the odd last column goes to acc directly.
template <int K, int Rows>
void gather_rows(const float* b, int w, const int* R, const float* y, float* pairs, float* acc) {
  static_assert(Rows == 1 || Rows == 2, "groups of two rows, or one row alone");
  float yr[Rows][K];
  for (int i = 0; i < Rows; ++i) {
    for (int c = 0; c < K; ++c) yr[i][c] = y[static_cast<std::ptrdiff_t>(R[i]) * K + c];
  }
  if constexpr (Rows == 1) {
    for (int k = w - 1; k >= 0; --k) {
      for (int c = 0; c < K; ++c) acc[c * w + k] += b[k] * yr[0][c];
    }
    return;
  } else {
    const int paired = w & ~1, count = paired / 2;
    if (paired < w) {
      for (int c = 0; c < K; ++c) acc[c * w + paired] += b[2 * paired + 1] * yr[1][c] + b[2 * paired] * yr[0][c];
    }
    Quad yq[K];
    for (int c = 0; c < K; ++c) yq[c] = Quad{yr[0][c], yr[0][c], yr[1][c], yr[1][c]};
    for (int p = count - 1; p >= 0; --p) {
      const Quad bk = load_quad(b + 4 * p);
      for (int c = 0; c < K; ++c) {
        float* sum = pairs + 4 * (c * count + p);
        store_quad(sum, load_quad(sum) + bk * yq[c]);
      }
    }
  }
}

template <int K>
void fold_pairs(const float* pairs, int w, float* acc) {
  const int count = w / 2;
  for (int c = 0; c < K; ++c) {
    for (int p = 0; p < count; ++p) {
      const float* sum = pairs + 4 * (c * count + p);
      acc[c * w + 2 * p] += sum[0] + sum[2];
      acc[c * w + 2 * p + 1] += sum[1] + sum[3];
    }
  }
}

// The backward sweep over a supernode's block (r rows R), into acc (by
// column, zeroed): the rows after the last group first (they are stored
// last), then the groups from the last down.
template <int K>
void gather_block(const double* b, int w, int r, const int* R, const double* y, double* /*pairs*/, double* acc) {
  const int grouped = r - r % kRowBlock;
  for (int i = r - 1; i >= grouped; --i) gather_rows<K, 1>(b + static_cast<std::ptrdiff_t>(i) * w, w, R + i, y, acc);
  for (int i = grouped - kRowBlock; i >= 0; i -= kRowBlock) {
    gather_rows<K, kRowBlock>(b + static_cast<std::ptrdiff_t>(i) * w, w, R + i, y, acc);
  }
}

template <int K>
void gather_block(const float* b, int w, int r, const int* R, const float* y, float* pairs, float* acc) {
  const int grouped = r - r % kRowBlock;
  std::fill(pairs, pairs + 4 * K * (w / 2), 0.0f);
  for (int i = r - 1; i >= grouped; --i) {
    gather_rows<K, 1>(b + static_cast<std::ptrdiff_t>(i) * w, w, R + i, y, pairs, acc);
  }
  for (int i = grouped - kRowBlock; i >= 0; i -= kRowBlock) {
    gather_rows<K, kRowBlock>(b + static_cast<std::ptrdiff_t>(i) * w, w, R + i, y, pairs, acc);
  }
  fold_pairs<K>(pairs, w, acc);
}

// The vector registers of each precision, for the triangle kernels.
template <typename Scalar>
struct Lanes;
template <>
struct Lanes<double> {
  using Vector = Pair;
  static constexpr int size = 2;
  static Vector load(const double* p) { return load_pair(p); }
  static void store(double* p, Vector v) { store_pair(p, v); }
  static Vector splat(double x) { return Vector{x, x}; }
  static double sum(Vector v) { return v[0] + v[1]; }
};
template <>
struct Lanes<float> {
  using Vector = Quad;
  static constexpr int size = 4;
  static Vector load(const float* p) { return load_quad(p); }
  static void store(float* p, Vector v) { store_quad(p, v); }
  static Vector splat(float x) { return Vector{x, x, x, x}; }
  static float sum(Vector v) { return (v[0] + v[1]) + (v[2] + v[3]); }
};

// The triangle's column k, forward: x_c[k+1+m] -= t[m] x_c[k] for its n
// entries t and each of the K columns x_c (x_c = xk + c w, xk at row k),
// reading t once for all of them.
template <int K, typename Scalar>
void subtract_column(const Scalar* t, int n, int w, Scalar* xk) {
  using L = Lanes<Scalar>;
  Scalar xs[K];
  typename L::Vector xv[K];
  for (int c = 0; c < K; ++c) {
    xs[c] = xk[c * w];
    xv[c] = L::splat(xs[c]);
  }
  Scalar* below = xk + 1;
  int m = 0;
  for (; m + L::size <= n; m += L::size) {
    const typename L::Vector tm = L::load(t + m);
    for (int c = 0; c < K; ++c) L::store(below + c * w + m, L::load(below + c * w + m) - tm * xv[c]);
  }
  for (; m < n; ++m) {
    for (int c = 0; c < K; ++c) below[c * w + m] -= t[m] * xs[c];
  }
}

// The triangle's column k, backward: x_c[k] -= t . x_c[k+1 .. k+n] for each
// of the K columns, reading t once, from its end down (as gather_rows); two
// partial sums of vectors per column, added at the end.
template <int K, typename Scalar>
void subtract_dots(const Scalar* t, int n, int w, Scalar* xk) {
  using L = Lanes<Scalar>;
  constexpr int step = 2 * L::size;
  const Scalar* below = xk + 1;
  typename L::Vector s0[K] = {}, s1[K] = {};
  Scalar tail[K] = {};
  const int blocks = n - n % step;
  for (int j = n - 1; j >= blocks; --j) {
    for (int c = 0; c < K; ++c) tail[c] += t[j] * below[c * w + j];
  }
  for (int m = blocks - step; m >= 0; m -= step) {
    const typename L::Vector t1 = L::load(t + m + L::size), t0 = L::load(t + m);
    for (int c = 0; c < K; ++c) {
      s1[c] += t1 * L::load(below + c * w + m + L::size);
      s0[c] += t0 * L::load(below + c * w + m);
    }
  }
  for (int c = 0; c < K; ++c) xk[c * w] -= L::sum(s0[c] + s1[c]) + tail[c];
}

}  // namespace

SupernodalFactor::SupernodalFactor(int n, std::vector<int> first_column, const std::vector<int>& row_offsets,
                                   const std::vector<int>& rows, const std::vector<std::size_t>& panel_offsets,
                                   const double* panels)
    : n_(n), first_column_(std::move(first_column)) {
  // Sized once: grown entry by entry, the values were copied over and over
  // (a few % of each of the flattening refinement's factorizations).
  std::size_t values = 0;
  for (int s = 0; s < supernodes(); ++s) {
    const std::size_t w = first_column_[s + 1] - first_column_[s];
    const std::size_t m = row_offsets[s + 1] - row_offsets[s];
    values += w * (w - 1) / 2 + (m - w) * w;
  }
  values_.reserve(values);
  rows_.reserve(rows.size());
  row_start_.reserve(supernodes() + 1);
  triangle_start_.reserve(supernodes());
  block_start_.reserve(supernodes());
  for (int s = 0; s < supernodes(); ++s) {
    const int w = first_column_[s + 1] - first_column_[s];
    const int m = row_offsets[s + 1] - row_offsets[s];
    store(s, rows.data() + row_offsets[s] + w, m - w, panels + panel_offsets[s], m);
  }
  row_start_.push_back(static_cast<int>(rows_.size()));
}

void SupernodalFactor::store(int s, const int* R, int r, const double* panel, int m) {
  const int w = first_column_[s + 1] - first_column_[s];
  widest_ = std::max(widest_, w);
  row_start_.push_back(static_cast<int>(rows_.size()));
  rows_.insert(rows_.end(), R, R + r);
  triangle_start_.push_back(static_cast<int>(values_.size()));
  for (int k = 0; k + 1 < w; ++k) {
    const double* column = panel + static_cast<std::size_t>(k) * m;
    values_.insert(values_.end(), column + k + 1, column + w);
  }
  block_start_.push_back(static_cast<int>(values_.size()));
  values_.resize(values_.size() + static_cast<std::size_t>(r) * w);
  double* block = values_.data() + block_start_.back();
  // The block's entry (i, k) is below[k m + i]. Written in the block layout
  // without computing the offset per value: each pair of rows is
  // 2-by-2 tiles of pairs of columns (then a last odd column's two
  // values), and a last odd row stands alone, row-major. The index
  // arithmetic per value was most of this copy's time (in WASM, 5 % of a
  // 30k-vertex flatten, which factors once per refinement step).
  const double* below = panel + w;
  const int paired = w & ~1, grouped = r - r % kRowBlock;
  static_assert(kRowBlock == 2, "the copy below writes groups of two rows");
  for (int k0 = 0; k0 < w; k0 += kCopyTile) {
    const int k1 = std::min(w, k0 + kCopyTile), pairs_end = std::min(k1, paired);
    for (int i = 0; i < grouped; i += 2) {
      double* out = block + static_cast<std::size_t>(i) * w;
      for (int k = k0; k < pairs_end; k += 2) {
        const double* left = below + static_cast<std::size_t>(k) * m + i;
        const double* right = left + m;
        out[2 * k] = left[0];
        out[2 * k + 1] = right[0];
        out[2 * k + 2] = left[1];
        out[2 * k + 3] = right[1];
      }
      if (pairs_end < k1) {  // the odd last column
        const double* last = below + static_cast<std::size_t>(paired) * m + i;
        out[2 * paired] = last[0];
        out[2 * paired + 1] = last[1];
      }
    }
    for (int i = grouped; i < r; ++i) {
      double* out = block + static_cast<std::size_t>(i) * w;
      for (int k = k0; k < k1; ++k) out[k] = below[static_cast<std::size_t>(k) * m + i];
    }
  }
}

template <typename Scalar, int K>
void SupernodalFactor::sweeps(const Scalar* values, const Scalar* inv_d, Scalar* y) const {
  const int count = supernodes();
  // A wide supernode's own columns, by column (column c at xt + c w), so
  // that the vector loops read them contiguously; the backward sums, and
  // the single precision's lane sums (gather_block).
  std::vector<Scalar> xt(static_cast<std::size_t>(widest_) * K), acc(xt.size()), pairs(4 * xt.size());
  // Forward: L z = y, supernode by supernode.
  for (int s = 0; s < count; ++s) {
    const int c0 = first_column_[s], w = first_column_[s + 1] - c0;
    Scalar* x = y + static_cast<std::ptrdiff_t>(c0) * K;
    const int* R = rows_.data() + row_start_[s];
    const int r = row_start_[s + 1] - row_start_[s];
    const Scalar* b = values + block_start_[s];
    if (w == 1) {  // most supernodes (the leaves): the simplicial column
      for (int i = 0; i < r; ++i) {
        Scalar* yi = y + static_cast<std::ptrdiff_t>(R[i]) * K;
        for (int c = 0; c < K; ++c) yi[c] -= b[i] * x[c];
      }
      continue;
    }
    for (int k = 0; k < w; ++k) {
      for (int c = 0; c < K; ++c) xt[c * w + k] = x[k * K + c];
    }
    // The triangle, column by column: column k's entries (rows k+1 .. w-1)
    // are contiguous, and so are the values they update.
    const Scalar* t = values + triangle_start_[s];
    for (int k = 0; k + 1 < w; t += w - 1 - k, ++k) subtract_column<K>(t, w - 1 - k, w, xt.data() + k);
    for (int k = 0; k < w; ++k) {
      for (int c = 0; c < K; ++c) x[k * K + c] = xt[c * w + k];
    }
    int i = 0;
    for (; i + kRowBlock <= r; i += kRowBlock, b += kRowBlock * w) {
      subtract_rows<K, kRowBlock>(b, w, xt.data(), R + i, y);
    }
    for (; i < r; ++i, b += w) subtract_rows<K, 1>(b, w, xt.data(), R + i, y);
  }
  for (int j = 0; j < n_; ++j) {
    for (int c = 0; c < K; ++c) y[static_cast<std::ptrdiff_t>(j) * K + c] *= inv_d[j];
  }
  // Backward: L^T x = z, supernodes in reverse, each one's values read from
  // its last down (gather_rows).
  for (int s = count - 1; s >= 0; --s) {
    const int c0 = first_column_[s], w = first_column_[s + 1] - c0;
    Scalar* x = y + static_cast<std::ptrdiff_t>(c0) * K;
    const int* R = rows_.data() + row_start_[s];
    const int r = row_start_[s + 1] - row_start_[s];
    const Scalar* b = values + block_start_[s];
    if (w == 1) {
      Scalar sum[K] = {};
      for (int i = r - 1; i >= 0; --i) {
        const Scalar* yi = y + static_cast<std::ptrdiff_t>(R[i]) * K;
        for (int c = 0; c < K; ++c) sum[c] += b[i] * yi[c];
      }
      for (int c = 0; c < K; ++c) x[c] -= sum[c];
      continue;
    }
    // The block first (R's rows are final), then the triangle, last column
    // first; column k's entries follow the (w-1) + ... + (w-k) of the
    // columns before it.
    std::fill(acc.begin(), acc.begin() + w * K, Scalar(0));
    gather_block<K>(b, w, r, R, y, pairs.data(), acc.data());
    for (int k = 0; k < w; ++k) {
      for (int c = 0; c < K; ++c) xt[c * w + k] = x[k * K + c] - acc[c * w + k];
    }
    const Scalar* triangle = values + triangle_start_[s];
    for (int k = w - 2; k >= 0; --k) {
      subtract_dots<K>(triangle + k * (w - 1) - k * (k - 1) / 2, w - 1 - k, w, xt.data() + k);
    }
    for (int k = 0; k < w; ++k) {
      for (int c = 0; c < K; ++c) x[k * K + c] = xt[c * w + k];
    }
  }
}

void SupernodalFactor::solve(const Eigen::VectorXd& inv_d, double* y, int columns) const {
  switch (columns) {
    case 1: sweeps<double, 1>(values_.data(), inv_d.data(), y); break;
    case 2: sweeps<double, 2>(values_.data(), inv_d.data(), y); break;
    case 3: sweeps<double, 3>(values_.data(), inv_d.data(), y); break;
    default:
      fail(ErrorCode::BadParameter, "SupernodalFactor::solve takes 1, 2 or 3 columns, not " + std::to_string(columns));
  }
}

void SupernodalFactor::make_single() { single_values_.assign(values_.begin(), values_.end()); }

void SupernodalFactor::solve(const Eigen::VectorXf& inv_d, float* y, int columns) const {
  if (!has_single()) fail(ErrorCode::Numerical, "SupernodalFactor: the single-precision copy was not made");
  switch (columns) {
    case 1: sweeps<float, 1>(single_values_.data(), inv_d.data(), y); break;
    case 2: sweeps<float, 2>(single_values_.data(), inv_d.data(), y); break;
    case 3: sweeps<float, 3>(single_values_.data(), inv_d.data(), y); break;
    default:
      fail(ErrorCode::BadParameter, "SupernodalFactor::solve takes 1, 2 or 3 columns, not " + std::to_string(columns));
  }
}

}  // namespace aniso
