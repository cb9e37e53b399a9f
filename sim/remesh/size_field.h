#pragma once
// Target element size from the curvature, and the remeshing criterion (seed 002 §5.1).
//
// Eq. 29 of seed 002: h_new is the size at which |κ| h_new² equals a preset constant c,
//   h_new = √(c / |κ|),   h_target = clamp(h_new, h_lower, h_upper),
// (eq. 28, Volkov & Li 2005: refine where |κ| h² exceeds a prescribed value). |κ| h is the
// non-dimensional relative curvature; the extra h makes the field smoother (seed 002 §5.1), and
// c has the unit of a length. Flat cloth (|κ| = 0) gets h_upper.

#include <Eigen/Core>

#include "sim/remesh/remesh_types.h"

namespace weft::sim::remesh {

struct SizeFieldParams {
  double c_m = 1e-3;       // eq. 29's constant: |κ| h² at the target size, metres
  double h_min_m = 0.005;  // h_lower of eq. 29: the finest edge, metres
  double h_max_m = 0.05;   // h_upper: the coarsest edge, metres
};

// Throws std::invalid_argument naming the parameter unless 0 < h_min ≤ h_max and c > 0, all
// finite.
void check_size_field_params(const SizeFieldParams& params);

// Eq. 29 for one curvature magnitude |κ| (1/m, ≥ 0): the target edge length, metres.
double target_size(double curvature_magnitude, const SizeFieldParams& params);

// Eq. 29 per vertex.
Eigen::VectorXd target_sizes(const Eigen::VectorXd& curvature, const SizeFieldParams& params);

// Mean material edge length of each triangle: the h of eq. 28 ("the average side length").
Eigen::VectorXd triangle_sizes(const Matrix2X& material, const Triangles& triangles);

// The remeshing criterion of seed 002 §5.2 d: max over triangles of |κ_t| h_t², with |κ_t| the
// mean of the triangle's vertex curvatures and h_t its mean side length. What a remesh cannot
// refine does not count, so that a fold sharper than h_min allows does not call for a remesh at
// every check: a triangle already at h_min or finer (h_t ≤ h_min) is left out, and |κ_t| is
// capped at c / h_min², the curvature at which eq. 29 reaches h_min (so a triangle counts at most
// c h_t²/h_min²). Metres; remesh when it exceeds a threshold above c (after a remesh it is about
// c where the cloth is curved).
double remesh_indicator(const Matrix2X& material, const Triangles& triangles,
                        const Eigen::VectorXd& curvature, const SizeFieldParams& params);

// The coarsening criterion (docs/remeshing.md, "Coarsening under the indicator"): how many
// times more triangles the mesh has than one graded by eq. 29 for this curvature,
//   (Σ_t A_t / h_t²) / (Σ_t A_t / h_target,t²),
// with A_t the triangle's material area, h_t its mean side and h_target,t eq. 29 of |κ_t| (the
// mean of its vertex curvatures, as in remesh_indicator). A triangle of side h covers an area
// proportional to h², so each sum counts triangles up to the same shape factor, which cancels.
// Dimensionless; a mesh made for this curvature gives about 1/0.69² ≈ 2 (the mesher's mean side
// is about 0.69 h) plus what its kept boundary vertices add; it grows as the cloth flattens
// under a fine mesh (h_target grows, h_t does not).
double refinement_excess(const Matrix2X& material, const Triangles& triangles,
                         const Eigen::VectorXd& curvature, const SizeFieldParams& params);

}  // namespace weft::sim::remesh
