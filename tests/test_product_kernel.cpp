// multiply_by_transpose (base/product_kernel.h), the supernodal
// factorization's update product: C = A B^T on column blocks inside larger
// panels (leading dimensions above the block sizes), for every remainder of
// its 4-by-4 register blocks, against Eigen's product.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

#include <Eigen/Core>

#include "base/product_kernel.h"

using namespace aniso;

TEST_CASE("product kernel: A B^T on blocks of every shape equals Eigen's product", "[laplacian]") {
  // Panels larger than the blocks, so that the strides are exercised.
  const Eigen::MatrixXd A_panel = Eigen::MatrixXd::Random(23, 11);
  const Eigen::MatrixXd B_panel = Eigen::MatrixXd::Random(17, 11);
  for (int rows : {1, 2, 3, 4, 5, 8, 13, 20}) {
    for (int cols : {1, 3, 4, 6, 9, 14}) {
      for (int depth : {0, 1, 2, 7, 11}) {
        INFO(rows << " x " << cols << ", depth " << depth);
        const auto A = A_panel.block(2, 0, rows, depth);
        const auto B = B_panel.block(1, 0, cols, depth);
        Eigen::MatrixXd C_panel = Eigen::MatrixXd::Constant(25, 16, 7.0);
        multiply_by_transpose(A.data(), static_cast<int>(A_panel.rows()), B.data(), static_cast<int>(B_panel.rows()),
                              rows, cols, depth, C_panel.data() + 1, static_cast<int>(C_panel.rows()));
        const Eigen::MatrixXd expected = A * B.transpose();
        CHECK((C_panel.block(1, 0, rows, cols) - expected).cwiseAbs().maxCoeff() <= 1e-14);
        // Nothing outside the block is written.
        CHECK(C_panel.row(0).cwiseEqual(7.0).all());
        CHECK(C_panel.bottomRows(24 - rows).cwiseEqual(7.0).all());
        CHECK(C_panel.rightCols(16 - cols).cwiseEqual(7.0).all());
      }
    }
  }
}

TEST_CASE("product kernel: the lower variant computes every entry on and below the diagonal", "[laplacian]") {
  const Eigen::MatrixXd A_panel = Eigen::MatrixXd::Random(23, 11);
  const Eigen::MatrixXd B_panel = Eigen::MatrixXd::Random(17, 11);
  for (int rows : {1, 3, 4, 5, 8, 13, 20}) {
    for (int cols : {1, 3, 4, 6, 9, 14}) {
      if (cols > rows) continue;  // as the factorization's updates: at least as many rows
      for (int depth : {1, 7, 11}) {
        INFO(rows << " x " << cols << ", depth " << depth);
        const auto A = A_panel.block(2, 0, rows, depth);
        const auto B = B_panel.block(1, 0, cols, depth);
        Eigen::MatrixXd C_panel = Eigen::MatrixXd::Constant(25, 16, 7.0);
        multiply_by_transpose(A.data(), static_cast<int>(A_panel.rows()), B.data(), static_cast<int>(B_panel.rows()),
                              rows, cols, depth, C_panel.data() + 1, static_cast<int>(C_panel.rows()), true);
        const Eigen::MatrixXd expected = A * B.transpose();
        const Eigen::MatrixXd C = C_panel.block(1, 0, rows, cols);
        int skipped = 0;
        for (int j = 0; j < cols; ++j) {
          for (int i = 0; i < rows; ++i) {
            if (i >= j) CHECK(std::abs(C(i, j) - expected(i, j)) <= 1e-14);
            // A 4-by-4 block wholly above the diagonal is not computed.
            if (j >= 4 && i < (j / 4) * 4 && j < (cols / 4) * 4 && C(i, j) == 7.0) ++skipped;
          }
        }
        int above = 0;
        for (int j = 4; j < (cols / 4) * 4; ++j) above += std::min(rows, (j / 4) * 4);
        CHECK(skipped == above);
        CHECK(C_panel.rightCols(16 - cols).cwiseEqual(7.0).all());
      }
    }
  }
}
