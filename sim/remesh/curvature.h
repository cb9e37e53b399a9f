#pragma once
// Curvature of the deformed cloth, per vertex: the largest principal curvature magnitude |κ| of
// the surface x(u, v), the refinement indicator of seed 002 §5.1 (eq. 28–29).
//
// Estimate: at each vertex a quadratic Taylor patch of the deformation map is fitted in
// material coordinates by least squares over the vertex's two-ring,
//   x(X_k) − x(X_i) ≈ J d_k + ½ (x_uu d_u² + 2 x_uv d_u d_v + x_vv d_v²),  d_k = X_k − X_i,
// which gives the first fundamental form I = JᵀJ, the normal n ∝ x_u × x_v, the second
// fundamental form II_pq = n·x_pq and the shape operator I⁻¹ II, whose eigenvalues are the
// principal curvatures. This is seed 002's eq. 7 (κ_pq = nᵀ U,pq from a patch of nodes around
// the triangle) with the metric I kept, so it stays right when the cloth stretches, and taken
// per vertex with the invariant max |κ_i| instead of the frame-dependent norm of
// (κ_xx, κ_yy, 2κ_xy) (which gives √2/R on a sphere and depends on the fold's direction).
// On a symmetric two-ring the cubic terms of x cancel, so the error is O(h²/R²).

#include <Eigen/Core>
#include <vector>

#include "sim/remesh/remesh_types.h"

namespace weft::sim::remesh {

// The fitted quadratic Taylor patch of x(u, v) at one vertex: its first derivatives (m/m) and
// second derivatives (1/m) in material coordinates. valid = false where no stencil within three
// rings carries the fit, or the fitted surface has no normal there.
struct VertexPatch {
  bool valid = false;
  Vec3 x_u = Vec3::Zero(), x_v = Vec3::Zero();
  Vec3 x_uu = Vec3::Zero(), x_uv = Vec3::Zero(), x_vv = Vec3::Zero();
};

// The patch of every vertex (two rings; three where a corner's two-ring is too small).
// material: #V×2 (m); triangles: #T×3; positions: #V×3 (m).
std::vector<VertexPatch> vertex_patches(const Matrix2X& material, const Triangles& triangles,
                                        const Matrix3X& positions);

// |κ|max of a patch (1/m): the larger principal curvature magnitude; 0 for an invalid patch.
double patch_curvature(const VertexPatch& patch);

// The per-vertex |κ|max of the patches: #V, 1/m.
Eigen::VectorXd patch_curvatures(const std::vector<VertexPatch>& patches);

// #V max principal curvature magnitudes, 1/m (patch_curvatures of vertex_patches). material: #V×2 (m); triangles: #T×3;
// positions: #V×3 world positions (m). A vertex whose stencil cannot carry a quadratic fit
// (fewer than 5 points in general position within three rings) gets 0.
Eigen::VectorXd vertex_curvature(const Matrix2X& material, const Triangles& triangles,
                                 const Matrix3X& positions);

// The principal curvatures (κ1 ≥ κ2) of a surface from its first and second fundamental forms,
// both symmetric 2×2 in the same parameters; I must be positive definite.
Eigen::Vector2d principal_curvatures(const Eigen::Matrix2d& first_form,
                                     const Eigen::Matrix2d& second_form);

}  // namespace weft::sim::remesh
