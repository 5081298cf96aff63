#include "geometry/supernodal_factor.h"

#include <algorithm>
#include <cstddef>
#include <string>
#include <utility>

#include "anisoform/error.h"
#include "base/simd_pair.h"
#include "base/vector_kernels.h"

namespace aniso {

namespace {

// Rows of a supernode's block taken together in the sweeps: each value of
// the right-hand side loaded serves them all.
constexpr int kRowBlock = 2;
// Columns copied together into the row-major block: a cache line of each
// destination row per pass, each source column read in order.
constexpr int kCopyTile = 8;

// The sweeps multiply and add two consecutive columns k, k+1 of a
// supernode at a time (base/simd_pair.h).

// Forward: y[R[i]] -= B_i x for Rows rows B_i (w values each, consecutive);
// xt holds x by column (column c's w values at xt + c w).
template <int K, int Rows>
void subtract_rows(const double* b, int w, const double* xt, const int* R, double* y) {
  Pair acc[Rows][K] = {};
  int k = 0;
  for (; k + 2 <= w; k += 2) {
    Pair xk[K];
    for (int c = 0; c < K; ++c) xk[c] = load_pair(xt + c * w + k);
    for (int i = 0; i < Rows; ++i) {
      const Pair bk = load_pair(b + i * w + k);
      for (int c = 0; c < K; ++c) acc[i][c] += bk * xk[c];
    }
  }
  for (int i = 0; i < Rows; ++i) {
    double* yi = y + static_cast<std::ptrdiff_t>(R[i]) * K;
    for (int c = 0; c < K; ++c) {
      double sum = acc[i][c][0] + acc[i][c][1];
      if (k < w) sum += b[i * w + k] * xt[c * w + k];
      yi[c] -= sum;
    }
  }
}

// Backward: acc += sum_i B_i^T y[R[i]] over Rows rows, acc by column (column
// c's w sums at acc + c w), each sum taking the rows in order.
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
  int k = 0;
  for (; k + 2 <= w; k += 2) {
    Pair bk[Rows];
    for (int i = 0; i < Rows; ++i) bk[i] = load_pair(b + i * w + k);
    for (int c = 0; c < K; ++c) {
      Pair a = load_pair(acc + c * w + k);
      for (int i = 0; i < Rows; ++i) a += bk[i] * yp[i][c];
      store_pair(acc + c * w + k, a);
    }
  }
  if (k < w) {
    for (int c = 0; c < K; ++c) {
      double a = acc[c * w + k];
      for (int i = 0; i < Rows; ++i) a += b[i * w + k] * yr[i][c];
      acc[c * w + k] = a;
    }
  }
}

}  // namespace

SupernodalFactor::SupernodalFactor(int n, std::vector<int> first_column, const std::vector<int>& row_offsets,
                                   const std::vector<int>& rows, const std::vector<std::size_t>& panel_offsets,
                                   const double* panels)
    : n_(n), first_column_(std::move(first_column)) {
  for (int s = 0; s < supernodes(); ++s) {
    const int w = first_column_[s + 1] - first_column_[s];
    const int m = row_offsets[s + 1] - row_offsets[s];
    const double* panel = panels + panel_offsets[s];
    store(s, rows.data() + row_offsets[s] + w, m - w,
          [&](int p, int k) { return panel[static_cast<std::size_t>(k) * m + p]; });
  }
  row_start_.push_back(static_cast<int>(rows_.size()));
}

template <typename Entry>
void SupernodalFactor::store(int s, const int* R, int r, const Entry& entry) {
  const int w = first_column_[s + 1] - first_column_[s];
  widest_ = std::max(widest_, w);
  row_start_.push_back(static_cast<int>(rows_.size()));
  rows_.insert(rows_.end(), R, R + r);
  triangle_start_.push_back(static_cast<int>(values_.size()));
  for (int k = 0; k + 1 < w; ++k) {
    for (int p = k + 1; p < w; ++p) values_.push_back(entry(p, k));
  }
  block_start_.push_back(static_cast<int>(values_.size()));
  values_.resize(values_.size() + static_cast<std::size_t>(r) * w);
  double* block = values_.data() + block_start_.back();
  for (int k0 = 0; k0 < w; k0 += kCopyTile) {
    const int k1 = std::min(w, k0 + kCopyTile);
    for (int i = 0; i < r; ++i) {
      for (int k = k0; k < k1; ++k) block[i * w + k] = entry(w + i, k);
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
    for (int k = 0; k + 1 < w; t += w - 1 - k, ++k) {
      for (int c = 0; c < K; ++c) {
        double* column = xt.data() + c * w;
        const double xk = column[k];
        for (int m = k + 1; m < w; ++m) column[m] -= t[m - k - 1] * xk;
      }
    }
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
  // Backward: L^T x = z, supernodes in reverse.
  for (int s = count - 1; s >= 0; --s) {
    const int c0 = first_column_[s], w = first_column_[s + 1] - c0;
    double* x = y + static_cast<std::ptrdiff_t>(c0) * K;
    const int* R = rows_.data() + row_start_[s];
    const int r = row_start_[s + 1] - row_start_[s];
    const double* b = values_.data() + block_start_[s];
    if (w == 1) {
      double sum[K] = {};
      for (int i = 0; i < r; ++i) {
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
    int i = 0;
    for (; i + kRowBlock <= r; i += kRowBlock, b += kRowBlock * w) {
      gather_rows<K, kRowBlock>(b, w, R + i, y, acc.data());
    }
    for (; i < r; ++i, b += w) gather_rows<K, 1>(b, w, R + i, y, acc.data());
    for (int k = 0; k < w; ++k) {
      for (int c = 0; c < K; ++c) xt[c * w + k] = x[k * K + c] - acc[c * w + k];
    }
    const double* triangle = values_.data() + triangle_start_[s];
    for (int k = w - 2; k >= 0; --k) {
      const double* t = triangle + k * (w - 1) - k * (k - 1) / 2;
      for (int c = 0; c < K; ++c) xt[c * w + k] -= dot(t, xt.data() + c * w + k + 1, static_cast<std::size_t>(w - 1 - k));
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
