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

// The triangle's column k, forward: x_c[k+1+m] -= t[m] x_c[k] for its n
// entries t and each of the K columns x_c (x_c = xk + c w, xk at row k),
// reading t once for all of them.
template <int K>
void subtract_column(const double* t, int n, int w, double* xk) {
  double xs[K];
  Pair xp[K];
  for (int c = 0; c < K; ++c) {
    xs[c] = xk[c * w];
    xp[c] = Pair{xs[c], xs[c]};
  }
  double* below = xk + 1;
  int m = 0;
  for (; m + 2 <= n; m += 2) {
    const Pair tm = load_pair(t + m);
    for (int c = 0; c < K; ++c) store_pair(below + c * w + m, load_pair(below + c * w + m) - tm * xp[c]);
  }
  if (m < n) {
    for (int c = 0; c < K; ++c) below[c * w + m] -= t[m] * xs[c];
  }
}

// The triangle's column k, backward: x_c[k] -= t . x_c[k+1 .. k+n] for each
// of the K columns, reading t once, from its end down (as gather_rows); two
// partial sums of pairs per column, added at the end.
template <int K>
void subtract_dots(const double* t, int n, int w, double* xk) {
  const double* below = xk + 1;
  Pair s0[K] = {}, s1[K] = {};
  double tail[K] = {};
  const int quads = n & ~3;
  for (int j = n - 1; j >= quads; --j) {
    for (int c = 0; c < K; ++c) tail[c] += t[j] * below[c * w + j];
  }
  for (int m = quads - 4; m >= 0; m -= 4) {
    const Pair t1 = load_pair(t + m + 2), t0 = load_pair(t + m);
    for (int c = 0; c < K; ++c) {
      s1[c] += t1 * load_pair(below + c * w + m + 2);
      s0[c] += t0 * load_pair(below + c * w + m);
    }
  }
  for (int c = 0; c < K; ++c) {
    const Pair sum = s0[c] + s1[c];
    xk[c * w] -= (sum[0] + sum[1]) + tail[c];
  }
}

}  // namespace

SupernodalFactor::SupernodalFactor(int n, const std::vector<int>& first_column, const std::vector<int>& row_offsets,
                                   const std::vector<int>& rows, const std::vector<std::size_t>& panel_offsets,
                                   const double* panels) {
  assign(n, first_column, row_offsets, rows, panel_offsets, panels);
}

void SupernodalFactor::assign(int n, const std::vector<int>& first_column, const std::vector<int>& row_offsets,
                              const std::vector<int>& rows, const std::vector<std::size_t>& panel_offsets,
                              const double* panels) {
  n_ = n;
  widest_ = 0;
  first_column_ = first_column;
  row_start_.clear();
  rows_.clear();
  triangle_start_.clear();
  block_start_.clear();
  // Sized once: grown entry by entry, the values were copied over and over
  // (a few % of each of the flattening refinement's factorizations).
  std::size_t values = 0;
  for (int s = 0; s < supernodes(); ++s) {
    const std::size_t w = first_column_[s + 1] - first_column_[s];
    const std::size_t m = row_offsets[s + 1] - row_offsets[s];
    values += w * (w - 1) / 2 + (m - w) * w;
  }
  values_.resize(values);
  std::size_t stored = 0;
  rows_.reserve(rows.size());
  row_start_.reserve(supernodes() + 1);
  triangle_start_.reserve(supernodes());
  block_start_.reserve(supernodes());
  for (int s = 0; s < supernodes(); ++s) {
    const int w = first_column_[s + 1] - first_column_[s];
    const int m = row_offsets[s + 1] - row_offsets[s];
    store(s, rows.data() + row_offsets[s] + w, m - w, panels + panel_offsets[s], m, stored);
  }
  row_start_.push_back(static_cast<int>(rows_.size()));
}

void SupernodalFactor::store(int s, const int* R, int r, const double* panel, int m, std::size_t& stored) {
  const int w = first_column_[s + 1] - first_column_[s];
  widest_ = std::max(widest_, w);
  row_start_.push_back(static_cast<int>(rows_.size()));
  rows_.insert(rows_.end(), R, R + r);
  triangle_start_.push_back(static_cast<int>(stored));
  for (int k = 0; k + 1 < w; ++k) {
    const double* column = panel + static_cast<std::size_t>(k) * m;
    std::copy(column + k + 1, column + w, values_.data() + stored);
    stored += w - 1 - k;
  }
  block_start_.push_back(static_cast<int>(stored));
  double* block = values_.data() + stored;
  stored += static_cast<std::size_t>(r) * w;
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

template <int K>
void SupernodalFactor::sweeps(const Eigen::VectorXd& inv_d, double* y) const {
  const int count = supernodes();
  // A wide supernode's own columns, by column (column c at xt + c w), so
  // that the pair loops read them contiguously; and the backward sums.
  std::vector<double> xt(static_cast<std::size_t>(widest_) * K), acc(xt.size());
  // Forward: L z = y, supernode by supernode.
  for (int s = 0; s < count; ++s) {
    const int c0 = first_column_[s], w = first_column_[s + 1] - c0;
    double* x = y + static_cast<std::ptrdiff_t>(c0) * K;
    const int* R = rows_.data() + row_start_[s];
    const int r = row_start_[s + 1] - row_start_[s];
    const double* b = values_.data() + block_start_[s];
    if (w == 1) {  // most supernodes (the leaves): the simplicial column
      for (int i = 0; i < r; ++i) {
        double* yi = y + static_cast<std::ptrdiff_t>(R[i]) * K;
        for (int c = 0; c < K; ++c) yi[c] -= b[i] * x[c];
      }
      continue;
    }
    for (int k = 0; k < w; ++k) {
      for (int c = 0; c < K; ++c) xt[c * w + k] = x[k * K + c];
    }
    // The triangle, column by column: column k's entries (rows k+1 .. w-1)
    // are contiguous, and so are the values they update.
    const double* t = values_.data() + triangle_start_[s];
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
    double* x = y + static_cast<std::ptrdiff_t>(c0) * K;
    const int* R = rows_.data() + row_start_[s];
    const int r = row_start_[s + 1] - row_start_[s];
    const double* b = values_.data() + block_start_[s];
    if (w == 1) {
      double sum[K] = {};
      for (int i = r - 1; i >= 0; --i) {
        const double* yi = y + static_cast<std::ptrdiff_t>(R[i]) * K;
        for (int c = 0; c < K; ++c) sum[c] += b[i] * yi[c];
      }
      for (int c = 0; c < K; ++c) x[c] -= sum[c];
      continue;
    }
    // The block first (R's rows are final), then the triangle, last column
    // first; column k's entries follow the (w-1) + ... + (w-k) of the
    // columns before it.
    std::fill(acc.begin(), acc.begin() + w * K, 0.0);
    // The rows after the last group first (they are stored last).
    const int grouped = r - r % kRowBlock;
    for (int i = r - 1; i >= grouped; --i) {
      gather_rows<K, 1>(b + static_cast<std::ptrdiff_t>(i) * w, w, R + i, y, acc.data());
    }
    for (int i = grouped - kRowBlock; i >= 0; i -= kRowBlock) {
      gather_rows<K, kRowBlock>(b + static_cast<std::ptrdiff_t>(i) * w, w, R + i, y, acc.data());
    }
    for (int k = 0; k < w; ++k) {
      for (int c = 0; c < K; ++c) xt[c * w + k] = x[k * K + c] - acc[c * w + k];
    }
    const double* triangle = values_.data() + triangle_start_[s];
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
    case 1: sweeps<1>(inv_d, y); break;
    case 2: sweeps<2>(inv_d, y); break;
    case 3: sweeps<3>(inv_d, y); break;
    default:
      fail(ErrorCode::BadParameter, "SupernodalFactor::solve takes 1, 2 or 3 columns, not " + std::to_string(columns));
  }
}

}  // namespace aniso
