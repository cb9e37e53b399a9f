#pragma once
// A geometric multigrid V-cycle on the cloth's warp/weft vertex grid: the preconditioner of
// implicit Euler's conjugate gradients (block_conjugate_gradient.h) on grid meshes.
//
// Block Jacobi's iteration count grows with the resolution (37, 48, 83 iterations a step at
// 64², 128², 256² on the two-corner hang), because the shear springs and the string stiffness
// of a taut cloth couple it over its whole extent (h²k/m grows as the vertex count), and a point smoother removes only the error that varies from vertex
// to vertex. A grid hierarchy removes the smooth error on coarser grids, where it varies fast:
//   - level l + 1 keeps every other vertex of level l along warp and weft (nu/2 + 1 of nu: the
//     last vertex of an even row then has one coarse neighbour beyond it);
//   - P, level l + 1 → l, is bilinear: a kept vertex copies its coarse vertex, one between two
//     takes their mean, one in a cell's middle the mean of four (weights 1, ½, ¼ per 3×3 block,
//     the same for x, y and z);
//   - the coarse matrix is Pᵀ A P (Galerkin), SPD when A is, rebuilt by update() in one pass
//     over the fine blocks; coarse block rows are addressed through a table of their stencil
//     (every block within a radius that covers PᵀAP's coupling);
//   - the cycle: damped block Jacobi (ω = kSmoothingWeight) before and after the coarse
//     correction, and a dense Cholesky factor on the coarsest grid (at most kCoarsestRows
//     vertices). The same smoother before and after makes the cycle a symmetric operator, as
//     conjugate gradients require.
// A coarse vertex that no fine coupling reaches (the grid's unused vertices, a pin's
// identity row) gets an identity diagonal block, which keeps its level nonsingular.
//
// Everything here runs on one thread in a fixed order except the fine products, which
// BlockSparseMatrix shares by rows: the cycle's result is the same bits for any thread count.

#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include <Eigen/Cholesky>
#include <Eigen/Core>

#include "sim/linear/block_sparse_matrix.h"
#include "sim/types.h"

namespace weft::sim {

class GridMultigrid {
 public:
  static constexpr double kSmoothingWeight = 0.6;
  static constexpr Index kCoarsestRows = 16;

  // The hierarchy for matrices of `fine`'s pattern on an nu × nv vertex grid (vertex (i, j) is
  // block row j·nu + i). Returns nothing when the grid is too small to coarsen, or the pattern
  // couples vertices farther apart than a few grid steps (then it is not a grid operator).
  static std::optional<GridMultigrid> make(const BlockSparseMatrix& fine, Index nu, Index nv);

  // The coarse matrices PᵀAP of `fine`'s current values and their smoothers and factor.
  void update(const BlockSparseMatrix& fine);
  // z = B r, one V-cycle from zero (B symmetric, positive definite when A is and the smoother
  // converges). `fine_inverse`: the inverses of fine's diagonal blocks.
  void apply(const BlockSparseMatrix& fine, const std::vector<Eigen::Matrix3d>& fine_inverse,
             const Eigen::VectorXd& r, Eigen::VectorXd& z, base::ThreadPool* pool) const;
  int levels() const { return static_cast<int>(m_levels.size()) + 1; }
  // Level l's matrix (1 ≤ l < levels(); level 0 is the fine matrix) and grid width.
  const BlockSparseMatrix& coarse_matrix(int l) const { return m_levels[static_cast<std::size_t>(l - 1)].A; }
  Index coarse_nu(int l) const { return m_levels[static_cast<std::size_t>(l - 1)].nu; }

 private:
  // A coarse level: its grid, its matrix, and where each stencil offset of a row is stored.
  struct Level {
    Index nu = 0, nv = 0;
    int radius = 0;  // the stencil's reach in grid steps
    BlockSparseMatrix A;
    std::vector<int> slot;  // per row, (2·radius + 1)² offsets (du fastest): block index, −1 none
    // Per off-diagonal block of the level above (the fine matrix for the first), its column's
    // grid offset from its row: the Galerkin pass needs no division.
    std::vector<std::int8_t> above_du, above_dv;
    std::vector<Eigen::Matrix3d> inverse;
    mutable Eigen::VectorXd b, x, t;  // the cycle's right-hand side, iterate, residual
  };
  struct Parent {
    Index i, j, vertex;  // the coarse vertex (i, j), j·nu + i
    double weight;
  };

  GridMultigrid() = default;
  // Level `into`'s blocks += PᵀAP of the level above (the fine matrix for into = 0).
  void accumulate_galerkin(const BlockSparseMatrix& A, Index nu, std::size_t into);
  // The coarse vertices of vertex (i, j) and their weights (1, 2 or 4 of them); returns how many.
  static int parents(Index i, Index j, Index coarse_nu, Parent* out);
  // coarse.b = Pᵀ fine, and fine += P coarse.x; nu: the fine level's width.
  void restrict_to(const Level& coarse, Index nu, const Eigen::VectorXd& fine) const;
  void prolong_from(const Level& coarse, Index nu, Eigen::VectorXd& fine) const;
  void cycle(std::size_t level, const BlockSparseMatrix& A, const std::vector<Eigen::Matrix3d>& inverse,
             Index nu, const Eigen::VectorXd& b, Eigen::VectorXd& x, Eigen::VectorXd& t,
             base::ThreadPool* pool) const;

  Index m_fine_nu = 0, m_fine_nv = 0;
  std::vector<Level> m_levels;            // coarse levels, finest first
  Eigen::LLT<Eigen::MatrixXd> m_coarsest;  // the last level's dense factor
  bool m_coarsest_ok = false;
  mutable Eigen::VectorXd m_fine_residual;  // the cycle's scratch on the fine grid
};

}  // namespace weft::sim
