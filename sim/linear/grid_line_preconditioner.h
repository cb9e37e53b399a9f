#pragma once
// Line solves on the cloth's warp/weft vertex grid: a preconditioner of implicit Euler's
// conjugate gradients (block_conjugate_gradient.h), exact along grid lines.
//
// What makes the implicit step's system stiff on a grid cloth is its shear springs (the
// diagonals of each cell, k = G for square cells, so h²k/m grows as the vertex count: 62 at
// 64² with wool's G and h = 1/120 s) and, once it hangs, the tension it carries along its warp
// or weft. Point block Jacobi removes the error that varies from vertex to vertex only, and
// conjugate gradients spend their iterations on the rest. But each of these couplings acts
// along one line of the grid and in one direction: a ↗ diagonal's shear spring pulls along ↗
// (its block is −h²k d dᵀ at rest), a ↘ one along ↘, tension along its edge, bending across
// the sheet. So each vertex gets a frame: its first two axes the orthonormal pair nearest the
// axes of its ↗ and ↘ shear springs (as near the one as the other, so that a mirrored cloth
// gets mirrored frames), its third the normal — or the pair nearest its warp and weft springs,
// where those are the more directional couplings (a mass-spring cloth, whose warp and weft are
// far stiffer than its shear). Each of the three components of the displacement in those
// frames is solved exactly along the lines of one family (u, v, ↗ or ↘: the one whose coupling
// of that component weighs most), a scalar tridiagonal system per line (the Thomas
// algorithm). With B the block diagonal over lines of Vᵀ A V (V the frames), the
// preconditioner is V B⁻¹ Vᵀ: symmetric, and positive definite when
// every line's pivot is. For a flat sheet held by its shear springs alone it is A⁻¹.
//
// The line solves drop what couples a vertex's own components in its frame. A contact that
// implicit Euler holds by a penalty κ n nᵀ (κ a million times the block's scale) would leave
// most of itself there, so where a vertex's own stiffness (its block row's sum: what does not
// couple it to other vertices) is far from isotropic, the axis of that stiffness replaces the
// frame's axis nearest it.
//
// update() costs about as much as a dozen products with A (the frames, the choice of families,
// the factorization: 11 % of the 64² hang's profile, against 9 % for its ~9 products a step);
// apply() about one product. The couplings across lines (the other family's springs, tension
// across the sheet) are left to conjugate gradients.
//
// One thread, one fixed order: the result is the same bits for any thread count.

#include <algorithm>
#include <vector>

#include <Eigen/Core>

#include "sim/linear/block_sparse_matrix.h"
#include "sim/types.h"

namespace weft::sim {

class GridLinePreconditioner {
 public:
  static constexpr int kFamilies = 4;  // lines along u, v, and the two diagonals

  // For matrices of `pattern`'s pattern on an nu × nv vertex grid (vertex (i, j) is block row
  // j·nu + i).
  GridLinePreconditioner(const BlockSparseMatrix& pattern, Index nu, Index nv);

  // Factors the lines of A's current values; false when a pivot is not positive.
  bool update(const BlockSparseMatrix& A);
  // z = B r (B symmetric positive definite after a successful update()).
  void apply(const Eigen::VectorXd& r, Eigen::VectorXd& z) const;

 private:
  struct Family {
    std::vector<Index> order;            // every vertex once, line after line
    std::vector<Index> previous_vertex;  // per position in order: the line's previous vertex, −1
    std::vector<int> previous, next;     // per vertex: the block (p, previous), (p, next), −1 none
  };
  struct Component {
    int family = 0;
    std::vector<double> inverse_pivot, lower;  // per position in the family's order: 1/d_k, l_k
  };
  void update_frames(const BlockSparseMatrix& A);
  // The choices of frames and families read every sample_stride()-th vertex: about
  // kSampledVertices of them, whatever the grid.
  static constexpr Index kSampledVertices = 1024;
  Index sample_stride() const { return std::max<Index>(1, m_nu * m_nv / kSampledVertices); }
  bool factor(const BlockSparseMatrix& A, int c);

  Index m_nu = 0, m_nv = 0;
  Family m_family[kFamilies];
  Component m_component[3];
  std::vector<Eigen::Matrix3d> m_frame;  // per vertex, its axes as columns
  mutable Eigen::VectorXd m_local;       // apply()'s scratch, in the vertices' frames
};

}  // namespace weft::sim
