#pragma once
// One adaptive remeshing step (seed 002 §5.2 e–h): curvature of the deformed
// cloth → target sizes (eq. 29) → a new mesh of the material domain graded by them (CGAL
// Delaunay refinement, boundary and pins kept) → positions and velocities interpolated onto it.
// When to call it (every N steps, or when remesh_indicator passes a threshold) is the caller's.

#include <Eigen/Core>
#include <vector>

#include "sim/remesh/curvature.h"
#include "sim/remesh/mesher.h"
#include "sim/remesh/remesh_types.h"
#include "sim/remesh/size_field.h"
#include "sim/remesh/transfer.h"

namespace weft::sim::remesh {

struct RemeshParams {
  SizeFieldParams size;
  MesherParams mesher;
  PositionTransfer positions = PositionTransfer::quadratic;
};

struct RemeshInput {
  Matrix2X material;        // #V×2 rest (u, v), metres
  Triangles triangles;      // #T×3
  Matrix3X positions;       // #V×3 world positions, metres
  Matrix3X velocities;      // #V×3, m/s
  std::vector<Index> pins;  // vertices to keep exactly (besides the boundary, which is kept)
};

struct RemeshOutput {
  MeshResult mesh;                  // the new material coordinates, triangles, new → old vertex
  Matrix3X positions;               // #V_new×3, interpolated (kept vertices copied)
  Matrix3X velocities;              // #V_new×3
  TransferMap transfer;             // to carry further per-vertex quantities (transfer.h)
  Eigen::VectorXd old_curvature;    // #V_old |κ| (1/m) the sizes came from
  Eigen::VectorXd old_target_size;  // #V_old h_target (m), eq. 29
  // Wall time of the phases, seconds: curvature, sizes and the old mesh's point locator; the
  // CGAL mesher (with its size queries); locating the new vertices and interpolating.
  double curvature_s = 0.0, mesher_s = 0.0, transfer_s = 0.0;
};

// The second derivatives of the fitted patches as transfer_quadratic takes them: #V×9, zero for
// a vertex without a valid patch (no correction there).
SecondDerivatives patch_second_derivatives(const std::vector<VertexPatch>& patches);

// Throws std::invalid_argument naming the array or parameter on bad input.
RemeshOutput remesh(const RemeshInput& input, const RemeshParams& params);

}  // namespace weft::sim::remesh
