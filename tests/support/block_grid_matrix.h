#pragma once
// Test support, part of no library: symmetric positive definite 3×3-block matrices with the
// coupling of a cloth grid, for the conjugate-gradient and multigrid tests.

#include <random>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "sim/linear/sparse_spd_solver.h"

namespace weft::sim::test_matrices {

// n×n vertices (vertex (i, j) at j·n + i), a random SPD 3×3 block H on each grid edge and
// diagonal (a spring's [H −H; −H H]) scaled by `stiffness`, with `both_diagonals` on each
// cell's other diagonal too, and, with `reach2`, on each pair two steps apart along warp or
// weft (a bending spring's coupling), plus `mass` on the diagonal. The full matrix.
inline SparseMatrix grid_system(int n, double mass, unsigned seed, double stiffness = 1.0,
                                bool reach2 = false, bool both_diagonals = false) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<Eigen::Triplet<double, int>> t;
  const auto add_block = [&](int p, int q, const Eigen::Matrix3d& b) {
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) t.emplace_back(3 * p + r, 3 * q + c, b(r, c));
  };
  for (int v = 0; v < n * n; ++v) add_block(v, v, mass * Eigen::Matrix3d::Identity());
  const auto spring = [&](int a, int b) {
    Eigen::Matrix3d g;
    for (int k = 0; k < 9; ++k) g(k / 3, k % 3) = u(rng);
    const Eigen::Matrix3d H = stiffness * (g * g.transpose() + 0.1 * Eigen::Matrix3d::Identity());
    add_block(a, a, H);
    add_block(b, b, H);
    add_block(a, b, -H);
    add_block(b, a, -H);
  };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const int v = j * n + i;
      if (i + 1 < n) spring(v, v + 1);
      if (j + 1 < n) spring(v, v + n);
      if (i + 1 < n && j + 1 < n) spring(v, v + n + 1);
      if (both_diagonals && i > 0 && j + 1 < n) spring(v, v + n - 1);
      if (reach2 && i + 2 < n) spring(v, v + 2);
      if (reach2 && j + 2 < n) spring(v, v + 2 * n);
    }
  SparseMatrix A(3 * n * n, 3 * n * n);
  A.setFromTriplets(t.begin(), t.end());
  A.makeCompressed();
  return A;
}

// The lower triangle of `full`, compressed: what the solvers take.
inline SparseMatrix lower_triangle(const SparseMatrix& full) {
  SparseMatrix l = full.triangularView<Eigen::Lower>();
  l.makeCompressed();
  return l;
}

inline Eigen::VectorXd random_vector(Eigen::Index n, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> g;
  Eigen::VectorXd b(n);
  for (Eigen::Index i = 0; i < n; ++i) b[i] = g(rng);
  return b;
}

}  // namespace weft::sim::test_matrices
