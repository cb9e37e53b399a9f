#pragma once
// Transfer of per-vertex quantities (positions, velocities, anything) from an old mesh to a new
// mesh of the same material domain: barycentric interpolation in material coordinates (seed 002
// §5.2 f–h does the same through a background grid; here the old mesh itself is the grid).
// Linear in the values and exact for any field affine in (u, v). A new vertex that is an old
// vertex (kept boundary vertices and pins) gets that vertex's values bit for bit.
//
// Positions of a curved cloth may be transferred with a quadratic correction instead
// (transfer_quadratic): the linear interpolant puts a new vertex on the old flat facet, inside
// the curved surface by about h²|κ|/8, which shortens the new edges across curved regions. For
// any smooth x(X), with e_i = X_i − X from the new point X to the old triangle's corners and
// b_i its barycentric weights (Σ b_i e_i = 0),
//   Σ b_i x(X_i) = x(X) + ½ Σ b_i H(e_i, e_i) + O(h³),
// with H(e, e) = x_uu e_u² + 2 x_uv e_u e_v + x_vv e_v², so
//   x(X) ≈ Σ b_i [x_i − ½ H_i(e_i, e_i)],
// H_i the second derivatives of the quadratic Taylor patch fitted at old vertex i for the
// curvature (curvature.h). The error drops from O(h²) to O(h³); the correction is zero for an
// affine field (to the fit's rounding), so affine fields and a flat cloth at rest are still
// reproduced; a vertex without a fitted patch contributes no correction.

#include <vector>

#include "base/enum_names.h"
#include "sim/remesh/point_locator.h"
#include "sim/remesh/remesh_types.h"

namespace weft::sim::remesh {

// How positions reach the new vertices (scene key simulation.remesh.transfer). Velocities are
// always linear.
enum class PositionTransfer {
  linear,     // barycentric interpolation (transfer): new vertices on the old mesh's flat facets
  quadratic,  // plus the fitted curvature patches' correction (transfer_quadratic): on the
              // curved surface rather than on its chords
};

inline constexpr base::EnumNames<PositionTransfer, 2> position_transfer_names{
    {{PositionTransfer::quadratic, "quadratic"}, {PositionTransfer::linear, "linear"}}};

// Where each new vertex lies in the old mesh: the old triangle and weights, or, for a kept old
// vertex (new_to_old[i] ≥ 0), that vertex alone (triangle −1, weights unused).
struct TransferMap {
  std::vector<Location> location;  // per new vertex
  std::vector<Index> new_to_old;   // per new vertex: the old vertex it is, or −1
};

// new_to_old may be empty (no vertex kept) or have one entry per new vertex.
TransferMap make_transfer_map(const PointLocator& old_mesh, const Matrix2X& new_material,
                              const std::vector<Index>& new_to_old);

// The old mesh's #V_old×k values, evaluated at the new vertices: #V_new×k. `old_triangles`
// must be the triangles the locator was built on.
MatrixX transfer(const TransferMap& map, const Triangles& old_triangles, const MatrixX& values);

// The same for #V×3 arrays (positions, velocities).
Matrix3X transfer(const TransferMap& map, const Triangles& old_triangles, const Matrix3X& values);

// #V_old second derivatives of x(u, v), 1/m: columns x_uu (0–2), x_uv (3–5), x_vv (6–8).
using SecondDerivatives = Eigen::Matrix<double, Eigen::Dynamic, 9, Eigen::RowMajor>;

// Positions (#V_old×3, m) at the new vertices with the quadratic correction above: #V_new×3.
// old_material: the #V_old×2 material coordinates the map was made on.
Matrix3X transfer_quadratic(const TransferMap& map, const Matrix2X& old_material,
                            const Triangles& old_triangles, const Matrix3X& positions,
                            const SecondDerivatives& second_derivatives);

}  // namespace weft::sim::remesh
