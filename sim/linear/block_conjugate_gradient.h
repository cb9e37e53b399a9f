#pragma once
// Conjugate gradients for implicit Euler's 3#V system (sim/integrators/implicit_euler.h), with
// a 3×3 block-Jacobi preconditioner (the inverse of each vertex's diagonal block) and the
// matrix–vector product shared among threads.
//
// The system arrives as SparseSpdSolver takes it: the lower triangle, column-major. analyze()
// builds a full (both triangles) copy of its pattern in 3×3 blocks (block compressed rows: one
// column index per 9 values) once; set_matrix() gathers the values into it. Each thread
// multiplies a contiguous range of block rows, and every block row is summed in one fixed
// order, so the product — and with the sequential vector updates and dot products, every
// iterate — is the same bits for any number of threads.
//
// On a warp/weft grid (analyze() given its size) the preconditioner is instead a geometric
// multigrid V-cycle (grid_multigrid.h), whose iteration count does not grow with the
// resolution, or exact solves along the grid's lines in each vertex's shear frame
// (grid_line_preconditioner.h), which remove the stiff shear and tension couplings at the cost
// of about one product. Should the cycle not be positive definite for some matrix (a
// breakdown), that solve is redone with block Jacobi; should a line's factorization fail, that
// matrix is preconditioned by block Jacobi.
//
// The lines cost about a dozen products to set up and one to apply, against about a ninth of
// one for block Jacobi (one block a row, where the product reads nine): they pay where block
// Jacobi would take many iterations (a taut hanging cloth at a time step of 1/120 s: 37 at
// 64²), and cost time where it takes few (the shorter steps of a drape: about 4). With
// GridPreconditioner::lines_when_slow each solve starts with block Jacobi; after
// kProbeIterations, if the residual's mean rate of decrease so far predicts more than
// kSlowIterations in all, the lines are set up and the solve goes on with them from the iterate
// reached. The first iterations remove the error fastest: on the 64² hang the rate of the
// first four predicted 9–30 iterations where the solves took 36–59, hence the low bar.
//
// Stops at ‖b − A x‖ ≤ tolerance ‖b‖ (the convention of Eigen::ConjugateGradient, which this
// replaces) or after max_iterations; either way x is the last iterate.

#include <cstddef>
#include <memory>
#include <vector>

#include <Eigen/LU>
#include <Eigen/SparseCore>

#include "base/thread_pool.h"
#include "sim/linear/block_sparse_matrix.h"
#include "sim/linear/grid_line_preconditioner.h"
#include "sim/linear/grid_multigrid.h"
#include "sim/linear/sparse_spd_solver.h"

namespace weft::sim {

class BlockConjugateGradient {
 public:
  struct Result {
    int iterations = 0;
    double relative_residual = 0.0;  // ‖b − A x‖ / ‖b‖ at the end
    bool breakdown = false;  // a non-positive curvature pᵀAp or preconditioner rᵀz: A or its
                             // diagonal blocks are not positive definite, or not finite
  };

  // threads: as base::thread_count (0 = all hardware threads).
  explicit BlockConjugateGradient(int threads);
  ~BlockConjugateGradient();

  enum class GridPreconditioner { multigrid, lines, lines_when_slow };
  static constexpr int kProbeIterations = 6;
  static constexpr int kSlowIterations = 10;
  // The pattern of `lower` (square, 3k rows, lower triangle, compressed). Once per pattern.
  // grid_nu × grid_nv = k: the vertices form that warp/weft grid (vertex (i, j) is block row
  // j·grid_nu + i), and `grid` preconditions where it can (0 × 0: block Jacobi).
  void analyze(const SparseMatrix& lower, Index grid_nu = 0, Index grid_nv = 0,
               GridPreconditioner grid = GridPreconditioner::multigrid);
  // The values of `lower` (the analysed pattern), the inverses of its 3×3 diagonal blocks and
  // the multigrid's coarse matrices.
  void set_matrix(const SparseMatrix& lower);
  // From the initial guess x (resized to b's size and zeroed if its size differs).
  Result solve(const Eigen::VectorXd& b, Eigen::VectorXd& x, double tolerance,
               int max_iterations);

  // y = A x (y sized like x beforehand).
  void multiply(const Eigen::VectorXd& x, Eigen::VectorXd& y) const;
  const BlockSparseMatrix& matrix() const { return m_matrix; }
  // The multigrid's levels, the fine grid's included; 0 without one.
  int multigrid_levels() const;
  // Whether the last set_matrix() left the line preconditioner in use (false: none, or a
  // line's factorization failed and block Jacobi preconditions); with lines_when_slow, whether
  // the last solve went on with them.
  bool lines_in_use() const { return m_line && m_line_ok; }

 private:
  // Where each stored value of the block matrix comes from: its index in the lower triangle's
  // values (a value above the diagonal: its mirror's), −1 for none.
  struct Sources {
    std::vector<int> diagonal, off_diagonal;  // 9 per block, as the block matrix stores them
    Eigen::Index nonzeros = 0;                // of the analysed lower triangle
    int& at(const BlockSparseMatrix& matrix, int row, int col);
  };
  enum class Preconditioner { block_jacobi, multigrid, lines };
  // probe > 0: after `probe` iterations, stop (slow) if the rate so far predicts more
  // than kSlowIterations.
  struct Iteration {
    Result result;
    bool slow = false;
  };
  Iteration iterate(const Eigen::VectorXd& b, Eigen::VectorXd& x, double tolerance,
                    int max_iterations, Preconditioner preconditioner, int probe = 0) const;
  void precondition(const Eigen::VectorXd& r, Eigen::VectorXd& z, Preconditioner which) const;
  static bool slow(double start_norm2, double now_norm2, double threshold, int done);

  std::unique_ptr<base::ThreadPool> m_pool;
  BlockSparseMatrix m_matrix;
  Sources m_source;
  std::vector<Eigen::Matrix3d> m_block_inverse;  // per vertex
  std::unique_ptr<GridMultigrid> m_multigrid;
  std::unique_ptr<GridLinePreconditioner> m_line;
  bool m_line_ok = false;  // the last set_matrix() factored every line
  bool m_line_when_slow = false;  // GridPreconditioner::lines_when_slow
  bool m_line_current = false;    // … and the lines were set up for the current matrix
};

}  // namespace weft::sim
